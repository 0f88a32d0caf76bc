#pragma once
// A built-in function as a sample source: any box of its grid is sampled when read, so that
// `encode builtin:NAME:N --blocks ...` holds one block at a time, like a file read out of core.
#include <memory>
#include <string>

#include "core/analytic/BuiltinFunction.h"
#include "core/grid/GridSampleSource.h"

namespace mfadvr {

class BuiltinGridSource final : public GridSampleSource {
 public:
  // spec: builtin:NAME[:N|:NXxNYxNZ]; throws mfadvr::Error as parseBuiltinSpec does.
  explicit BuiltinGridSource(const std::string& spec);
  const StructuredGrid& layout() const override { return layout_; }
  StructuredGrid read(const SampleRange& range) override;
  // One pass over every sample, slab by slab (nothing held).
  std::pair<double, double> valueRange() override;

 private:
  std::unique_ptr<BuiltinFunction> function_;
  StructuredGrid layout_;
  bool haveRange_ = false;
  std::pair<double, double> range_{0.0, 0.0};
};

}  // namespace mfadvr
