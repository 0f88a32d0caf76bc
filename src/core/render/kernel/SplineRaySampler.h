#pragma once
// The MFA model as a ray sampler (RayIntegrator.h), host and device, for a compile-time degree P
// (0: per-axis degrees at run time).
//
// A sample costs the span lookup, Horner's rule for the basis, the gather of its cell's
// (p+1)^3 control points into a local block and the contraction over that block
// (SplineKernel.h). With SIMD rows (host, one degree) samples are evaluated in batches
// (SampleBatch.h), every sample gathers its block (kGatherEverySample) and a shaded render
// computes value and gradient together, for degrees 1..3 with one SIMD lane per sample
// (SplineLaneKernel.h). Where rows are plain arrays (device, mixed degrees)
// samples go one at a time, consecutive samples in one knot-span cell reuse the block, and the
// gradient, asked for only when the sample is visible, reuses the value's z contraction.
//
// Exact empty-space skipping (Skip): `empty` flags, per knot-span cell, that no value the spline
// can take in the cell is visible (EmptySpaceGrid.h: a cell's values lie within the range of
// its control points and of its Bezier coefficients, widened by the rounding bounds). A
// sample in such a cell is not evaluated, and the ray jumps to where it leaves the largest
// aligned empty block around it (of 1, 2, 4, 8, ... cells per axis), walking on through the
// empty blocks beyond without locating a sample: crossing empty space costs one located sample
// per stretch of empty blocks and a few flag reads per block, not work per cell.
#include <cstdint>

#include "core/mask/BoundaryView.h"
#include "core/mask/MaskView.h"
#include "core/render/kernel/BoundaryTileView.h"
#include "core/render/kernel/ExtremeLevels.h"
#include "core/render/kernel/RaySteps.h"
#include "core/render/kernel/SampleBatch.h"
#include "core/spline/SplineKernel.h"
#include "core/spline/SplineLaneKernel.h"

namespace mfadvr {

// One coarser level of the empty-space flags (EmptySpaceFlags::pyramid): its block counts per
// axis and where its flags start.
struct EmptyLevelView {
  int count[3] = {0, 0, 0};
  std::int64_t offset = 0;
};

// Levels above the cells: 2^16 cells per axis and more are covered by blocks of 2^16 cells.
inline constexpr int kMaxEmptyLevels = 16;

// The model's placement and the optional skipping flags, shared by every ray.
struct ModelView {
  SplineView spline;
  double boxMin[3];
  double inverseExtent[3];  // physical -> parameter: u = (x - boxMin) * inverseExtent
  MaskView mask;
  // The mesh's exact boundary (null nodes: none). Where it is given, rays sample only their
  // stretches inside it (SplineRaySampler::beginRay): the host's gathered a tile of rays at a
  // time (BoundaryRaster.h), the device's queried ray by ray; the mask serves rays that cross it
  // more often than kMaxBoundaryCrossings.
  BoundaryView boundary;
  // Per knot-span cell, x fastest over (count - degree) cells per axis: 0 when the cell is
  // visible under the current transfer function, else 1 + the level of the largest block of the
  // pyramid around it that is all empty (1: the cell alone), so that a ray crosses a large
  // empty region in one step, found with one read. Null: no skipping information.
  const std::uint8_t* empty = nullptr;
  // The flags' pyramid: level l = 1..emptyLevels has one flag per block of 2^l x 2^l x 2^l cells
  // (aligned at cell 0, clipped at the far faces; x fastest over emptyLevel[l - 1].count blocks,
  // from emptyPyramid + emptyLevel[l - 1].offset), non-zero when every cell of the block is
  // empty. The rays read the levels from `empty`; the depth bounds (DepthBounds.h) project
  // the pyramid's blocks.
  const std::uint8_t* emptyPyramid = nullptr;
  int emptyLevels = 0;
  EmptyLevelView emptyLevel[kMaxEmptyLevels];
  // Maximum and minimum intensity skipping (ExtremeBounds.h); null: none. Per cell (indexed as
  // `empty`) the byte of an upper and of a lower bound of its values: the index of a level of
  // extremeUpperLevels / extremeLowerLevels (kExtremeLevels ascending floats each). Their
  // pyramids: level l = 1..extremeLevels has the greatest upper and the least lower byte per
  // block of 2^l cells per axis, from extremeUpperPyramid / extremeLowerPyramid +
  // extremeLevel[l - 1].offset.
  const std::uint8_t* extremeUpper = nullptr;
  const std::uint8_t* extremeLower = nullptr;
  const std::uint8_t* extremeUpperPyramid = nullptr;
  const std::uint8_t* extremeLowerPyramid = nullptr;
  const float* extremeUpperLevels = nullptr;
  const float* extremeLowerLevels = nullptr;
  int extremeLevels = 0;
  EmptyLevelView extremeLevel[kMaxEmptyLevels];
};

// Shade: evaluate() also computes the basis derivatives (one Horner pass gives both), which
// gradient() reuses.
template <int P, bool Skip, bool Shade>
class SplineRaySampler {
 public:
  static constexpr bool kSkipsEmptySpace = Skip;
  // Blocks an empty-space jump walks through at most (emptyAlong): 8, 16 and 64 measured alike
  // (docs/benchmarks.md, "Walking on through empty blocks"); a bound keeps a device thread's
  // loop short.
  static constexpr int kWalk = 16;
  // How far (in parameter units) the faces a ray leaves an empty block by are pulled in.
  static constexpr double kEmptyInset = 1e-10;
  static constexpr int W = SplineDegree<P>::kWidth;
  // With SIMD rows a gather is (p+1)^2 vector loads; doing it for every sample lets the
  // compiler keep the block in registers, and measured faster than reusing it, even at 16
  // samples per cell (docs/benchmarks.md). The scalar and device paths keep the cached block
  // and take one sample at a time.
  static constexpr bool kGatherEverySample = Lanes<P + 1, (P > 0)>::kVector;
  static constexpr int kBatch = kGatherEverySample ? kSampleBatch : 1;
  // Without skipping, a batch's points are located together as vectors (locateLanesOnAxis);
  // with skipping, emptyAt() has located every point before it is staged, and stage() keeps
  // that (measured faster than locating the batch again).
  static constexpr bool kLocateLanes = kGatherEverySample && !Skip;
  // Shaded renders of degrees 1..3 on an AVX2 host evaluate a batch with one SIMD lane per
  // sample (SplineLaneKernel.h), the same values and gradients bit for bit: 1.13x faster frames
  // shaded; unshaded it measured no faster than the per-point kernel, which stays there
  // (docs/benchmarks.md).
  static constexpr bool kLaneKernel =
      Shade && kGatherEverySample && SplineLaneKernel<P>::kAvailable;
  static constexpr bool kLaneLocations = kLocateLanes || kLaneKernel;
  // Eight rays at once, one lane per ray (RayPacketIntegrator.h): evaluatePacket() locates
  // and evaluates one sample of each, through the lane kernel for value (and gradient).
  static constexpr bool kRayPackets = kLocateLanes && SplineLaneKernel<P>::kAvailable;

  MFADVR_HD explicit SplineRaySampler(const ModelView& m) : m_(m) {
    for (int a = 0; a < 3; ++a) {
      p_[a] = SplineDegree<P>::of(m.spline.axis[a].degree);
      cells_[a] = m.spline.axis[a].count - p_[a];
      gradientScale_[a] = static_cast<float>(m.inverseExtent[a]);
    }
  }

  // A ray in parameter space, for emptyAlong(): its origin, direction and the direction's
  // inverse (0 where the direction is 0) per axis.
  struct RayMarch {
    double uo[3] = {0.0, 0.0, 0.0}, ud[3] = {0.0, 0.0, 0.0}, invUd[3] = {0.0, 0.0, 0.0};
    // Ray distances closer than this are a tie for the empty-space walk: 8 times the most the
    // faces' inset (kEmptyInset) moves where the ray leaves a block, over all axes.
    double tieMargin = 0.0;
  };

  MFADVR_HD MFADVR_INLINE void beginMarch(const double o[3], const double d[3], RayMarch& r) const {
    for (int a = 0; a < 3; ++a) {
      r.uo[a] = (o[a] - m_.boxMin[a]) * m_.inverseExtent[a];
      r.ud[a] = d[a] * m_.inverseExtent[a];
      r.invUd[a] = r.ud[a] != 0.0 ? 1.0 / r.ud[a] : 0.0;
    }
    r.tieMargin = 0.0;
    for (int a = 0; a < 3; ++a)
      r.tieMargin += 8.0 * kEmptyInset * (r.invUd[a] < 0.0 ? -r.invUd[a] : r.invUd[a]);
  }

  // The stretches inside the mesh's boundary of the rays of a tile, gathered beforehand
  // (BoundaryRaster.h): rays of its pixels read them instead of querying the boundary.
  MFADVR_HD MFADVR_INLINE void useBoundaryTile(const BoundaryTileView& tile) {
    boundaryTile_ = tile;
  }

  MFADVR_HD MFADVR_INLINE void beginRay(const RaySegment& ray) {
    const double* o = ray.o;
    const double* d = ray.d;
    if constexpr (Skip) beginMarch(o, d, march_);
    // The ray's stretches inside the mesh's boundary: the tile's, or gathered at its first
    // inside() test (only masked renders test; the unmasked kernels leave the traversal out).
    if (m_.boundary.nodes) {
      for (int a = 0; a < 3; ++a) {
        rayOrigin_[a] = o[a];
        rayDirection_[a] = d[a];
      }
      rayInverseLength2_ = rayInverseLength2(d);
      stretches_ = boundaryIntervals_;
      boundaryStretches_ = boundaryTile_.find(ray.pixel, stretches_);
      if (boundaryStretches_ == kStretchesNotGathered) stretches_ = boundaryIntervals_;
    }
  }

  // Whether inside() answers for the ray of the last beginRay() only (a mesh's exact boundary):
  // then rays cannot be marched interleaved through one sampler (InterleavedMarch.h).
  MFADVR_HD MFADVR_INLINE bool insideFollowsTheRay() const { return m_.boundary.nodes != nullptr; }

  // The isosurface walk's pieces (kernel/IsoSurfaceWalk.h): inside a knot-span cell the spline
  // along a ray is a polynomial of the degrees' sum.
  MFADVR_HD MFADVR_INLINE int rayDegree() const { return p_[0] + p_[1] + p_[2]; }

  // Where the ray o + t d leaves the knot-span cell it is in just after t: the nearest knot
  // plane beyond t on any axis (+inf for a ray parallel to every axis's knots).
  MFADVR_HD MFADVR_INLINE double pieceEnd(const double o[3], const double d[3], double t) const {
    double end = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const double ud = d[a] * m_.inverseExtent[a];
      if (ud == 0.0) continue;
      const double uo = (o[a] - m_.boxMin[a]) * m_.inverseExtent[a];
      const KnotAxisView& axis = m_.spline.axis[a];
      const double* U = axis.knots;
      int j = findSpan<P>(axis, uo + t * ud);
      double ta;
      if (ud > 0.0) {
        ++j;  // knots[j]: the span's far end; on past knots that rounding puts behind t
        while (j < axis.count && !((U[j] - uo) / ud > t)) ++j;
        ta = (U[j] - uo) / ud;
      } else {
        while (j > p_[a] && !((U[j] - uo) / ud > t)) --j;
        ta = (U[j] - uo) / ud;
      }
      if (ta < end) end = ta;
    }
    return end;
  }

  // Inside the mesh's exact boundary (the stretches of the current ray), or, without one or on
  // a ray of more crossings than kMaxBoundaryCrossings, inside the domain mask.
  MFADVR_HD MFADVR_INLINE bool inside(const double p[3]) {
    if (boundaryStretches_ == kStretchesNotGathered)
      boundaryStretches_ =
          boundaryIntervals(m_.boundary, rayOrigin_, rayDirection_, boundaryIntervals_);
    return insideOnRay(stretches_, boundaryStretches_, rayOrigin_, rayDirection_,
                       rayInverseLength2_, p);
  }

  // Where the ray r leaves, on axis a, the aligned block of 2^level cells per axis whose first
  // cell on that axis is b (clipped at the grid's far face): the knot plane of the face it leaves
  // by, pulled in by kEmptyInset; +inf when the ray is parallel to the axis's faces.
  MFADVR_HD MFADVR_INLINE double blockExit(const RayMarch& r, int a, int b, int level) const {
    const double* U = m_.spline.axis[a].knots;
    if (r.ud[a] > 0.0) {
      const int end = b + (1 << level);
      return (U[p_[a] + (end < cells_[a] ? end : cells_[a])] - kEmptyInset - r.uo[a]) * r.invUd[a];
    }
    if (r.ud[a] < 0.0) return (U[p_[a] + b] + kEmptyInset - r.uo[a]) * r.invUd[a];
    return static_cast<double>(INFINITY);
  }

  MFADVR_HD MFADVR_INLINE bool emptyAt(const double p[3], double& tLeave) {
    located_ = true;
    return emptyAlong(march_, p, tLeave, loc_);
  }

  using PointLocation = AxisLocation[3];  // a point's span and local coordinate per axis

  // emptyAt() for the ray r (beginMarch), with no state of the sampler's own: several rays can
  // be marched at once (InterleavedMarch.h). loc: p's location.
  MFADVR_HD MFADVR_INLINE bool emptyAlong(const RayMarch& r, const double p[3], double& tLeave,
                                          AxisLocation loc[3]) const {
    double u[3];
    toParameter(p, u);
    locatePoint<P>(m_.spline, u, loc);
    const std::int64_t cell =
        (loc[0].span - p_[0]) +
        cells_[0] * ((loc[1].span - p_[1]) + std::int64_t(cells_[1]) * (loc[2].span - p_[2]));
    const int flag = m_.empty[cell];
    if (!flag) return false;
    // The region to leave: the largest aligned block of the pyramid around the cell that is all
    // empty (its level kept in the cell's flag), else the cell. From there the ray walks on
    // through the faces it leaves by, block to block as a DDA (no sample located on the way): the
    // neighbouring block of the same level is all empty when the flag of its first cell gives
    // a largest empty block of that level or more, and the walk goes on in that largest block.
    // It stops at a block that is not all empty, at the grid's faces, after kWalk blocks, or
    // where the ray leaves through two faces at nearly the same distance (which one comes first
    // is then not certain). The faces are knots, those the ray leaves by pulled in by far more
    // than the rounding of a sample's parameter, so every sample before tLeave is found in an
    // empty block the walk went through.
    int level = flag - 1;
    int b[3] = {0, 0, 0};  // the region's first cell on each axis
    double tn[3];          // where the ray leaves the region on each axis
    const auto leave = [&](int a) { return blockExit(r, a, b[a], level); };
    for (int a = 0; a < 3; ++a) {
      b[a] = ((loc[a].span - p_[a]) >> level) << level;
      tn[a] = leave(a);
    }
    // The flags' strides per axis, and the index of the region's first cell.
    const std::int64_t stride[3] = {1, cells_[0], std::int64_t(cells_[0]) * cells_[1]};
    const auto firstCell = [&] { return b[0] + stride[1] * b[1] + stride[2] * b[2]; };
    std::int64_t first = firstCell();
    for (int walk = 0;; ++walk) {
      // The nearest face and the next one, compared as values rather than looked up by axis.
      const double t0 = tn[0], t1 = tn[1], t2 = tn[2];
      const bool yFirst = t1 < t0;
      const double near01 = yFirst ? t1 : t0, far01 = yFirst ? t0 : t1;
      const bool zFirst = t2 < near01;
      const int a = zFirst ? 2 : (yFirst ? 1 : 0);
      tLeave = zFirst ? t2 : near01;
      if (walk == kWalk) break;
      const double next = zFirst ? near01 : (t2 < far01 ? t2 : far01);
      if (!(next - tLeave > r.tieMargin)) break;
      const int step = r.ud[a] > 0.0 ? (1 << level) : -(1 << level);
      const int na = b[a] + step;  // the neighbouring block's first cell on axis a
      if (na < 0 || na >= cells_[a]) break;
      const std::int64_t neighbour = first + step * stride[a];
      const int f = m_.empty[neighbour];
      if (f - 1 < level) break;
      b[a] = na;
      if (f - 1 == level) {
        first = neighbour;
        tn[a] = leave(a);
      } else {
        level = f - 1;
        for (int e = 0; e < 3; ++e) {
          b[e] = (b[e] >> level) << level;
          tn[e] = leave(e);
        }
        first = firstCell();
      }
    }
    return true;
  }

  // Maximum (maximum = true) or minimum intensity skipping: true when no value the spline can
  // take in the cell of p is above the level of upper byte `bound` (below that of lower byte
  // `bound`; upperByteAtMost / lowerByteAtLeast of the ray's running extreme); tLeave: where the
  // ray leaves the largest aligned block of cells around p where that holds (faces pulled in as
  // emptyAlong's). Locates p for stage() either way.
  MFADVR_HD MFADVR_INLINE bool boundedAt(const double p[3], bool maximum, int bound,
                                         double& tLeave) {
    located_ = true;
    double u[3];
    toParameter(p, u);
    locatePoint<P>(m_.spline, u, loc_);
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = loc_[a].span - p_[a];
    const std::uint8_t* cells = maximum ? m_.extremeUpper : m_.extremeLower;
    const std::uint8_t* pyramid = maximum ? m_.extremeUpperPyramid : m_.extremeLowerPyramid;
    const auto passes = [&](int byte) { return maximum ? byte <= bound : byte >= bound; };
    if (!passes(cells[c[0] + cells_[0] * (c[1] + std::int64_t(cells_[1]) * c[2])])) return false;
    int level = 0;  // the largest block (of 2^level cells per axis) around the cell that passes
    while (level < m_.extremeLevels) {
      const EmptyLevelView& L = m_.extremeLevel[level];
      const int s = level + 1;
      const std::int64_t block =
          (c[0] >> s) + L.count[0] * ((c[1] >> s) + std::int64_t(L.count[1]) * (c[2] >> s));
      if (!passes(pyramid[L.offset + block])) break;
      ++level;
    }
    tLeave = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const double t = blockExit(march_, a, (c[a] >> level) << level, level);
      if (t < tLeave) tLeave = t;
    }
    return true;
  }

  // The levels of the extreme bounds' bytes (boundedAt).
  MFADVR_HD MFADVR_INLINE const float* upperLevels() const { return m_.extremeUpperLevels; }
  MFADVR_HD MFADVR_INLINE const float* lowerLevels() const { return m_.extremeLowerLevels; }

  MFADVR_HD MFADVR_INLINE void stage(int lane, const double p[3]) {
    if constexpr (kLocateLanes) {
      // Located for the whole batch in evaluate().
#if defined(MFADVR_KERNEL_VECTOR_LANES)
      points_[lane] = LaneDouble4{p[0], p[1], p[2], 0.0};
#endif
      return;
    }
    AxisLocation* loc = locs_[lane];
    if (Skip && located_) {
      loc = loc_;
    } else {
      double u[3];
      toParameter(p, u);
      locatePoint<P>(m_.spline, u, loc);
    }
    if constexpr (kLaneLocations) {
      for (int a = 0; a < 3; ++a) {
        span_[a][lane] = loc[a].span;
        tau_[a][lane] = loc[a].tau;
      }
    } else if (loc != locs_[lane]) {
      for (int a = 0; a < 3; ++a) locs_[lane][a] = loc[a];
    }
    located_ = false;
  }

  // v has room for kBatch values.
  MFADVR_HD MFADVR_INLINE void evaluate(int n, float v[]) {
#if defined(MFADVR_KERNEL_VECTOR_LANES)
    if constexpr (kLocateLanes) {
      static_assert(kBatch == 8, "lanes are located as 8-lane vectors");
      // The lanes' spans and local coordinates, axis by axis, as vectors.
      LaneDouble8 x[3];
      transposePoints(points_, x);
      for (int a = 0; a < 3; ++a)
        locateLanesOnAxis<P>(m_.spline.axis[a], m_.boxMin[a], m_.inverseExtent[a], x[a], n,
                             span_[a], tau_[a]);
    }
#endif
#if defined(MFADVR_SPLINE_LANE_KERNEL)
    if constexpr (kLaneKernel) {
      static_assert(kBatch == 8, "the lane kernel takes 8 samples");
      if (evaluateLanes<P, kOrder>(m_.spline, span_, tau_, n, v, grads_)) return;
    }
#endif
    evaluateEach(n, v);
  }

#if defined(MFADVR_SPLINE_LANE_KERNEL)
  // A packet's eight points, as coordinate vectors (physical, x[axis][lane]): their values, and
  // for shading their gradients (gradientPacket()). Every lane is evaluated.
  MFADVR_INLINE LaneVector8 evaluatePacket(const LaneDouble8 x[3]) {
    static_assert(kRayPackets && kBatch == 8, "a sampler made for ray packets");
    for (int a = 0; a < 3; ++a)
      locateLanesOnAxis<P>(m_.spline.axis[a], m_.boxMin[a], m_.inverseExtent[a], x[a], 8, span_[a],
                           tau_[a]);
    float v[8];
    if (!evaluateLanes<P, kOrder>(m_.spline, span_, tau_, 8, v, grads_)) evaluateEach(8, v);
    LaneVector8 values;
    __builtin_memcpy(&values, v, sizeof values);
    return values;
  }

  // Packets of masked renders: the lanes' rays (`live`: -1 in the lanes with steps to take)
  // with their stretches inside the mesh's boundary, from the tile (useBoundaryTile). False
  // where a live lane's stretches were not gathered: those rays go one at a time.
  MFADVR_INLINE bool beginPacket(const RaySegment rays[8], LaneInt8 live) {
    static_assert(kRayPackets, "a sampler made for ray packets");
    for (int l = 0; l < 8; ++l) {
      int count = -1;  // the mask decides
      if (live[l] && m_.boundary.nodes) {
        count = boundaryTile_.find(rays[l].pixel, laneStretches_[l]);
        if (count == kStretchesNotGathered) return false;
      }
      laneStretchCount_[l] = count;
      laneCursor_[l] = 0;
      maskLanes_[l] = live[l] && count < 0 ? -1 : 0;
      for (int a = 0; a < 3; ++a) {
        laneOrigin_[a][l] = rays[l].o[a];
        laneDirection_[a][l] = rays[l].d[a];
      }
      laneInverseLength2_[l] = rayInverseLength2(rays[l].d);
      // The stretch the lane is in or before; none (an empty one) where it has none or the
      // mask decides.
      stretchStart_[l] = count > 0 ? laneStretches_[l][0] : INFINITY;
      stretchEnd_[l] = count > 0 ? laneStretches_[l][1] : -INFINITY;
    }
    return true;
  }

  // Where each live lane's ray may first be inside: the start of its first stretch (-inf where
  // the mask decides, +inf where nothing of the ray is inside).
  MFADVR_INLINE LaneDouble8 firstInsidePacket() const {
    return __builtin_convertvector(maskLanes_, LaneMask8) ? -INFINITY : stretchStart_;
  }

  // Which of the `live` lanes' points x[axis][lane] are inside: inside() of each lane's ray.
  // The points of a lane advance along its ray, so each lane keeps the stretch it is in or
  // before (its stretches are ordered and disjoint: the first that does not end before the
  // point is the only one that can hold it). Lanes past their ray's last stretch are cleared
  // from `live`: nothing of their rays is left inside.
  MFADVR_INLINE LaneInt8 insidePacket(const LaneDouble8 x[3], LaneInt8& live) {
    const LaneDouble8 t =
        rayParameterOf<LaneDouble8>(laneOrigin_, laneDirection_, laneInverseLength2_, x);
    const LaneInt8 beyond = live & ~maskLanes_ & __builtin_convertvector(t > stretchEnd_, LaneInt8);
    if (anyLane(beyond)) [[unlikely]] {
      for (int l = 0; l < 8; ++l) {
        if (!beyond[l]) continue;
        int& c = laneCursor_[l];
        const int count = laneStretchCount_[l];
        const double* stretches = laneStretches_[l];
        while (c < count && t[l] > stretches[2 * c + 1]) ++c;
        if (c == count) {
          live[l] = 0;
        } else {
          stretchStart_[l] = stretches[2 * c];
          stretchEnd_[l] = stretches[2 * c + 1];
        }
      }
    }
    LaneInt8 in =
        live & __builtin_convertvector((t >= stretchStart_) & (t <= stretchEnd_), LaneInt8);
    const LaneInt8 masked = live & maskLanes_;
    if (anyLane(masked)) [[unlikely]] {
      for (int l = 0; l < 8; ++l) {
        if (!masked[l]) continue;
        const double p[3] = {x[0][l], x[1][l], x[2][l]};
        double u[3];
        toParameter(p, u);
        in[l] = insideMask(m_.mask, u) ? -1 : 0;
      }
    }
    return in;
  }

  // Physical gradients at the last packet's eight points, g[axis] over the lanes: each lane is
  // what gradient() gives it.
  MFADVR_INLINE void gradientPacket(LaneVector8 g[3]) const {
    static_assert(Shade, "gradients need a sampler made for shading");
    for (int a = 0; a < 3; ++a) {
      __builtin_memcpy(&g[a], grads_[a], sizeof g[a]);
      g[a] *= gradientScale_[a];
    }
  }
#endif

  // Physical gradient at a lane's point (one lane: from its value's basis and z contraction).
  MFADVR_HD MFADVR_INLINE void gradient(int lane, float g[3]) const {
    static_assert(Shade, "gradients need a sampler made for shading");
    if constexpr (kGatherEverySample) {
      for (int a = 0; a < 3; ++a) g[a] = grads_[a][lane];
    } else {
      contractPartials<P, kOrder>(block_, basis_, Tz_, g);
    }
    for (int a = 0; a < 3; ++a) g[a] *= gradientScale_[a];
  }

  // Physical Hessian (xx, xy, xz, yy, yz, zz) at the lane's point p: exact, from the second
  // derivatives of the basis (evaluated again at p: only curvature renders ask for it).
  MFADVR_HD MFADVR_INLINE void hessian(int, const double p[3], float h[6]) const {
    double u[3];
    toParameter(p, u);
    float out[10];
    splineValueGradientHessian<P>(m_.spline, u, out);
    const float* s = gradientScale_;
    h[0] = out[4] * s[0] * s[0];
    h[1] = out[5] * s[0] * s[1];
    h[2] = out[6] * s[0] * s[2];
    h[3] = out[7] * s[1] * s[1];
    h[4] = out[8] * s[1] * s[2];
    h[5] = out[9] * s[2] * s[2];
  }

 private:
  // Lanes 0..n-1 one point at a time, each located (locs_, or span_ / tau_).
  MFADVR_HD MFADVR_INLINE void evaluateEach(int n, float v[]) {
    for (int i = 0; i < n; ++i) {
      const AxisLocation* loc = locs_[i];
      AxisLocation lane[3];
      if constexpr (kLaneLocations) {
        for (int a = 0; a < 3; ++a) lane[a] = {span_[a][i], tau_[a][i]};
        loc = lane;
      }
      if constexpr (kGatherEverySample) {
        // The block stays in registers. A shaded render takes the gradient here too: measured
        // faster than keeping each lane's block for the visible lanes' gradients later, also
        // where most samples are transparent (docs/benchmarks.md).
        ControlBlock<P> block;
        PointBasis<P, kOrder> basis;
        Row<P> Tz[W];
        gatherBlock<P>(m_.spline, loc, block);
        pointBasis<P, kOrder>(m_.spline, loc, basis);
        v[i] = contractValue<P, kOrder>(block, basis, Tz);
        if constexpr (Shade) {
          float g[3];
          contractPartials<P, kOrder>(block, basis, Tz, g);
          for (int a = 0; a < 3; ++a) grads_[a][i] = g[a];
        }
      } else {
        // One lane: the block is kept while the ray stays in the cell; value first, the
        // gradient only when asked for (a visible sample).
        if (loc[0].span != cached_[0] || loc[1].span != cached_[1] || loc[2].span != cached_[2]) {
          gatherBlock<P>(m_.spline, loc, block_);
          for (int a = 0; a < 3; ++a) cached_[a] = loc[a].span;
        }
        pointBasis<P, kOrder>(m_.spline, loc, basis_);
        v[i] = contractValue<P, kOrder>(block_, basis_, Tz_);
      }
    }
  }

  // Whether p, a point of the ray o + t d, is inside: in the ray's `count` stretches inside the
  // mesh's boundary, or where they do not decide (count -1: no boundary, or more crossings than
  // kMaxBoundaryCrossings) in the domain mask.
  MFADVR_HD MFADVR_INLINE bool insideOnRay(const double* stretches, int count, const double o[3],
                                           const double d[3], double inverseLength2,
                                           const double p[3]) const {
    if (count >= 0)
      return inIntervals(stretches, count, rayParameterOf<double>(o, d, inverseLength2, p));
    double u[3];
    toParameter(p, u);
    return insideMask(m_.mask, u);
  }

  MFADVR_HD MFADVR_INLINE void toParameter(const double p[3], double u[3]) const {
    for (int a = 0; a < 3; ++a) u[a] = (p[a] - m_.boxMin[a]) * m_.inverseExtent[a];
  }

  const ModelView& m_;
  int p_[3];
  int cells_[3];
  float gradientScale_[3];  // parametric -> physical derivative: 1 / box extent
  int cached_[3] = {-1, -1, -1};
  bool located_ = false;
  AxisLocation loc_[3];
  RayMarch march_;
  // The current ray's stretches inside the boundary (-1: no boundary, or more stretches than the
  // limit: the mask decides; kStretchesNotGathered: not gathered yet) at stretches_ (the tile's
  // or boundaryIntervals_), and the ray, to turn a sample's point into its distance.
  int boundaryStretches_ = -1;
  double boundaryIntervals_[2 * kMaxBoundaryIntervals];
  const double* stretches_ = nullptr;
  BoundaryTileView boundaryTile_;
  double rayOrigin_[3], rayDirection_[3], rayInverseLength2_ = 0.0;
#if defined(MFADVR_SPLINE_LANE_KERNEL)
  // The same for each lane of a packet (beginPacket), with the stretch each lane is in or
  // before (laneCursor_: its index) and the lanes where the mask decides.
  int laneStretchCount_[8], laneCursor_[8];
  const double* laneStretches_[8];
  LaneDouble8 laneOrigin_[3], laneDirection_[3], laneInverseLength2_, stretchStart_, stretchEnd_;
  LaneInt8 maskLanes_;
#endif
  static constexpr int kOrder = Shade ? 1 : 0;
  AxisLocation locs_[kBatch][3];  // each lane's location, unless kLaneLocations
  // kLocateLanes: each lane's point; kLaneLocations: its spans and local coordinates, axis by
  // axis.
#if defined(MFADVR_KERNEL_VECTOR_LANES)
  LaneDouble4 points_[kBatch] = {};
#endif
  int span_[3][kBatch] = {};
  float tau_[3][kBatch] = {};
  float grads_[3][kBatch];       // SIMD path: each lane's parametric gradient
  ControlBlock<P> block_;        // one-lane path: the current cell's block, and the
  PointBasis<P, kOrder> basis_;  // last sample's basis and z contraction
  Row<P> Tz_[W];
};

}  // namespace mfadvr
