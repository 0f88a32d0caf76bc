#include "core/mesh/ScatteredData.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

Vec3d ScatteredData::boxMin() const {
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  for (const Vec3d& p : points) lo = lo.cwiseMin(p);
  return lo;
}

Vec3d ScatteredData::boxMax() const {
  Vec3d hi = Vec3d::Constant(-std::numeric_limits<double>::infinity());
  for (const Vec3d& p : points) hi = hi.cwiseMax(p);
  return hi;
}

double ScatteredData::volume6(const Tetrahedron& t) const {
  const Vec3d& a = points[static_cast<size_t>(t[0])];
  const Vec3d e1 = points[static_cast<size_t>(t[1])] - a;
  const Vec3d e2 = points[static_cast<size_t>(t[2])] - a;
  const Vec3d e3 = points[static_cast<size_t>(t[3])] - a;
  return e1.dot(e2.cross(e3));
}

void ScatteredData::validate() const {
  const std::string name = source.empty() ? std::string("scattered data") : source;
  if (points.empty()) throw Error(name + ": has no points");
  if (values.size() != points.size()) {
    std::ostringstream m;
    m << name << ": " << values.size() << " values for " << points.size() << " points";
    throw Error(m.str());
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      std::ostringstream m;
      m << name << ": point " << i << " has a NaN or infinite coordinate";
      throw Error(m.str());
    }
    if (!std::isfinite(values[i])) {
      std::ostringstream m;
      m << name << ": the value at point " << i << " is " << values[i]
        << "; every value must be finite";
      throw Error(m.str());
    }
  }
  const Vec3d lo = boxMin(), hi = boxMax();
  for (int a = 0; a < 3; ++a) {
    if (!(hi[a] > lo[a])) {
      std::ostringstream m;
      m << name << ": the points span no extent along "
        << "xyz"[a] << " (all at " << lo[a] << "): 2-D data; a 3-D model needs a box with volume";
      throw Error(m.str());
    }
  }
  const auto n = static_cast<std::int64_t>(points.size());
  for (size_t t = 0; t < tets.size(); ++t)
    for (std::int64_t v : tets[t])
      if (v < 0 || v >= n) {
        std::ostringstream m;
        m << name << ": cell " << t << " refers to point " << v << " of " << n;
        throw Error(m.str());
      }
}

}  // namespace mfadvr
