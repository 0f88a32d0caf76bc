#include "core/mask/DomainBoundary.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

constexpr int kLeafTriangles = 4;

// The direction of the lines that point queries count crossings along: no simple ratio between
// its components, so that it runs along no face or edge of a mesh built on axis-aligned or
// diagonal planes.
const double kQueryDirection[3] = {0.5772156649015329, 0.6180339887498949, 0.5329070518200948};

}  // namespace

DomainBoundary::DomainBoundary(std::vector<Vec3f> vertices, std::vector<BoundaryTriangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  if (static_cast<std::int64_t>(vertices_.size()) > kMaxBoundaryElements ||
      static_cast<std::int64_t>(triangles_.size()) > kMaxBoundaryElements)
    throw Error("domain boundary: more than 2^26 vertices or triangles");
  for (size_t i = 0; i < vertices_.size(); ++i)
    if (!vertices_[i].allFinite())
      throw Error("domain boundary: vertex " + std::to_string(i) + " is NaN or infinite");
  for (size_t i = 0; i < triangles_.size(); ++i)
    for (std::uint32_t v : triangles_[i])
      if (v >= vertices_.size())
        throw Error("domain boundary: triangle " + std::to_string(i) + " names vertex " +
                    std::to_string(v) + " of " + std::to_string(vertices_.size()));
  if (triangles_.empty()) return;

  // The hierarchy: median splits of the centroids along the longest axis of their box.
  const auto count = static_cast<std::int64_t>(triangles_.size());
  std::vector<Vec3d> centroid(static_cast<size_t>(count));
  Vec3d lo = Vec3d::Constant(INFINITY), hi = Vec3d::Constant(-INFINITY);
  for (std::int64_t i = 0; i < count; ++i) {
    Vec3d c = Vec3d::Zero();
    for (std::uint32_t v : triangles_[static_cast<size_t>(i)]) {
      const Vec3d p = vertices_[v].cast<double>();
      c += p;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    centroid[static_cast<size_t>(i)] = c / 3.0;
  }
  scale_ = std::max((hi - lo).norm(), 1e-300);
  std::vector<std::int32_t> order(static_cast<size_t>(count));
  std::iota(order.begin(), order.end(), 0);
  struct Task {
    std::int32_t node, begin, end;
  };
  std::vector<Task> tasks{{0, 0, static_cast<std::int32_t>(count)}};
  nodes_.emplace_back();
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    Vec3d nlo = Vec3d::Constant(INFINITY), nhi = Vec3d::Constant(-INFINITY);
    Vec3d clo = nlo, chi = nhi;
    for (std::int32_t i = task.begin; i < task.end; ++i) {
      const std::int32_t t = order[static_cast<size_t>(i)];
      for (std::uint32_t v : triangles_[static_cast<size_t>(t)]) {
        nlo = nlo.cwiseMin(vertices_[v].cast<double>());
        nhi = nhi.cwiseMax(vertices_[v].cast<double>());
      }
      clo = clo.cwiseMin(centroid[static_cast<size_t>(t)]);
      chi = chi.cwiseMax(centroid[static_cast<size_t>(t)]);
    }
    BoundaryNode& node = nodes_[static_cast<size_t>(task.node)];
    for (int a = 0; a < 3; ++a) {
      node.lo[a] = nlo[a];
      node.hi[a] = nhi[a];
    }
    if (task.end - task.begin <= kLeafTriangles) {
      node.first = task.begin;
      node.count = task.end - task.begin;
      continue;
    }
    int axis = 0;
    const Vec3d extent = chi - clo;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    const std::int32_t mid = task.begin + (task.end - task.begin) / 2;
    std::nth_element(order.begin() + task.begin, order.begin() + mid, order.begin() + task.end,
                     [&](std::int32_t x, std::int32_t y) {
                       const double cx = centroid[static_cast<size_t>(x)][axis];
                       const double cy = centroid[static_cast<size_t>(y)][axis];
                       return cx < cy || (cx == cy && x < y);
                     });
    const auto children = static_cast<std::int32_t>(nodes_.size());
    node.first = children;
    node.count = 0;
    nodes_.emplace_back();  // invalidates `node`
    nodes_.emplace_back();
    tasks.push_back({children + 1, mid, task.end});
    tasks.push_back({children, task.begin, mid});
  }
  leafTriangles_.resize(static_cast<size_t>(9 * count));
  for (std::int64_t i = 0; i < count; ++i) {
    const BoundaryTriangle& t = triangles_[static_cast<size_t>(order[static_cast<size_t>(i)])];
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a)
        leafTriangles_[static_cast<size_t>(9 * i + 3 * c + a)] = vertices_[t[c]][a];
  }
}

BoundaryView DomainBoundary::view() const {
  BoundaryView v;
  if (triangles_.empty()) return v;
  v.nodes = nodes_.data();
  v.triangles = leafTriangles_.data();
  v.nodeCount = static_cast<std::int32_t>(nodes_.size());
  v.triangleCount = static_cast<std::int32_t>(leafTriangles_.size() / 9);
  v.scale = scale_;
  return v;
}

bool DomainBoundary::contains(const Vec3d& x) const {
  if (triangles_.empty()) return true;
  const BoundaryView v = view();
  std::vector<BoundaryCrossing> c;
  const double o[3] = {x[0], x[1], x[2]};
  forEachCrossing(v, o, kQueryDirection, [&](double t, int step) {
    c.push_back({t, step});
    return true;
  });
  const int n = mergeCrossings(c.data(), static_cast<int>(c.size()), v.scale);
  std::vector<double> intervals(2 * static_cast<size_t>(n) + 2);
  const int stretches = intervalsOfCrossings(c.data(), n, intervals.data(), n + 1);
  return inIntervals(intervals.data(), stretches, 0.0);
}

DomainBoundary boundaryOfTetrahedra(std::span<const Vec3d> points,
                                    std::span<const Tetrahedron> tets) {
  const auto pointCount = static_cast<std::int64_t>(points.size());
  // One index per position: points sorted by their coordinates, equal ones share the first's.
  std::vector<std::int64_t> byPosition(points.size());
  std::iota(byPosition.begin(), byPosition.end(), 0);
  auto less = [&](std::int64_t a, std::int64_t b) {
    const Vec3d& p = points[static_cast<size_t>(a)];
    const Vec3d& q = points[static_cast<size_t>(b)];
    if (p[0] != q[0]) return p[0] < q[0];
    if (p[1] != q[1]) return p[1] < q[1];
    if (p[2] != q[2]) return p[2] < q[2];
    return a < b;
  };
  std::sort(byPosition.begin(), byPosition.end(), less);
  std::vector<std::int64_t> canonical(points.size());
  for (size_t i = 0; i < byPosition.size(); ++i) {
    const std::int64_t p = byPosition[i];
    canonical[static_cast<size_t>(p)] =
        i > 0 && points[static_cast<size_t>(byPosition[i - 1])] == points[static_cast<size_t>(p)]
            ? canonical[static_cast<size_t>(byPosition[i - 1])]
            : p;
  }

  struct Face {
    std::array<std::int64_t, 3> key;    // sorted canonical indices
    std::array<std::int64_t, 3> order;  // outward order
  };
  std::vector<Face> faces;
  faces.reserve(4 * tets.size());
  for (size_t t = 0; t < tets.size(); ++t) {
    std::array<std::int64_t, 4> v{};
    for (int i = 0; i < 4; ++i) {
      const std::int64_t id = tets[t][static_cast<size_t>(i)];
      if (id < 0 || id >= pointCount) {
        std::ostringstream m;
        m << "tetrahedron " << t << " names point " << id << " of " << pointCount;
        throw Error(m.str());
      }
      v[static_cast<size_t>(i)] = canonical[static_cast<size_t>(id)];
    }
    auto at = [&](int i) -> const Vec3d& { return points[static_cast<size_t>(v[i])]; };
    const double volume = (at(1) - at(0)).cross(at(2) - at(0)).dot(at(3) - at(0));
    if (volume == 0.0 || !std::isfinite(volume)) continue;
    for (int opposite = 0; opposite < 4; ++opposite) {
      std::array<std::int64_t, 3> f{};
      int k = 0;
      for (int i = 0; i < 4; ++i)
        if (i != opposite) f[static_cast<size_t>(k++)] = v[static_cast<size_t>(i)];
      const Vec3d& a = points[static_cast<size_t>(f[0])];
      const Vec3d n =
          (points[static_cast<size_t>(f[1])] - a).cross(points[static_cast<size_t>(f[2])] - a);
      if (n.dot(at(opposite) - a) > 0.0) std::swap(f[1], f[2]);
      std::array<std::int64_t, 3> key = f;
      std::sort(key.begin(), key.end());
      faces.push_back({key, f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });

  std::vector<std::int64_t> newIndex(points.size(), -1);
  std::vector<Vec3f> vertices;
  std::vector<BoundaryTriangle> triangles;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) {
      BoundaryTriangle tri{};
      for (int c = 0; c < 3; ++c) {
        std::int64_t& ni = newIndex[static_cast<size_t>(faces[i].order[static_cast<size_t>(c)])];
        if (ni < 0) {
          if (static_cast<std::int64_t>(vertices.size()) >= kMaxBoundaryElements)
            throw Error("the mesh boundary has more than 2^26 vertices");
          ni = static_cast<std::int64_t>(vertices.size());
          vertices.push_back(
              points[static_cast<size_t>(faces[i].order[static_cast<size_t>(c)])].cast<float>());
        }
        tri[static_cast<size_t>(c)] = static_cast<std::uint32_t>(ni);
      }
      triangles.push_back(tri);
    }
    i = j;
  }
  return DomainBoundary(std::move(vertices), std::move(triangles));
}

}  // namespace mfadvr
