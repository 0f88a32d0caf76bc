#include "core/mesh/CellSamples.h"

#include <array>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

namespace {

// Barycentric weights of the rules: the centroid, and the symmetric degree-2 rule of four
// points with a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20 (exact for quadratics).
constexpr double kA = 0.5854101966249685;
constexpr double kB = 0.1381966011250105;
constexpr std::array<std::array<double, 4>, 1> kCentroid{{{0.25, 0.25, 0.25, 0.25}}};
constexpr std::array<std::array<double, 4>, 4> kFourPoint{
    {{kA, kB, kB, kB}, {kB, kA, kB, kB}, {kB, kB, kA, kB}, {kB, kB, kB, kA}}};

template <size_t N>
void appendSamples(const ScatteredData& data, const std::array<std::array<double, 4>, N>& rule,
                   ScatteredData& out) {
  for (const Tetrahedron& t : data.tets) {
    if (data.volume6(t) == 0.0) continue;
    for (const auto& w : rule) {
      Vec3d p{0.0, 0.0, 0.0};
      double v = 0.0;
      for (int k = 0; k < 4; ++k) {
        p += w[k] * data.points[static_cast<size_t>(t[k])];
        v += data.values[static_cast<size_t>(t[k])] * w[k];
      }
      out.points.push_back(p);
      out.values.push_back(v);
    }
  }
}

}  // namespace

bool isCellSampleCount(int perCell) {
  return perCell == 1 || perCell == 4;
}

std::int64_t cellSampleCount(const ScatteredData& data, int perCell) {
  std::int64_t n = 0;
  for (const Tetrahedron& t : data.tets)
    if (data.volume6(t) != 0.0) ++n;
  return n * perCell;
}

ScatteredData withCellSamples(const ScatteredData& data, int perCell) {
  if (!isCellSampleCount(perCell))
    throw Error("cell samples per tetrahedron must be 1 or 4, not " + std::to_string(perCell));
  if (!data.hasCells())
    throw Error(data.source + ": cell samples need a mesh; a point cloud has no cells");
  data.validate();  // tetrahedra index the points
  ScatteredData out = data;
  const auto total = data.points.size() + static_cast<size_t>(cellSampleCount(data, perCell));
  out.points.reserve(total);
  out.values.reserve(total);
  if (perCell == 1)
    appendSamples(data, kCentroid, out);
  else
    appendSamples(data, kFourPoint, out);
  return out;
}

}  // namespace mfadvr
