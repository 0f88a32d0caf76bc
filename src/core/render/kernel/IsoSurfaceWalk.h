#pragma once
// The isosurface blend (BlendMode::Iso), host and device: each ray's crossings of the isovalues,
// composited front to back as surfaces.
//
// Exact where the field is a polynomial along the ray piece by piece (the sampler tells where a
// piece ends: the MFA model's knot-span cells, kernel/SplineRaySampler.h; the grid filters'
// cells between samples, gridPieceEnd in kernel/TrilinearKernel.h): the ray is walked
// piece by piece, not by samples, so nothing depends on the step. A piece whose cell the
// empty-space flags mark (flags built for an isovalue band: no value the cell can take is an
// isovalue, EmptySpaceGrid.h) is passed over without an evaluation. In the others the
// restriction f(t) of the model, a polynomial of degree n = the sum of the axes' degrees, is
// sampled at the n + 1 Chebyshev-Lobatto points of the piece and turned into its Bernstein
// coefficients (rp.isoNodes, rp.isoBasis: IsoBasis.h). By the convex-hull
// property f - c has no root where every coefficient of (f - c) has one sign; elsewhere de
// Casteljau halving isolates each sign change in order along the ray (a piece has at most n
// crossings of a value), and each bracket is refined on the field itself (safeguarded regula
// falsi, Illinois variant) to the float precision of its values. A tangent touch without a sign
// change is not a crossing.
//
// Samplers without pieces (the nearest-sample filter, the analytic truth) are walked at the
// sample distance: a sign change of f - c between two consecutive samples is a crossing,
// refined the same way (as VTK's isosurface blend finds them, then solved rather than taken at
// the sample).
//
// A hit on isovalue i has colour rp.isoColor[i] (rgb) and opacity rp.isoColor[i][3], shaded
// with the field's gradient at the hit for shaded renders, coloured and weighted by the surface's
// curvature there with rp.curvatureTf (its exact Hessian for the MFA model). Depth: the first
// hit.
#include "core/render/kernel/RaySteps.h"
#include "core/render/kernel/ShadingKernel.h"

namespace mfadvr {

// Samplers that know the polynomial pieces of a ray:
//   int rayDegree() const
//   double pieceEnd(const double o[3], const double d[3], double t) const
template <class Sampler>
constexpr bool hasRayPieces() {
  return requires(const Sampler& s, const double* o, double t) {
    s.rayDegree();
    s.pieceEnd(o, o, t);
  };
}

// Most Bernstein coefficients of a piece: degree 21 (7 per axis) + 1.
inline constexpr int kMaxIsoCoefficients = 22;
// Hits composited per piece (more crossings of one piece are dropped).
inline constexpr int kMaxIsoHitsPerPiece = 16;

namespace iso {

// The field's value at ray distance t, one evaluation.
template <class Sampler>
MFADVR_HD MFADVR_INLINE float valueAt(Sampler& s, const RaySegment& ray, double t,
                                      RayCounters& counters) {
  double p[3];
  for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + t * ray.d[a];
  if constexpr (Sampler::kSkipsEmptySpace) {
    double tLeave;
    (void)s.emptyAt(p, tLeave);  // locates the point for stage()
  }
  s.stage(0, p);
  float v[Sampler::kBatch];
  s.evaluate(1, v);
  ++counters.samples;
  return v[0];
}

// A crossing of c in [ta, tb] (fa - c and fb - c of opposite signs, or one zero), refined on the
// field: safeguarded regula falsi with the Illinois halving, until the bracket is below `tol`
// or the value is exactly c.
template <class Sampler>
MFADVR_HD MFADVR_INLINE double refine(Sampler& s, const RaySegment& ray, float c, double ta,
                                      double tb, double fa, double fb, double tol,
                                      RayCounters& counters) {
  if (fa == 0.0) return ta;
  if (fb == 0.0) return tb;
  int side = 0;
  for (int i = 0; i < 40 && tb - ta > tol; ++i) {
    double t = (ta * fb - tb * fa) / (fb - fa);
    // Safeguard: stay well inside the bracket (else bisect).
    const double w = tb - ta;
    if (!(t > ta + 0.01 * w && t < tb - 0.01 * w)) t = ta + 0.5 * w;
    const double f = static_cast<double>(valueAt(s, ray, t, counters)) - c;
    if (f == 0.0) return t;
    if ((f < 0.0) == (fa < 0.0)) {
      ta = t;
      fa = f;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      tb = t;
      fb = f;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (ta + tb);
}

struct Hit {
  double t;
  int surface;
};

// Adds a hit, kept sorted by t (few per piece: insertion).
MFADVR_HD MFADVR_INLINE void addHit(Hit hits[], int& count, double t, int surface) {
  if (count == kMaxIsoHitsPerPiece) return;
  int i = count++;
  while (i > 0 && hits[i - 1].t > t) {
    hits[i] = hits[i - 1];
    --i;
  }
  hits[i] = {t, surface};
}

// Halvings of a piece at most: brackets 2^-16 of it long, which the field decides.
inline constexpr int kIsoDepth = 16;

// The brackets [s0, s1] of the parameter s in [0, 1] of the sign changes of the Bernstein
// polynomial b (degree n), left to right: halving by de Casteljau while more than one sign
// change of the coefficients is left or the ends do not differ in sign, to depth kIsoDepth
// (where the field then tells a crossing from a touch). Float coefficients: they only isolate,
// the roots are solved on the field; they keep a device thread's stack small.
template <class Found>
MFADVR_HD MFADVR_INLINE void isolateRoots(const double b[], int n, Found&& found) {
  struct Part {
    float c[kMaxIsoCoefficients];
    float s0, s1;
    int depth;
  };
  // Depth-first, left half first: at most one pending right half per level.
  Part stack[kIsoDepth + 2];
  int top = 0;
  for (int i = 0; i <= n; ++i) stack[0].c[i] = static_cast<float>(b[i]);
  stack[0].s0 = 0.0f;
  stack[0].s1 = 1.0f;
  stack[0].depth = 0;
  top = 1;
  while (top > 0) {
    Part part = stack[--top];
    int changes = 0;
    for (int i = 0; i < n; ++i)
      if ((part.c[i] < 0.0f) != (part.c[i + 1] < 0.0f)) ++changes;
    if (changes == 0) continue;
    const bool endsDiffer = (part.c[0] < 0.0f) != (part.c[n] < 0.0f);
    if (changes == 1 && endsDiffer) {
      found(part.s0, part.s1);
      continue;
    }
    if (part.depth >= kIsoDepth) {
      found(part.s0, part.s1);  // the field decides: a crossing where its ends differ
      continue;
    }
    // de Casteljau at 1/2: left coefficients into `left`, right ones stay in part.c.
    Part left;
    left.s0 = part.s0;
    left.s1 = 0.5f * (part.s0 + part.s1);
    left.depth = part.depth + 1;
    left.c[0] = part.c[0];
    for (int r = 1; r <= n; ++r) {
      for (int i = 0; i <= n - r; ++i) part.c[i] = 0.5f * (part.c[i] + part.c[i + 1]);
      left.c[r] = part.c[0];
    }
    part.s0 = left.s1;
    part.depth = left.depth;
    if (top + 2 > kIsoDepth + 2) continue;
    stack[top++] = part;  // the right half waits
    stack[top++] = left;  // the left half first
  }
}

}  // namespace iso

// The isosurfaces along `ray` into out (RGBA over the background) and rp.depth.
template <bool Masked, bool Shade, class Sampler>
MFADVR_HD MFADVR_OUTLINE void isoSegment(const RayParams& rp, Sampler& sampler,
                                         const RaySegment& ray, float out[4],
                                         RayCounters& counters) {
  float red = 0.0f, green = 0.0f, blue = 0.0f, alpha = 0.0f;
  float depth = NAN;
  sampler.beginRay(ray);
  RayShading rayShading;
  if constexpr (Shade) {
    const float df[3] = {float(ray.d[0]), float(ray.d[1]), float(ray.d[2])};
    if (rp.shadeSamples) prepareRayShading(rp.shading, df, rayShading);
  }
  bool done = false;
  // Composites one hit (skipped outside a domain mask).
  const auto composite = [&](double t, int surface) {
    double p[3];
    for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + t * ray.d[a];
    if constexpr (Masked) {
      if (!sampler.inside(p)) return;
    }
    const float* colour = rp.isoColor[surface];
    float c[3] = {colour[0], colour[1], colour[2]};
    float opacity = colour[3];
    if constexpr (Shade) {
      if constexpr (Sampler::kSkipsEmptySpace) {
        double tLeave;
        (void)sampler.emptyAt(p, tLeave);
      }
      sampler.stage(0, p);
      float v[Sampler::kBatch];
      sampler.evaluate(1, v);
      ++counters.samples;
      float g[3];
      sampler.gradient(0, g);
      // The surface's colour and opacity by its curvature at the hit, then shading, then the
      // contours (CurvatureTransferView.h).
      float unshaded[3] = {c[0], c[1], c[2]}, contour = 0.0f;
      if (rp.curvatureTf.active()) {
        float h[6], factor = 1.0f;
        sampler.hessian(0, p, h);
        rp.curvatureTf.apply(g, h, ray.d, t, unshaded, factor, contour);
        opacity *= factor;
      }
      if (rp.shadeSamples) {
        shadeSample(rp.shading, rayShading, unshaded, g, c);
      } else {
        for (int a = 0; a < 3; ++a) c[a] = unshaded[a];
      }
      if (contour > 0.0f)
        for (int a = 0; a < 3; ++a) c[a] += contour * (rp.curvatureTf.contourColor[a] - c[a]);
    }
    if (!(opacity > 0.0f)) return;
    if (depth != depth) depth = static_cast<float>(t);
    compositeSample(red, green, blue, alpha, opacity, c);
    if (alpha >= rp.stopOpacity) {
      ++counters.terminated;
      done = true;
    }
  };
  const double length = ray.tExit - ray.tEnter;
  const double tol = 1e-7 * (length > 0.0 ? length : 1.0);

  if constexpr (hasRayPieces<Sampler>()) {
    const int n = sampler.rayDegree();
    // The degree's nodes and basis (IsoBasis.h: blocks for degrees 0, 1, 2, ... in turn).
    const double* nodes = rp.isoNodes + n * (n + 1) / 2;
    const double* basis = rp.isoBasis + n * (n + 1) * (2 * n + 1) / 6;
    double t = ray.tEnter;
    while (!done && t < ray.tExit) {
      double end = sampler.pieceEnd(ray.o, ray.d, t);
      if (!(end > t + tol)) end = t + tol;  // progress past a knot that rounding holds back
      if (end > ray.tExit) end = ray.tExit;
      if constexpr (Sampler::kSkipsEmptySpace) {
        const double mid = 0.5 * (t + end);
        double p[3], tLeave;
        for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + mid * ray.d[a];
        if (sampler.emptyAt(p, tLeave)) {
          // Past the empty block: to the end of the cell that holds its far face.
          if (tLeave > end) {
            const double farEnd = sampler.pieceEnd(ray.o, ray.d, tLeave);
            end = farEnd > tLeave ? farEnd : tLeave;
            if (end > ray.tExit) end = ray.tExit;
          }
          t = end;
          continue;
        }
      }
      // The piece's values at the Chebyshev-Lobatto points, then its Bernstein coefficients.
      double f[kMaxIsoCoefficients], b[kMaxIsoCoefficients];
      const double w = end - t;
      for (int j0 = 0; j0 <= n; j0 += Sampler::kBatch) {
        const int m = n + 1 - j0 < Sampler::kBatch ? n + 1 - j0 : Sampler::kBatch;
        for (int j = 0; j < m; ++j) {
          double p[3];
          const double tj = t + w * nodes[j0 + j];
          for (int a = 0; a < 3; ++a) p[a] = ray.o[a] + tj * ray.d[a];
          if constexpr (Sampler::kSkipsEmptySpace) {
            double tLeave;
            (void)sampler.emptyAt(p, tLeave);
          }
          sampler.stage(j, p);
        }
        float v[Sampler::kBatch];
        sampler.evaluate(m, v);
        for (int j = 0; j < m; ++j) f[j0 + j] = v[j];
        counters.samples += m;
      }
      iso::Hit hits[kMaxIsoHitsPerPiece];
      int hitCount = 0;
      for (int i = 0; i <= n; ++i) {
        double s = 0.0;
        for (int j = 0; j <= n; ++j) s += basis[i * (n + 1) + j] * f[j];
        b[i] = s;
      }
      for (int k = 0; k < rp.isoCount; ++k) {
        const double c = rp.isoValue[k];
        double shifted[kMaxIsoCoefficients];
        bool below = false, above = false;
        for (int i = 0; i <= n; ++i) {
          shifted[i] = b[i] - c;
          below |= shifted[i] < 0.0;
          above |= shifted[i] >= 0.0;
        }
        if (!(below && above)) continue;
        iso::isolateRoots(shifted, n, [&](double s0, double s1) {
          const double ta = t + s0 * w, tb = t + s1 * w;
          const double fa = static_cast<double>(iso::valueAt(sampler, ray, ta, counters)) - c;
          const double fb = static_cast<double>(iso::valueAt(sampler, ray, tb, counters)) - c;
          // The coefficients' sign change stands for the field's, up to their rounding: a
          // bracket whose ends agree in sign on the field is a touch.
          if ((fa < 0.0) == (fb < 0.0) && fa != 0.0 && fb != 0.0) return;
          iso::addHit(
              hits, hitCount,
              iso::refine(sampler, ray, static_cast<float>(c), ta, tb, fa, fb, tol, counters), k);
        });
      }
      for (int h = 0; h < hitCount && !done; ++h) composite(hits[h].t, hits[h].surface);
      t = end;
    }
  } else {
    // Step by step: sign changes between consecutive samples.
    const double dt = rp.sampleDistance;
    double tPrev = ray.tEnter;
    float fPrev = iso::valueAt(sampler, ray, tPrev, counters);
    for (double t = ray.tEnter; !done && t < ray.tExit;) {
      t = t + dt < ray.tExit ? t + dt : ray.tExit;
      const float fNow = iso::valueAt(sampler, ray, t, counters);
      iso::Hit hits[kMaxIsoHitsPerPiece];
      int hitCount = 0;
      for (int k = 0; k < rp.isoCount; ++k) {
        const double c = rp.isoValue[k];
        const double fa = static_cast<double>(fPrev) - c, fb = static_cast<double>(fNow) - c;
        if (!(fa == fa && fb == fb)) continue;
        if ((fa < 0.0) != (fb < 0.0))
          iso::addHit(
              hits, hitCount,
              iso::refine(sampler, ray, static_cast<float>(c), tPrev, t, fa, fb, tol, counters), k);
      }
      for (int h = 0; h < hitCount && !done; ++h) composite(hits[h].t, hits[h].surface);
      tPrev = t;
      fPrev = fNow;
    }
  }
  if (rp.depth) rp.depth[ray.pixel] = depth;
  overBackground(rp, red, green, blue, alpha, out);
}

}  // namespace mfadvr
