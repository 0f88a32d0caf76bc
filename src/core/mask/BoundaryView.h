#pragma once
// A mesh's exact boundary as a plain view: its boundary triangles, oriented outward, in the
// leaves of a bounding-volume hierarchy (DomainBoundary.h builds and owns both). What is inside
// is decided along lines: a line's crossings of the triangles, each an entry (the line goes
// against the triangle's outward normal) or an exit, counted from far outside, give the stretches
// of the line inside the mesh (winding number above 0).
//
// The crossings are found with the watertight ray-triangle test of Woop, Benthin and Wald,
// "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013: in the ray's sheared frame the three
// edge functions of a triangle are computed from the vertices alone (each edge's in one order for
// both of its triangles: boundaryEdgeFunction), so that a line through an edge or a vertex shared
// by several triangles is never missed by all of them. It may be found by
// more than one of them instead; those crossings lie at the same distance and in the same
// direction, and are merged into one (mergeCrossings). A line through a silhouette edge touches
// the surface: one entry and one exit at the same distance, which cancel.
//
// Plain arrays and no allocation: the device's ray caster queries it once per ray
// (SplineRaySampler::inside), Model::inside once per point; the host's ray caster gathers a
// tile's rays at once with the same test (crossesTriangle, BoundaryRaster.h) and queries only
// the rays a tile leaves out.
#include <cstdint>

#include "core/util/HostDevice.h"

namespace mfadvr {

// A node of the hierarchy: its box, and either its two children (count 0: at first and
// first + 1) or its triangles (count > 0: triangles first .. first + count - 1).
struct BoundaryNode {
  double lo[3], hi[3];
  std::int32_t first = 0, count = 0;
};

struct BoundaryView {
  const BoundaryNode* nodes = nullptr;  // null: no boundary
  const double* triangles = nullptr;    // 9 per triangle: a, b, c with (b - a) x (c - a) outward
  std::int32_t nodeCount = 0, triangleCount = 0;
  // The box diagonal: the scale of the distance below which two crossings are one.
  double scale = 1.0;
};

// Depth of the traversal stack: the builder keeps the tree's depth below it.
inline constexpr int kBoundaryStackDepth = 64;

// A crossing of a line o + t d: its distance t and +1 for an entry, -1 for an exit.
struct BoundaryCrossing {
  double t;
  int step;
};

// The edge function p x q = px qy - py qx of two projected vertices. The pair is taken in a
// fixed order (and the sign restored), so that the two triangles sharing an edge compute the same
// expression on the same operands and get exactly opposite values: a compiler may fuse one of the
// products into a multiply-add (GCC does by default), which rounds p x q and q x p differently:
// for a line through the edge, where both are zero in exact arithmetic, the two triangles would
// get rounding errors of the same sign and could both reject it.
MFADVR_HD MFADVR_INLINE double boundaryEdgeFunction(double px, double py, double qx, double qy) {
  const bool swap = qx < px || (qx == px && qy < py);
  const double ax = swap ? qx : px, ay = swap ? qy : py, bx = swap ? px : qx, by = swap ? py : qy;
  const double e = ax * by - ay * bx;
  return swap ? -e : e;
}

// A line o + t d set up for the watertight test: its origin and direction, and the shear that
// maps it to the z axis (kz the axis of the largest |d|, kx and ky the others in an order that
// keeps the winding of the triangles). valid is false for a zero direction, which crosses
// nothing.
struct BoundaryLine {
  double o[3], d[3];
  int kx = 0, ky = 1, kz = 2;
  double sx = 0.0, sy = 0.0, sz = 0.0;
  bool valid = false;
};

MFADVR_HD MFADVR_INLINE BoundaryLine boundaryLine(const double o[3], const double d[3]) {
  BoundaryLine l;
  for (int a = 0; a < 3; ++a) {
    l.o[a] = o[a];
    l.d[a] = d[a];
  }
  int kz = 0;
  for (int a = 1; a < 3; ++a)
    if ((d[a] < 0 ? -d[a] : d[a]) > (d[kz] < 0 ? -d[kz] : d[kz])) kz = a;
  int kx = kz + 1 == 3 ? 0 : kz + 1;
  int ky = kx + 1 == 3 ? 0 : kx + 1;
  if (d[kz] < 0.0) {
    const int s = kx;
    kx = ky;
    ky = s;
  }
  if (d[kz] == 0.0) return l;  // no direction
  l.kx = kx;
  l.ky = ky;
  l.kz = kz;
  l.sx = d[kx] / d[kz];
  l.sy = d[ky] / d[kz];
  l.sz = 1.0 / d[kz];
  l.valid = true;
  return l;
}

// Whether the line crosses the triangle tri (9 values: a, b, c with (b - a) x (c - a) outward);
// if so, its distance t and step +1 for an entry, -1 for an exit. A line in the triangle's plane
// crosses nothing.
MFADVR_HD MFADVR_INLINE bool crossesTriangle(const BoundaryLine& l, const double* tri, double& t,
                                             int& step) {
  const double* o = l.o;
  double ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0, cx = 0, cy = 0, cz = 0;
  {
    const double A[3] = {tri[0] - o[0], tri[1] - o[1], tri[2] - o[2]};
    const double B[3] = {tri[3] - o[0], tri[4] - o[1], tri[5] - o[2]};
    const double C[3] = {tri[6] - o[0], tri[7] - o[1], tri[8] - o[2]};
    ax = A[l.kx] - l.sx * A[l.kz];
    ay = A[l.ky] - l.sy * A[l.kz];
    bx = B[l.kx] - l.sx * B[l.kz];
    by = B[l.ky] - l.sy * B[l.kz];
    cx = C[l.kx] - l.sx * C[l.kz];
    cy = C[l.ky] - l.sy * C[l.kz];
    az = l.sz * A[l.kz];
    bz = l.sz * B[l.kz];
    cz = l.sz * C[l.kz];
  }
  const double U = boundaryEdgeFunction(cx, cy, bx, by);
  const double V = boundaryEdgeFunction(ax, ay, cx, cy);
  const double W = boundaryEdgeFunction(bx, by, ax, ay);
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
  const double det = U + V + W;
  if (det == 0.0) return false;  // the line lies in the triangle's plane: no crossing
  // Entry where d runs against the outward normal (b - a) x (c - a).
  const double* d = l.d;
  const double e1[3] = {tri[3] - tri[0], tri[4] - tri[1], tri[5] - tri[2]};
  const double e2[3] = {tri[6] - tri[0], tri[7] - tri[1], tri[8] - tri[2]};
  const double dn = (e1[1] * e2[2] - e1[2] * e2[1]) * d[0] +
                    (e1[2] * e2[0] - e1[0] * e2[2]) * d[1] + (e1[0] * e2[1] - e1[1] * e2[0]) * d[2];
  if (dn == 0.0) return false;
  t = (U * az + V * bz + W * cz) / det;
  step = dn < 0.0 ? 1 : -1;
  return true;
}

// Calls hit(t, step) for every crossing of the whole line o + t d (t over all reals) with the
// boundary; returns false if it stopped early because hit returned false.
template <class Hit>
MFADVR_HD MFADVR_INLINE bool forEachCrossing(const BoundaryView& v, const double o[3],
                                             const double d[3], Hit&& hit) {
  const BoundaryLine line = boundaryLine(o, d);
  if (!line.valid) return true;
  double inv[3];
  for (int a = 0; a < 3; ++a) inv[a] = d[a] != 0.0 ? 1.0 / d[a] : 0.0;

  std::int32_t stack[kBoundaryStackDepth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BoundaryNode& n = v.nodes[stack[--top]];
    // Whether the line meets the node's box (slabs; a line parallel to an axis only where its
    // coordinate lies within the slab).
    double tmin = -INFINITY, tmax = INFINITY;
    bool meets = true;
    for (int a = 0; a < 3 && meets; ++a) {
      if (d[a] == 0.0) {
        meets = o[a] >= n.lo[a] && o[a] <= n.hi[a];
        continue;
      }
      double t0 = (n.lo[a] - o[a]) * inv[a], t1 = (n.hi[a] - o[a]) * inv[a];
      if (t0 > t1) {
        const double s = t0;
        t0 = t1;
        t1 = s;
      }
      // Widened by a relative hair, so that rounding cannot lose a line along a box face.
      const double pad = 1e-12 * ((t0 < 0 ? -t0 : t0) + (t1 < 0 ? -t1 : t1)) + 1e-300;
      t0 -= pad;
      t1 += pad;
      if (t0 > tmin) tmin = t0;
      if (t1 < tmax) tmax = t1;
      meets = tmin <= tmax;
    }
    if (!meets) continue;
    if (n.count == 0) {
      if (top + 2 > kBoundaryStackDepth) return false;  // the builder prevents this
      stack[top++] = n.first + 1;
      stack[top++] = n.first;
      continue;
    }
    for (std::int32_t i = n.first; i < n.first + n.count; ++i) {
      double t = 0.0;
      int step = 0;
      if (crossesTriangle(line, v.triangles + 9 * static_cast<std::int64_t>(i), t, step) &&
          !hit(t, step))
        return false;
    }
  }
  return true;
}

// Sorts the n crossings c by distance and merges each group of them within 1e-9 of the scale
// of one another into one crossing: a line through an edge or a vertex shared by several
// triangles is found on each of them, in the same direction (one crossing), or in both
// directions at a silhouette, where the line only touches the surface (no crossing), as it
// does where two faces coincide (a seam of duplicated points). Returns the new count.
MFADVR_HD MFADVR_INLINE int mergeCrossings(BoundaryCrossing* c, int n, double scale) {
  for (int i = 1; i < n; ++i) {  // insertion sort: a line crosses a boundary a few times
    const BoundaryCrossing x = c[i];
    int j = i - 1;
    while (j >= 0 && c[j].t > x.t) {
      c[j + 1] = c[j];
      --j;
    }
    c[j + 1] = x;
  }
  const double eps = 1e-9 * scale;
  int m = 0;
  for (int i = 0; i < n;) {
    bool entry = false, exit = false;
    const double t = c[i].t;
    int j = i;
    for (; j < n && c[j].t - c[j == i ? i : j - 1].t <= eps; ++j) {
      entry = entry || c[j].step > 0;
      exit = exit || c[j].step < 0;
    }
    if (entry != exit) c[m++] = {t, entry ? 1 : -1};
    i = j;
  }
  return m;
}

// Most stretches inside the boundary a ray of the renderer keeps, and most crossings it gathers
// to find them; a ray with more is tested against the voxel mask instead.
inline constexpr int kMaxBoundaryIntervals = 16;
inline constexpr int kMaxBoundaryCrossings = 96;

// The stretches [t_in, t_out] inside the boundary, ascending, from the n merged crossings c of a
// line (2 values per stretch into intervals); returns their count, or -1 when there are more
// than maxIntervals. A stretch whose end was lost to rounding runs to +infinity.
MFADVR_HD MFADVR_INLINE int intervalsOfCrossings(const BoundaryCrossing* c, int n,
                                                 double* intervals, int maxIntervals) {
  int count = 0, winding = 0;
  for (int i = 0; i < n; ++i) {
    const int before = winding;
    winding += c[i].step;
    if (winding < 0) winding = 0;  // a crossing lost to rounding: start again from outside
    if (before == 0 && winding > 0) {
      if (count == maxIntervals) return -1;
      intervals[2 * count] = c[i].t;
      intervals[2 * count + 1] = INFINITY;
    } else if (before > 0 && winding == 0) {
      intervals[2 * count + 1] = c[i].t;
      ++count;
    }
  }
  if (winding > 0) ++count;
  return count;
}

// The stretches of the line o + t d inside the boundary (intervalsOfCrossings); -1 when the line
// has more crossings or stretches than the limits above.
MFADVR_HD MFADVR_INLINE int boundaryIntervals(const BoundaryView& v, const double o[3],
                                              const double d[3],
                                              double intervals[2 * kMaxBoundaryIntervals]) {
  BoundaryCrossing c[kMaxBoundaryCrossings];
  int n = 0;
  const bool all = forEachCrossing(v, o, d, [&](double t, int step) {
    if (n == kMaxBoundaryCrossings) return false;
    c[n++] = {t, step};
    return true;
  });
  if (!all) return -1;
  n = mergeCrossings(c, n, v.scale);
  return intervalsOfCrossings(c, n, intervals, kMaxBoundaryIntervals);
}

// 1 / |d|^2 (0 for a ray without direction): turns a point of the ray o + t d into its t.
MFADVR_HD MFADVR_INLINE double rayInverseLength2(const double d[3]) {
  double dd = 0.0;
  for (int a = 0; a < 3; ++a) dd += d[a] * d[a];
  return dd > 0.0 ? 1.0 / dd : 0.0;
}

// The t of p, a point of the ray o + t d: ((p - o) . d) / |d|^2, where its stretches inside are
// looked up; for one ray (D = double) and for the lanes of a ray packet (a vector of doubles),
// operation for operation alike, so that a lane finds what its ray alone finds.
template <class D>
MFADVR_HD MFADVR_INLINE D rayParameterOf(const D o[3], const D d[3], D inverseLength2,
                                         const D p[3]) {
  D t = {};
  for (int a = 0; a < 3; ++a) t += (p[a] - o[a]) * d[a];
  return t * inverseLength2;
}

// Whether distance t lies in one of the count stretches.
MFADVR_HD MFADVR_INLINE bool inIntervals(const double* intervals, int count, double t) {
  for (int i = 0; i < count; ++i)
    if (t >= intervals[2 * i] && t <= intervals[2 * i + 1]) return true;
  return false;
}

}  // namespace mfadvr
