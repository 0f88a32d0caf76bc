#pragma once
// An axis-aligned box in physical coordinates: a model's domain, a block's region, a render's
// clip box.
#include "core/util/Vec.h"

namespace mfadvr {

struct DomainBox {
  Vec3d min = Vec3d::Zero();
  Vec3d max = Vec3d::Ones();
  Vec3d extent() const { return max - min; }
  // Multiplies by the reciprocal extent, exactly as the renderer's ModelView does, so that a
  // point query and a render sample at the same point agree to the last bit.
  Vec3d toParameter(const Vec3d& x) const {
    return (x - min).cwiseProduct(extent().cwiseInverse());
  }
  bool contains(const Vec3d& x) const {
    return (x.array() >= min.array()).all() && (x.array() <= max.array()).all();
  }
};

}  // namespace mfadvr
