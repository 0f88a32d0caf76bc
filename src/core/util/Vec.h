#pragma once
// Small fixed-size vector types shared by the whole library.
#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace mfadvr {

using Vec3d = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Index3 = std::array<std::int64_t, 3>;
using Degree3 = std::array<int, 3>;

// Symmetric 3x3 second-derivative matrix stored as xx, xy, xz, yy, yz, zz.
using Sym3f = std::array<float, 6>;

}  // namespace mfadvr
