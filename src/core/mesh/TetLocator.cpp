#include "core/mesh/TetLocator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "core/util/Error.h"

namespace mfadvr {

namespace {

// Barycentric coordinates down to -kSlack count as inside: points on a shared face, or a
// rounding error off it, are found in one of its two tetrahedra.
constexpr double kSlack = 1e-9;

// About this many bins per tetrahedron, shaped like the mesh's box: with cells of graded size a
// bin holds a few of the large ones or many of the small ones.
constexpr double kBinsPerTet = 0.5;

}  // namespace

TetLocator::TetLocator(const ScatteredData& mesh) {
  if (!mesh.hasCells())
    throw Error((mesh.source.empty() ? std::string("the input") : mesh.source) +
                " has no cells: the mesh's own field needs a mesh with tetrahedra (a point "
                "cloud has none)");
  mesh.validate();
  if (mesh.tets.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error(mesh.source + ": more tetrahedra than the mesh locator indexes (2^32)");
  boxMin_ = mesh.boxMin();
  boxMax_ = mesh.boxMax();

  std::vector<std::array<Vec3d, 2>> bounds;
  tets_.reserve(mesh.tets.size());
  bounds.reserve(mesh.tets.size());
  for (const Tetrahedron& t : mesh.tets) {
    if (mesh.volume6(t) == 0.0) continue;
    const auto point = [&](int k) -> const Vec3d& {
      return mesh.points[static_cast<size_t>(t[static_cast<size_t>(k)])];
    };
    const auto value = [&](int k) { return mesh.values[static_cast<size_t>(t[size_t(k)])]; };
    Eigen::Matrix3d edges;
    for (int k = 1; k < 4; ++k) edges.col(k - 1) = point(k) - point(0);
    Piece p;
    p.origin = point(0);
    p.inverse = edges.inverse();
    if (!p.inverse.allFinite()) continue;  // flat to rounding
    const Vec3d rise(value(1) - value(0), value(2) - value(0), value(3) - value(0));
    // value = value0 + rise . (inverse (x - origin)), so the gradient is inverse^T rise.
    p.gradient = p.inverse.transpose() * rise;
    p.value0 = value(0);
    Vec3d lo = point(0), hi = point(0);
    for (int k = 1; k < 4; ++k) {
      lo = lo.cwiseMin(point(k));
      hi = hi.cwiseMax(point(k));
    }
    tets_.push_back(p);
    bounds.push_back({lo, hi});
  }
  if (tets_.empty()) throw Error(mesh.source + ": every tetrahedron of the mesh is flat");

  // Bins of equal shape over the box, about kBinsPerTet per tetrahedron in all.
  const Vec3d extent = (boxMax_ - boxMin_).cwiseMax(1e-300);
  const double cell = std::cbrt(extent.prod() / std::max(1.0, kBinsPerTet * double(tets_.size())));
  for (int a = 0; a < 3; ++a) {
    bins_[size_t(a)] = std::clamp<std::int64_t>(std::int64_t(std::ceil(extent[a] / cell)), 1, 1024);
    binScale_[a] = double(bins_[size_t(a)]) / extent[a];
  }
  const auto binOf = [&](const Vec3d& x, int a) { return binIndex(x, a); };
  const std::int64_t binTotal = bins_[0] * bins_[1] * bins_[2];
  // Two passes over the tetrahedra's bin ranges: count, then fill (compressed rows).
  auto forEachBin = [&](size_t t, auto&& fn) {
    const auto& [lo, hi] = bounds[t];
    for (std::int64_t k = binOf(lo, 2); k <= binOf(hi, 2); ++k)
      for (std::int64_t j = binOf(lo, 1); j <= binOf(hi, 1); ++j)
        for (std::int64_t i = binOf(lo, 0); i <= binOf(hi, 0); ++i)
          fn((k * bins_[1] + j) * bins_[0] + i);
  };
  binStart_.assign(size_t(binTotal) + 1, 0);
  for (size_t t = 0; t < tets_.size(); ++t)
    forEachBin(t, [&](std::int64_t b) { ++binStart_[size_t(b) + 1]; });
  for (size_t b = 0; b < size_t(binTotal); ++b) binStart_[b + 1] += binStart_[b];
  binTets_.resize(size_t(binStart_.back()));
  std::vector<std::int64_t> fill(binStart_.begin(), binStart_.end() - 1);
  for (size_t t = 0; t < tets_.size(); ++t)
    forEachBin(t, [&](std::int64_t b) { binTets_[size_t(fill[size_t(b)]++)] = std::uint32_t(t); });
}

std::int64_t TetLocator::binIndex(const Vec3d& x, int a) const {
  return std::clamp<std::int64_t>(std::int64_t((x[a] - boxMin_[a]) * binScale_[a]), 0,
                                  bins_[size_t(a)] - 1);
}

bool TetLocator::contains(const Piece& p, const Vec3d& x) const {
  const Vec3d l = p.inverse * (x - p.origin);
  return l.minCoeff() >= -kSlack && l.sum() <= 1.0 + kSlack;
}

std::int64_t TetLocator::locate(const Vec3d& x, std::int64_t hint) const {
  if (hint >= 0 && hint < tetCount() && contains(tets_[size_t(hint)], x)) return hint;
  if (!((x.array() >= boxMin_.array()).all() && (x.array() <= boxMax_.array()).all()))
    return -1;  // outside the box, or not a number
  std::int64_t b = 0;
  for (int a = 2; a >= 0; --a) b = b * bins_[size_t(a)] + binIndex(x, a);
  for (std::int64_t i = binStart_[size_t(b)]; i < binStart_[size_t(b) + 1]; ++i) {
    const std::uint32_t t = binTets_[size_t(i)];
    if (contains(tets_[t], x)) return t;
  }
  return -1;
}

ValueGradient TetLocator::linear(std::int64_t tet, const Vec3d& x) const {
  const Piece& p = tets_[size_t(tet)];
  ValueGradient vg;
  vg.value = float(p.value0 + p.gradient.dot(x - p.origin));
  vg.gradient = p.gradient.cast<float>();
  return vg;
}

}  // namespace mfadvr
