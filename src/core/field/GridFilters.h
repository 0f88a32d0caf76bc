#pragma once
// Local reconstruction filters over a PaddedGrid, each with its analytic gradient (the
// derivative of the same piecewise polynomial that gives the value). The per-sample functions
// are forced inline so that the ray caster's loop schedules them with its own work.
//
//   NearestFilter     value of the nearest sample; a piecewise-constant function has no useful
//                     derivative, so its gradient is the central difference at that sample.
//   TrilinearFilter   8 samples; gradient of the trilinear polynomial of the cell (the formulas
//                     live in render/kernel/TrilinearKernel.h, shared with the GPU).
//   TricubicFilter    Lekien & Marsden (2005): the C1 tricubic of each cell matching value,
//                     first, second-mixed and third-mixed derivatives at its 8 corners, the
//                     derivatives taken by central differences of the samples.
//   CatmullRomFilter  tensor-product Catmull-Rom spline (4^3 samples). With central differences,
//                     Lekien-Marsden's tricubic is this same function; the tests check it.
//   BSplineFilter     prefiltered cubic B-spline: cubic B-spline coefficients solved so that the
//                     spline interpolates the samples (natural end conditions), then 4^3 weights.
#include <array>
#include <cmath>

#include "core/field/PaddedGrid.h"
#include "core/render/kernel/TrilinearKernel.h"
#include "core/spline/TensorBSpline.h"

namespace mfadvr {

class NearestFilter {
 public:
  static PaddedGrid prepare(const StructuredGrid& g) { return PaddedGrid(g); }
  explicit NearestFilter(const PaddedGrid& g) : g_(&g) {}
  [[gnu::always_inline]] float value(const Vec3d& x) const;
  [[gnu::always_inline]] ValueGradient valueGradient(const Vec3d& x) const;

 private:
  const PaddedGrid* g_;
};

// The formulas are shared with the GPU renderer (render/kernel/TrilinearKernel.h).
class TrilinearFilter {
 public:
  static PaddedGrid prepare(const StructuredGrid& g) { return PaddedGrid(g); }
  explicit TrilinearFilter(const PaddedGrid& g) : g_(g.view()) {}
  [[gnu::always_inline]] float value(const Vec3d& x) const {
    const double p[3] = {x[0], x[1], x[2]};
    return trilinearValue(g_, p);
  }
  [[gnu::always_inline]] ValueGradient valueGradient(const Vec3d& x) const {
    const double p[3] = {x[0], x[1], x[2]};
    float g[3];
    ValueGradient r;
    r.value = trilinearValueGradient(g_, p, g);
    r.gradient = Vec3f(g[0], g[1], g[2]);
    return r;
  }
  // The exact isosurface walk's pieces (kernel/IsoSurfaceWalk.h): a cubic along a ray per cell.
  int rayDegree() const { return 3; }
  double pieceEnd(const double o[3], const double d[3], double t) const {
    return gridPieceEnd(g_, o, d, t);
  }

 private:
  GridView g_;
};

// Shared 4x4x4 tensor kernel of the two cubic filters; Weights gives the four weights (and their
// derivatives) of samples i-1..i+2 for the fraction t in cell i.
template <class Weights>
class Cubic4Filter {
 public:
  explicit Cubic4Filter(const PaddedGrid& g) : g_(&g) {}
  [[gnu::always_inline]] float value(const Vec3d& x) const;
  [[gnu::always_inline]] ValueGradient valueGradient(const Vec3d& x) const;
  // Tricubic in each cell between samples: degree 9 along a ray (kernel/IsoSurfaceWalk.h).
  int rayDegree() const { return 9; }
  double pieceEnd(const double o[3], const double d[3], double t) const {
    return gridPieceEnd(g_->view(), o, d, t);
  }

 private:
  const PaddedGrid* g_;
};

struct CatmullRomWeights {
  static void weights(double t, double w[4]) {
    const double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
  }
  static void derivatives(double t, double d[4]) {
    const double t2 = t * t;
    d[0] = 0.5 * (-3.0 * t2 + 4.0 * t - 1.0);
    d[1] = 0.5 * (9.0 * t2 - 10.0 * t);
    d[2] = 0.5 * (-9.0 * t2 + 8.0 * t + 1.0);
    d[3] = 0.5 * (3.0 * t2 - 2.0 * t);
  }
};

struct CubicBSplineWeights {
  static void weights(double t, double w[4]) {
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    w[0] = s * s * s / 6.0;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    w[3] = t3 / 6.0;
  }
  static void derivatives(double t, double d[4]) {
    const double s = 1.0 - t, t2 = t * t;
    d[0] = -0.5 * s * s;
    d[1] = 1.5 * t2 - 2.0 * t;
    d[2] = -1.5 * t2 + t + 0.5;
    d[3] = 0.5 * t2;
  }
};

class CatmullRomFilter : public Cubic4Filter<CatmullRomWeights> {
 public:
  static PaddedGrid prepare(const StructuredGrid& g) { return PaddedGrid(g); }
  using Cubic4Filter::Cubic4Filter;
};

class BSplineFilter : public Cubic4Filter<CubicBSplineWeights> {
 public:
  // Solves for the interpolating cubic B-spline coefficients (a tridiagonal system per grid
  // line, axis by axis, in double).
  static PaddedGrid prepare(const StructuredGrid& g);
  using Cubic4Filter::Cubic4Filter;
};

class TricubicFilter {
 public:
  static PaddedGrid prepare(const StructuredGrid& g) { return PaddedGrid(g); }
  explicit TricubicFilter(const PaddedGrid& g) : g_(&g) {}
  float value(const Vec3d& x) { return evaluate(x, false).value; }
  ValueGradient valueGradient(const Vec3d& x) { return evaluate(x, true); }
  // One tricubic per cell: degree 9 along a ray (kernel/IsoSurfaceWalk.h).
  int rayDegree() const { return 9; }
  double pieceEnd(const double o[3], const double d[3], double t) const {
    return gridPieceEnd(g_->view(), o, d, t);
  }

 private:
  ValueGradient evaluate(const Vec3d& x, bool gradient);
  void loadCell(const std::int64_t c[3]);

  const PaddedGrid* g_;
  // Coefficients a[i + 4j + 16k] of sum a * tx^i ty^j tz^k for the cached cell.
  std::array<double, 64> a_{};
  std::int64_t cached_[3] = {-1, -1, -1};
};

// ---- inline implementations (the ray caster's hot loop inlines them) ----

inline float NearestFilter::value(const Vec3d& x) const {
  const Vec3d u = g_->continuousIndex(x);
  return g_->at(std::llround(u[0]), std::llround(u[1]), std::llround(u[2]));
}

inline ValueGradient NearestFilter::valueGradient(const Vec3d& x) const {
  const Vec3d u = g_->continuousIndex(x);
  const std::int64_t i = std::llround(u[0]), j = std::llround(u[1]), k = std::llround(u[2]);
  const Vec3d& s = g_->inverseSpacing();
  ValueGradient r;
  r.value = g_->at(i, j, k);
  r.gradient = Vec3f(0.5 * (g_->at(i + 1, j, k) - g_->at(i - 1, j, k)) * s[0],
                     0.5 * (g_->at(i, j + 1, k) - g_->at(i, j - 1, k)) * s[1],
                     0.5 * (g_->at(i, j, k + 1) - g_->at(i, j, k - 1)) * s[2]);
  return r;
}

template <class Weights>
inline float Cubic4Filter<Weights>::value(const Vec3d& x) const {
  std::int64_t c[3];
  double t[3], wx[4], wy[4], wz[4];
  g_->cell(g_->continuousIndex(x), c, t);
  Weights::weights(t[0], wx);
  Weights::weights(t[1], wy);
  Weights::weights(t[2], wz);
  const float* base = g_->pointer(c[0] - 1, c[1] - 1, c[2] - 1);
  const std::int64_t sy = g_->strideY(), sz = g_->strideZ();
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    double plane = 0.0;
    for (int j = 0; j < 4; ++j) {
      const float* p = base + k * sz + j * sy;
      plane += wy[j] * (wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3]);
    }
    sum += wz[k] * plane;
  }
  return static_cast<float>(sum);
}

template <class Weights>
inline ValueGradient Cubic4Filter<Weights>::valueGradient(const Vec3d& x) const {
  std::int64_t c[3];
  double t[3], wx[4], wy[4], wz[4], dx[4], dy[4], dz[4];
  g_->cell(g_->continuousIndex(x), c, t);
  Weights::weights(t[0], wx);
  Weights::weights(t[1], wy);
  Weights::weights(t[2], wz);
  Weights::derivatives(t[0], dx);
  Weights::derivatives(t[1], dy);
  Weights::derivatives(t[2], dz);
  const float* base = g_->pointer(c[0] - 1, c[1] - 1, c[2] - 1);
  const std::int64_t sy = g_->strideY(), sz = g_->strideZ();
  double v = 0.0, gx = 0.0, gy = 0.0, gz = 0.0;
  for (int k = 0; k < 4; ++k) {
    double pv = 0.0, px = 0.0, py = 0.0;
    for (int j = 0; j < 4; ++j) {
      const float* p = base + k * sz + j * sy;
      const double lv = wx[0] * p[0] + wx[1] * p[1] + wx[2] * p[2] + wx[3] * p[3];
      const double lx = dx[0] * p[0] + dx[1] * p[1] + dx[2] * p[2] + dx[3] * p[3];
      pv += wy[j] * lv;
      px += wy[j] * lx;
      py += dy[j] * lv;
    }
    v += wz[k] * pv;
    gx += wz[k] * px;
    gy += wz[k] * py;
    gz += dz[k] * pv;
  }
  const Vec3d& s = g_->inverseSpacing();
  ValueGradient r;
  r.value = static_cast<float>(v);
  r.gradient = Vec3f(gx * s[0], gy * s[1], gz * s[2]);
  return r;
}

}  // namespace mfadvr
