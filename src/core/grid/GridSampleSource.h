#pragma once
// Where a grid's samples come from when they need not all be in memory at once: the encoder of
// a multi-block model reads one block (with its ghost layers) at a time, so that a volume larger
// than the memory is encoded with the memory of a block. A file source reads the box from disk;
// the in-memory source copies it out of a grid already loaded.
#include <utility>

#include "core/grid/SampleRange.h"
#include "core/grid/StructuredGrid.h"

namespace mfadvr {

class GridSampleSource {
 public:
  virtual ~GridSampleSource() = default;
  // The grid without its values: dims, origin, spacing, source, names, sample type, input bytes.
  virtual const StructuredGrid& layout() const = 0;
  // The samples of `range` as a grid of their own (origin at its first sample), validated.
  virtual StructuredGrid read(const SampleRange& range) = 0;
  // The smallest and largest sample; throws mfadvr::Error naming the first non-finite one. For a
  // file, one pass over its data (the result is kept).
  virtual std::pair<double, double> valueRange() = 0;
  // The whole grid when it is in memory anyway (choices made on all samples, such as
  // --smooth auto, need it); nullptr for sources that read from disk.
  virtual const StructuredGrid* wholeGrid() const { return nullptr; }
};

// A grid already in memory (held by reference: it must outlive the source).
class InMemoryGridSource final : public GridSampleSource {
 public:
  explicit InMemoryGridSource(const StructuredGrid& grid);
  const StructuredGrid& layout() const override { return layout_; }
  StructuredGrid read(const SampleRange& range) override;
  std::pair<double, double> valueRange() override;
  const StructuredGrid* wholeGrid() const override { return &grid_; }

 private:
  const StructuredGrid& grid_;
  StructuredGrid layout_;
};

}  // namespace mfadvr
