#include "core/encode/PieceEncoder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

SampleRange pieceRange(const Index3& dims, const Index3& pieces, const Index3& piece) {
  SampleRange r;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t intervals = dims[a] - 1;
    if (pieces[a] < 1 || (pieces[a] > 1 && pieces[a] > intervals))
      throw Error("cannot split " + std::to_string(dims[a]) + " samples along " + "xyz"[a] +
                  " into " + std::to_string(pieces[a]) + " pieces");
    if (piece[a] < 0 || piece[a] >= pieces[a])
      throw Error("piece index out of range along " + std::string(1, "xyz"[a]));
    r.lo[a] = piece[a] * intervals / pieces[a];
    r.hi[a] = (piece[a] + 1) * intervals / pieces[a];
  }
  return r;
}

SampleRange withGhostLayers(const SampleRange& range, int ghost, const Index3& dims) {
  SampleRange r = range;
  for (int a = 0; a < 3; ++a) {
    r.lo[a] = std::max<std::int64_t>(0, range.lo[a] - ghost);
    r.hi[a] = std::min<std::int64_t>(dims[a] - 1, range.hi[a] + ghost);
  }
  return r;
}

int defaultGhostLayers(const Degree3& degree) {
  return 2 * (*std::max_element(degree.begin(), degree.end()) + 1);
}

namespace {

// options with the whole grid's control counts scaled to the piece (same density).
EncodeOptions pieceOptions(const StructuredGrid& pieceGrid, const Index3& wholeDims,
                           const EncodeOptions& options) {
  EncodeOptions piece = options;
  for (int a = 0; a < 3; ++a) {
    if (options.controlCounts[a] <= 0) continue;
    if (wholeDims[a] < 2 || pieceGrid.dims[a] > wholeDims[a])
      throw Error("the piece is larger than the whole grid");
    // Same density: control intervals per sample interval as in the whole grid.
    const double density =
        double(options.controlCounts[a] - options.degree[a]) / double(wholeDims[a] - 1);
    const std::int64_t count =
        std::llround(density * double(pieceGrid.dims[a] - 1)) + options.degree[a];
    piece.controlCounts[a] =
        std::clamp<std::int64_t>(count, options.degree[a] + 1, pieceGrid.dims[a]);
  }
  if (piece.adaptive)
    for (int a = 0; a < 3; ++a)
      if (piece.adaptive->maxControlCounts[a] > 0)
        piece.adaptive->maxControlCounts[a] =
            std::min<std::int64_t>(piece.adaptive->maxControlCounts[a], pieceGrid.dims[a]);
  return piece;
}

}  // namespace

Model encodeStructuredPiece(const StructuredGrid& pieceGrid, const Index3& wholeDims,
                            const EncodeOptions& options, double valueMin, double valueMax,
                            FitReport* report) {
  Model m = encodeStructured(pieceGrid, pieceOptions(pieceGrid, wholeDims, options), report);
  m.setValueRange(valueMin, valueMax);
  return m;
}

Model encodeStructuredPiece(const StructuredGrid& pieceLayout, const GridSamples& samples,
                            const Index3& wholeDims, const EncodeOptions& options, double valueMin,
                            double valueMax, FitReport* report) {
  Model m =
      encodeStructured(pieceLayout, samples, pieceOptions(pieceLayout, wholeDims, options), report);
  m.setValueRange(valueMin, valueMax);
  return m;
}

Index3 defaultBlockCounts(const Index3& dims) {
  Index3 blocks{1, 1, 1};
  for (int a = 0; a < 3; ++a)
    blocks[a] = std::max<std::int64_t>(
        1, (dims[a] - 1 + kDefaultBlockIntervals - 1) / kDefaultBlockIntervals);
  return blocks;
}

void encodeStructuredBlocks(GridSampleSource& source, const Index3& blocks, int ghost,
                            const EncodeOptions& options, const BlockSink& sink) {
  const StructuredGrid& layout = source.layout();
  if (ghost < 0) ghost = defaultGhostLayers(options.degree);
  pieceRange(layout.dims, blocks, {0, 0, 0});  // checks the block counts before any reading
  EncodeOptions quiet = options;
  quiet.progress = nullptr;
  if (options.autoSmoothing) {
    // One lambda for every block, chosen on the whole grid: blocks must agree across their faces.
    const StructuredGrid* whole = source.wholeGrid();
    if (!whole)
      throw Error(layout.source +
                  ": --smooth auto chooses lambda on the whole grid, which out-of-core block "
                  "encoding never holds; give a fixed --smooth LAMBDA");
    quiet = withChosenSmoothing(*whole, quiet);
  }
  if (options.progress) options.progress(0.0, "value range");
  const auto [lo, hi] = source.valueRange();
  // Blocks hold nearly equal numbers of samples: their count measures the work done.
  const std::int64_t count = blocks[0] * blocks[1] * blocks[2];
  std::int64_t done = 0;
  for (std::int64_t k = 0; k < blocks[2]; ++k)
    for (std::int64_t j = 0; j < blocks[1]; ++j)
      for (std::int64_t i = 0; i < blocks[0]; ++i) {
        const SampleRange own = pieceRange(layout.dims, blocks, {i, j, k});
        FitReport report;
        Model model;
        {
          const StructuredGrid piece = source.read(withGhostLayers(own, ghost, layout.dims));
          model = encodeStructuredPiece(piece, layout.dims, quiet, lo, hi, &report);
        }
        ModelBlock b{{layout.position(own.lo[0], own.lo[1], own.lo[2]),
                      layout.position(own.hi[0], own.hi[1], own.hi[2])},
                     std::move(model)};
        // The region and the model's box are computed from different origins; keep rounding
        // from putting the region a hair outside the box.
        b.region.min = b.region.min.cwiseMax(b.model.domain().min);
        b.region.max = b.region.max.cwiseMin(b.model.domain().max);
        sink(std::move(b), report);
        ++done;
        if (options.progress)
          options.progress(double(done) / double(count),
                           "block " + std::to_string(done) + " of " + std::to_string(count));
      }
}

std::vector<ModelBlock> encodeStructuredBlocks(const StructuredGrid& grid, const Index3& blocks,
                                               int ghost, const EncodeOptions& options,
                                               std::vector<FitReport>* reports) {
  InMemoryGridSource source(grid);
  std::vector<ModelBlock> out;
  out.reserve(static_cast<size_t>(blocks[0] * blocks[1] * blocks[2]));
  encodeStructuredBlocks(source, blocks, ghost, options,
                         [&](ModelBlock&& b, const FitReport& report) {
                           if (reports) reports->push_back(report);
                           out.push_back(std::move(b));
                         });
  return out;
}

}  // namespace mfadvr
