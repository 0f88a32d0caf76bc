#include "core/mask/MaskVoxelizer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {
namespace {

// Tolerance of the inside tests, in barycentric (dimensionless) units and in node units.
constexpr double kBarycentricTolerance = 1e-9;
constexpr double kNodeTolerance = 1e-9;

void checkBox(const DomainBox& box) {
  const Vec3d e = box.extent();
  if (!((e.array() > 0.0).all() && e.allFinite() && box.min.allFinite()))
    throw Error("domain mask: the box must have positive, finite extent on every axis");
}

void checkPoints(std::span<const Vec3d> points) {
  for (size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) {
      std::ostringstream m;
      m << "domain mask: point " << i << " has a NaN or infinite coordinate";
      throw Error(m.str());
    }
}

// Position in node units: node i of axis a sits at i.
Vec3d nodeCoordinates(const Vec3d& x, const DomainBox& box, const Vec3d& scale) {
  return (x - box.min).cwiseQuotient(box.extent()).cwiseProduct(scale);
}

void raise(std::uint8_t& node) {
  std::atomic_ref<std::uint8_t>(node).store(1, std::memory_order_relaxed);
}

// One pass of a 3-node max (dilation) or min (erosion) filter along `axis`, over the neighbours
// that exist (the grid's border truncates the window).
void filterAxis(const std::vector<std::uint8_t>& src, std::vector<std::uint8_t>& dst,
                const Index3& d, int axis, bool dilate) {
  const std::int64_t stride = axis == 0 ? 1 : axis == 1 ? d[0] : d[0] * d[1];
  const std::int64_t n = d[axis];
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, d[2]), [&](const auto& r) {
    for (std::int64_t k = r.begin(); k < r.end(); ++k)
      for (std::int64_t j = 0; j < d[1]; ++j)
        for (std::int64_t i = 0; i < d[0]; ++i) {
          const std::int64_t at = i + d[0] * (j + d[1] * k);
          const std::int64_t pos = axis == 0 ? i : axis == 1 ? j : k;
          std::uint8_t v = src[at];
          if (pos > 0) v = dilate ? std::max(v, src[at - stride]) : std::min(v, src[at - stride]);
          if (pos + 1 < n)
            v = dilate ? std::max(v, src[at + stride]) : std::min(v, src[at + stride]);
          dst[at] = v;
        }
  });
}

// Dilation or erosion by the 3x3x3 block: the block is a product of intervals, so three passes
// of the 1-D filter give it, borders included.
void morph(std::vector<std::uint8_t>& nodes, const Index3& d, bool dilate) {
  std::vector<std::uint8_t> tmp(nodes.size());
  filterAxis(nodes, tmp, d, 0, dilate);
  filterAxis(tmp, nodes, d, 1, dilate);
  filterAxis(nodes, tmp, d, 2, dilate);
  nodes.swap(tmp);
}

}  // namespace

DomainMask meshOccupancyMask(std::span<const Vec3d> points, std::span<const Tetrahedron> tets,
                             const DomainBox& box, Index3 dims) {
  DomainMask::validateDims(dims);
  checkBox(box);
  checkPoints(points);
  const auto n = static_cast<std::int64_t>(points.size());
  for (size_t t = 0; t < tets.size(); ++t)
    for (std::int64_t v : tets[t])
      if (v < 0 || v >= n) {
        std::ostringstream m;
        m << "domain mask: tetrahedron " << t << " refers to point " << v << " of " << n;
        throw Error(m.str());
      }

  const Vec3d scale(double(dims[0] - 1), double(dims[1] - 1), double(dims[2] - 1));
  std::vector<std::uint8_t> nodes(static_cast<size_t>(dims[0] * dims[1] * dims[2]), 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tets.size(), 256), [&](const auto& r) {
    for (size_t t = r.begin(); t < r.end(); ++t) {
      // Work in node units, where node (i,j,k) is at (i,j,k): barycentric coordinates are
      // invariant under the (affine) change of units.
      Vec3d v[4];
      for (int c = 0; c < 4; ++c) v[c] = nodeCoordinates(points[tets[t][c]], box, scale);
      Eigen::Matrix3d m;
      m.col(0) = v[1] - v[0];
      m.col(1) = v[2] - v[0];
      m.col(2) = v[3] - v[0];
      const double det = m.determinant();
      const double edges = m.col(0).norm() * m.col(1).norm() * m.col(2).norm();
      if (!(std::abs(det) > 1e-12 * edges)) continue;  // flat (or NaN): no volume
      const Eigen::Matrix3d inv = m.inverse();
      std::int64_t lo[3], hi[3];
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        const double mn = std::min({v[0][a], v[1][a], v[2][a], v[3][a]});
        const double mx = std::max({v[0][a], v[1][a], v[2][a], v[3][a]});
        const double l = std::max(std::ceil(mn - kNodeTolerance), 0.0);
        const double h = std::min(std::floor(mx + kNodeTolerance), scale[a]);
        if (l > h) empty = true;
        lo[a] = static_cast<std::int64_t>(l);
        hi[a] = static_cast<std::int64_t>(h);
      }
      if (empty) continue;
      for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
          for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
            const Vec3d b = inv * (Vec3d(double(i), double(j), double(k)) - v[0]);
            const double b0 = 1.0 - b[0] - b[1] - b[2];
            if (b[0] >= -kBarycentricTolerance && b[1] >= -kBarycentricTolerance &&
                b[2] >= -kBarycentricTolerance && b0 >= -kBarycentricTolerance)
              raise(nodes[static_cast<size_t>(i + dims[0] * (j + dims[1] * k))]);
          }
    }
  });
  return DomainMask(MaskKind::MeshOccupancy, dims, std::move(nodes));
}

DomainMask pointCoverageMask(std::span<const Vec3d> points, const DomainBox& box, Index3 dims) {
  DomainMask::validateDims(dims);
  checkBox(box);
  checkPoints(points);
  const Vec3d scale(double(dims[0] - 1), double(dims[1] - 1), double(dims[2] - 1));
  std::vector<std::uint8_t> nodes(static_cast<size_t>(dims[0] * dims[1] * dims[2]), 0);
  const std::int64_t sy = dims[0], sz = dims[0] * dims[1];
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 4096), [&](const auto& r) {
    for (size_t p = r.begin(); p < r.end(); ++p) {
      const Vec3d u = nodeCoordinates(points[p], box, scale);
      std::int64_t c[3];
      for (int a = 0; a < 3; ++a)
        c[a] = std::min(static_cast<std::int64_t>(std::clamp(u[a], 0.0, scale[a])), dims[a] - 2);
      std::uint8_t* n = nodes.data() + c[0] + sy * c[1] + sz * c[2];
      for (std::int64_t dz : {std::int64_t(0), sz})
        for (std::int64_t dy : {std::int64_t(0), sy})
          for (std::int64_t dx : {std::int64_t(0), std::int64_t(1)}) raise(n[dx + dy + dz]);
    }
  });
  morph(nodes, dims, true);
  morph(nodes, dims, false);
  return DomainMask(MaskKind::PointCoverage, dims, std::move(nodes));
}

Index3 defaultMaskDims(const DomainBox& box, int longestAxisNodes) {
  checkBox(box);
  const Vec3d e = box.extent();
  auto dimsFor = [&](std::int64_t longest) {
    const double spacing = e.maxCoeff() / static_cast<double>(longest - 1);
    Index3 dims{};
    for (int a = 0; a < 3; ++a) {
      const double nodes = std::min(std::round(e[a] / spacing) + 1.0, double(longest));
      dims[a] = std::max<std::int64_t>(static_cast<std::int64_t>(nodes), 2);
    }
    return dims;
  };
  std::int64_t longest = std::clamp<std::int64_t>(longestAxisNodes, 2, kMaxMaskNodesPerAxis);
  Index3 dims = dimsFor(longest);
  while (dims[0] * dims[1] * dims[2] > kMaxMaskNodes) dims = dimsFor(--longest);
  return dims;
}

int defaultCoverageResolution(std::int64_t pointCount) {
  const double root = std::cbrt(static_cast<double>(std::max<std::int64_t>(pointCount, 0)));
  return static_cast<int>(std::clamp(std::lround(root), 8L, 256L));
}

}  // namespace mfadvr
