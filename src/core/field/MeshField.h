#pragma once
// A tetrahedral mesh's own field as a Field (TetLocator.h): linear in each tetrahedron, empty
// outside the mesh. Rendered through the same ray caster as the models (--method mesh), it is the
// reference a model of the mesh is measured against without a second renderer's differences.
#include <limits>

#include "core/field/Field.h"
#include "core/mesh/TetLocator.h"

namespace mfadvr {

class MeshField {
 public:
  explicit MeshField(const TetLocator& mesh) : mesh_(&mesh) {}
  Vec3d boxMin() const { return mesh_->boxMin(); }
  Vec3d boxMax() const { return mesh_->boxMax(); }

  // The ray caster asks inside(x) and then the value at the same x: the tetrahedron found for
  // the one serves the other, and is the first guess for the next sample.
  class Sampler {
   public:
    explicit Sampler(const TetLocator& m) : mesh_(&m) {}
    bool inside(const Vec3d& x) { return find(x) >= 0; }
    float value(const Vec3d& x) { return valueGradient(x).value; }
    ValueGradient valueGradient(const Vec3d& x) {
      const std::int64_t t = find(x);
      return t >= 0 ? mesh_->linear(t, x) : ValueGradient{};
    }

   private:
    std::int64_t find(const Vec3d& x) {
      if (x != last_) {
        last_ = x;
        const std::int64_t t = mesh_->locate(x, hint_);
        if (t >= 0) hint_ = t;
        tet_ = t;
      }
      return tet_;
    }
    const TetLocator* mesh_;
    Vec3d last_ = Vec3d::Constant(std::numeric_limits<double>::quiet_NaN());
    std::int64_t tet_ = -1, hint_ = -1;
  };
  Sampler sampler() const { return Sampler(*mesh_); }

 private:
  const TetLocator* mesh_;
};

}  // namespace mfadvr
