#pragma once
// Trilinear reconstruction of a regular grid and the gradient of its trilinear polynomial, over a
// plain view of a padded grid (host and device). TrilinearFilter (field/GridFilters.h) and the
// CUDA renderer's grid sampler both call these functions: one formula for the baseline on every
// device.
#include <cmath>
#include <cstdint>

#include "core/render/kernel/SampleBatch.h"
#include "core/util/HostDevice.h"

namespace mfadvr {

struct RaySegment;  // kernel/RaySteps.h

// Samples with one ghost layer (PaddedGrid.h): sample (i, j, k), i in [-1, n], at
// data[(i + 1) + sy (j + 1) + sz (k + 1)].
struct GridView {
  const float* data = nullptr;
  std::int64_t dims[3] = {0, 0, 0};
  std::int64_t sy = 0, sz = 0;
  double origin[3] = {0.0, 0.0, 0.0};
  double inverseSpacing[3] = {1.0, 1.0, 1.0};
};

// One axis of the grid lookup, shared by every grid filter (PaddedGrid.h) and the GPU: the
// continuous index of coordinate x on an axis of n samples, clamped to [0, n-1] (NaN -> 0;
// ternaries rather than fmin/fmax, which are library calls when NaN rules apply) ...
MFADVR_HD MFADVR_INLINE double gridIndex(double x, double origin, double inverseSpacing,
                                         std::int64_t n) {
  const double u = (x - origin) * inverseSpacing;
  const double hi = static_cast<double>(n - 1);
  return u > 0.0 ? (u < hi ? u : hi) : 0.0;
}
// ... and its cell i in [0, n-2] with the fraction t in [0, 1].
MFADVR_HD MFADVR_INLINE void gridCellOf(double u, std::int64_t n, std::int64_t& i, double& t) {
  i = static_cast<std::int64_t>(u);  // u >= 0, so truncation is floor
  if (i > n - 2) i = n - 2;
  t = u - static_cast<double>(i);
}

// The cell of physical point x: pointer to its first corner and the fractions t.
MFADVR_HD MFADVR_INLINE const float* gridCell(const GridView& g, const double x[3], double t[3]) {
  std::int64_t c[3];
  for (int a = 0; a < 3; ++a)
    gridCellOf(gridIndex(x[a], g.origin[a], g.inverseSpacing[a], g.dims[a]), g.dims[a], c[a], t[a]);
  return g.data + ((c[0] + 1) + g.sy * (c[1] + 1) + g.sz * (c[2] + 1));
}

// The isosurface walk's pieces on a grid (kernel/IsoSurfaceWalk.h): every grid filter is a
// polynomial inside each cell between samples, so a ray's piece ends where it crosses the
// nearest plane of whole continuous index beyond t on any axis (+inf for a ray parallel to
// every axis's planes). Outside [0, n - 1] the lookup clamps, so the extra planes there only
// split constant stretches.
MFADVR_HD MFADVR_INLINE double gridPieceEnd(const GridView& g, const double o[3], const double d[3],
                                            double t) {
  double end = static_cast<double>(INFINITY);
  for (int a = 0; a < 3; ++a) {
    const double ud = d[a] * g.inverseSpacing[a];
    if (ud == 0.0) continue;
    const double uo = (o[a] - g.origin[a]) * g.inverseSpacing[a];
    const double u = uo + t * ud;
    double plane = ud > 0.0 ? floor(u) + 1.0 : ceil(u) - 1.0;
    double ta = (plane - uo) / ud;
    if (!(ta > t)) ta = (plane + (ud > 0.0 ? 1.0 : -1.0) - uo) / ud;  // rounding held it back
    if (ta < end) end = ta;
  }
  return end;
}

MFADVR_HD MFADVR_INLINE float trilinearValue(const GridView& g, const double x[3]) {
  double t[3];
  const float* p = gridCell(g, x, t);
  const std::int64_t sy = g.sy, sz = g.sz;
  const double c00 = p[0] + t[0] * (p[1] - p[0]);
  const double c10 = p[sy] + t[0] * (p[sy + 1] - p[sy]);
  const double c01 = p[sz] + t[0] * (p[sz + 1] - p[sz]);
  const double c11 = p[sz + sy] + t[0] * (p[sz + sy + 1] - p[sz + sy]);
  const double c0 = c00 + t[1] * (c10 - c00), c1 = c01 + t[1] * (c11 - c01);
  return static_cast<float>(c0 + t[2] * (c1 - c0));
}

// The value; `gradient` receives the physical gradient of the cell's trilinear polynomial.
MFADVR_HD MFADVR_INLINE float trilinearValueGradient(const GridView& g, const double x[3],
                                                     float gradient[3]) {
  double t[3];
  const float* p = gridCell(g, x, t);
  const std::int64_t sy = g.sy, sz = g.sz;
  const double f000 = p[0], f100 = p[1], f010 = p[sy], f110 = p[sy + 1];
  const double f001 = p[sz], f101 = p[sz + 1], f011 = p[sz + sy], f111 = p[sz + sy + 1];
  // Interpolate along x, then y, then z, keeping the x derivative of each edge.
  const double c00 = f000 + t[0] * (f100 - f000), d00 = f100 - f000;
  const double c10 = f010 + t[0] * (f110 - f010), d10 = f110 - f010;
  const double c01 = f001 + t[0] * (f101 - f001), d01 = f101 - f001;
  const double c11 = f011 + t[0] * (f111 - f011), d11 = f111 - f011;
  const double c0 = c00 + t[1] * (c10 - c00), c1 = c01 + t[1] * (c11 - c01);
  const double dx0 = d00 + t[1] * (d10 - d00), dx1 = d01 + t[1] * (d11 - d01);
  const double dy0 = c10 - c00, dy1 = c11 - c01;
  gradient[0] = static_cast<float>((dx0 + t[2] * (dx1 - dx0)) * g.inverseSpacing[0]);
  gradient[1] = static_cast<float>((dy0 + t[2] * (dy1 - dy0)) * g.inverseSpacing[1]);
  gradient[2] = static_cast<float>((c1 - c0) * g.inverseSpacing[2]);
  return static_cast<float>(c0 + t[2] * (c1 - c0));
}

// The trilinear grid as a ray sampler (RayIntegrator.h): no mask, no skipping.
template <bool Shade>
class TrilinearRaySampler : public PointwiseBatch<TrilinearRaySampler<Shade>, kSampleBatch, Shade> {
 public:
  static constexpr bool kSkipsEmptySpace = false;
  MFADVR_HD explicit TrilinearRaySampler(const GridView& g) : g_(g) {}
  MFADVR_HD MFADVR_INLINE void beginRay(const RaySegment&) {}
  MFADVR_HD MFADVR_INLINE bool inside(const double*) const { return true; }
  MFADVR_HD MFADVR_INLINE bool emptyAt(const double*, double&) { return false; }
  MFADVR_HD MFADVR_INLINE float pointValue(const double p[3]) const {
    return trilinearValue(g_, p);
  }
  MFADVR_HD MFADVR_INLINE float pointValueGradient(const double p[3], float g[3]) const {
    return trilinearValueGradient(g_, p, g);
  }
  // A hundredth of a voxel: the differences of the gradient stay inside one cell but for a
  // hundredth of the samples, where the trilinear gradient jumps.
  MFADVR_HD MFADVR_INLINE double differenceStep(int axis) const {
    return 0.01 / g_.inverseSpacing[axis];
  }
  // Trilinear in each cell: a cubic along a ray (the exact isosurface walk).
  MFADVR_HD MFADVR_INLINE int rayDegree() const { return 3; }
  MFADVR_HD MFADVR_INLINE double pieceEnd(const double o[3], const double d[3], double t) const {
    return gridPieceEnd(g_, o, d, t);
  }

 private:
  GridView g_;
};

}  // namespace mfadvr
