#pragma once
// Partitioned encoding of a grid: the samples are split into pieces along each axis, each piece
// is fitted with a few ghost layers of its neighbours' samples around it, and renders only its
// own region. Used by `mfadvr encode --blocks` (a multi-block model file) and, one piece per
// rank, by the VTK encoder under ParaView's MPI pipelines.
//
// Pieces share their boundary samples, as VTK's extents do: piece b of B along an axis of n
// samples covers samples floor(b (n-1) / B) .. floor((b+1) (n-1) / B). A piece's model is fitted
// to its samples plus `ghost` layers beyond each face that has a neighbour, so that the models of
// two neighbours agree closely across their common face (each sees the same data there); its
// region is the box of its own samples, and the regions of the pieces tile the whole box without
// overlapping.
#include <functional>
#include <vector>

#include "core/encode/Encoder.h"
#include "core/grid/GridSampleSource.h"
#include "core/grid/SampleRange.h"
#include "core/grid/StructuredGrid.h"
#include "core/model/BlockModelFile.h"
#include "core/model/Model.h"

namespace mfadvr {

// Piece `piece` of a grid of `dims` samples split into `pieces` per axis. Throws mfadvr::Error
// when an axis has more pieces than sample intervals.
SampleRange pieceRange(const Index3& dims, const Index3& pieces, const Index3& piece);

// `range` grown by `ghost` samples on every side, clipped to the grid.
SampleRange withGhostLayers(const SampleRange& range, int ghost, const Index3& dims);

// The default ghost layers for a degree: enough samples that both neighbours' fits see the same
// data over the support of the basis functions near their common face.
int defaultGhostLayers(const Degree3& degree);

// Fits one piece: `pieceGrid` holds the piece's samples and its ghost layers, out of a whole grid
// of `wholeDims` samples. Control counts in `options` are for the whole grid and are scaled to
// the piece (same control-point density; 0, the default, interpolates the piece's samples). The
// model's value range is `valueRange` (the whole grid's, so that normalized transfer functions
// mean the same in every piece).
Model encodeStructuredPiece(const StructuredGrid& pieceGrid, const Index3& wholeDims,
                            const EncodeOptions& options, double valueMin, double valueMax,
                            FitReport* report = nullptr);
// The same for a piece whose samples are held elsewhere (Encoder.h's encodeStructured).
Model encodeStructuredPiece(const StructuredGrid& pieceLayout, const GridSamples& samples,
                            const Index3& wholeDims, const EncodeOptions& options, double valueMin,
                            double valueMax, FitReport* report = nullptr);

// Blocks per axis for out-of-core encoding: pieces of at most kDefaultBlockIntervals sample
// intervals along each axis (about 256^3 samples, a fit of a few hundred MB, and a good share
// for one rendering process).
inline constexpr std::int64_t kDefaultBlockIntervals = 256;
Index3 defaultBlockCounts(const Index3& dims);

// Receives each block as soon as it is fitted, in file order (x fastest).
using BlockSink = std::function<void(ModelBlock&& block, const FitReport& report)>;

// Splits the source's grid into blocks[0] x blocks[1] x blocks[2] pieces (x fastest), reads each
// with `ghost` layers (negative: defaultGhostLayers), fits it and hands it to `sink`: at any time
// only one block's samples and fit are held. The value range of every block is the whole grid's
// (one pass over the source first). options.progress receives the fraction of samples done.
// --smooth auto needs a source with the whole grid in memory (one lambda for every block).
void encodeStructuredBlocks(GridSampleSource& source, const Index3& blocks, int ghost,
                            const EncodeOptions& options, const BlockSink& sink);

// The same for a grid in memory, returning the blocks; reports (optional) receive one fit report
// per block.
std::vector<ModelBlock> encodeStructuredBlocks(const StructuredGrid& grid, const Index3& blocks,
                                               int ghost, const EncodeOptions& options,
                                               std::vector<FitReport>* reports = nullptr);

}  // namespace mfadvr
