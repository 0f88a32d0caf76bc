#pragma once
// A regular grid reconstructed by a local filter: the classic alternatives to the MFA model.
//
// GridField<Filter> owns the (padded) grid; Filter is the per-thread sampler type, constructed
// from the grid, with value(x) and valueGradient(x) in physical coordinates. The filters and
// their gradients are in GridFilters.h.
#include <memory>

#include "core/field/Field.h"
#include "core/field/PaddedGrid.h"

namespace mfadvr {

template <class Filter>
class GridField {
 public:
  // Filter::prepare turns the samples into what the filter interpolates (the samples
  // themselves, or B-spline coefficients).
  explicit GridField(const StructuredGrid& grid)
      : grid_(std::make_shared<const PaddedGrid>(Filter::prepare(grid))) {}
  Vec3d boxMin() const { return grid_->boxMin(); }
  Vec3d boxMax() const { return grid_->boxMax(); }
  const PaddedGrid& grid() const { return *grid_; }

  using Sampler = Filter;
  Filter sampler() const { return Filter(*grid_); }

 private:
  std::shared_ptr<const PaddedGrid> grid_;
};

}  // namespace mfadvr
