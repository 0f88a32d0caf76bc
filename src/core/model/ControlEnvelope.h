#pragma once
// The envelope of a time-varying model's slabs (TimeVaryingModel.h): per spatial control point,
// the least and the greatest of its nt values. The time basis is non-negative and sums to 1, so
// every instant's contracted control point lies between the two (and, rounded to float, still
// does: both ends are floats). The cell ranges of `lower` and `upper` then bound the values of
// every instant in each cell, and skip flags built from them (render/EmptySpaceGrid.h) hold at
// every time: changing the time needs no new flags. They skip fewer cells than an instant's own
// (a cell is skipped only if it is empty at every time). Envelopes of each time span's p_t + 1
// slabs would be tighter, but measured slower: computing one as the time crosses a span costs
// about what an instant's own flags cost (docs/time-varying.md).
#include "core/spline/TensorBSpline.h"

namespace mfadvr {

struct ControlEnvelope {
  TensorBSpline lower, upper;  // the model's spatial knots
};

}  // namespace mfadvr
