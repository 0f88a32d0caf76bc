#include "app/BlockChoice.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>

#include "app/FitReportOutput.h"
#include "app/OptionParsing.h"
#include "core/encode/PieceEncoder.h"
#include "core/encode/StructuredEncoder.h"
#include "core/model/BlockModelFile.h"
#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr::app {

namespace {

// The memory an in-core encoding of `dims` samples needs: the fit's peak, and for zfp coding
// one decoded candidate and its code beside the fit (measured: 15 B per sample at 512^3, 9 B
// with float32 coding).
std::int64_t inCoreEncodeBytes(const Index3& dims, const EncodeOptions& options) {
  Index3 counts = options.controlCounts;
  for (int a = 0; a < 3; ++a)
    if (counts[a] <= 0) counts[a] = dims[a];
  const std::int64_t ctrl = counts[0] * counts[1] * counts[2];
  const bool zfp = resolvedCoder(options.coding) == ControlCoder::kZfp;
  return structuredFitPeakBytes(dims, counts) + (zfp ? 8 * ctrl : 0);
}

// --blocks auto: at most kDefaultBlockIntervals intervals per block, then halved along the longest
// block axis until one block's encoding (ghost layers included) fits `limit`, or the blocks
// are as small as is worth it (ghost layers would then outweigh the block; the fit refuses with
// its own estimate when the memory really lacks).
constexpr std::int64_t kMinAutoBlockIntervals = 32;
Index3 autoBlockCounts(const Index3& dims, int ghost, const EncodeOptions& options,
                       std::int64_t limit) {
  Index3 blocks = defaultBlockCounts(dims);
  auto blockDims = [&](const Index3& b) {
    Index3 d;
    for (int a = 0; a < 3; ++a)
      d[a] = std::min<std::int64_t>(dims[a], (dims[a] - 1 + b[a] - 1) / b[a] + 1 + 2 * ghost);
    return d;
  };
  while (limit > 0 && inCoreEncodeBytes(blockDims(blocks), options) > limit) {
    const Index3 d = blockDims(blocks);
    int axis = -1;
    for (int a = 0; a < 3; ++a)
      if ((dims[a] - 1) / (2 * blocks[a]) >= kMinAutoBlockIntervals && (axis < 0 || d[a] > d[axis]))
        axis = a;
    if (axis < 0) break;
    blocks[axis] *= 2;
  }
  return blocks;
}

}  // namespace

std::int64_t parseByteCount(const std::string& option, const std::string& text) {
  try {
    return mfadvr::parseByteCount(text);
  } catch (const Error& e) {
    throw CLI::ValidationError(option, e.what());
  }
}

void requireBlockOptions(const BlockRequest& request, const EncodeOptions& options, bool strict) {
  if (request.ghost >= 0 && request.blocks.empty())
    throw CLI::ValidationError("--ghost", "applies with --blocks");
  if (!request.blocks.empty() && (options.adaptive || strict))
    throw CLI::ValidationError("--blocks", "does not combine with --max-error yet");
}

void requireBlockCounts(const Index3& blocks, const Index3& dims) {
  for (int a = 0; a < 3; ++a)
    if (blocks[a] < 1 || blocks[a] > dims[a] - 1 + (dims[a] == 1))
      throw CLI::ValidationError("--blocks",
                                 "each axis needs 1 to (samples - 1) blocks; the grid has " +
                                     std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
                                     std::to_string(dims[2]) + " samples");
}

BlockChoice chooseBlocks(const StructuredGrid& layout, const BlockRequest& request,
                         const EncodeOptions& options) {
  BlockChoice choice;
  choice.ghost = request.ghost >= 0 ? request.ghost : defaultGhostLayers(options.degree);
  const bool limitGiven = !request.memoryLimit.empty();
  const std::int64_t limit = limitGiven ? parseByteCount("--memory-limit", request.memoryLimit)
                                        : availableMemoryBytes() / 2;
  if (request.blocks == "auto") {
    choice.blocks = autoBlockCounts(layout.dims, choice.ghost, options, limit);
  } else if (!request.blocks.empty()) {
    const auto n = parseIntTriple("--blocks", request.blocks);
    choice.blocks = Index3{n[0], n[1], n[2]};
  } else {
    const std::int64_t need = inCoreEncodeBytes(layout.dims, options);
    if (options.adaptive || limit <= 0 || need <= limit) return choice;
    const Index3 b = autoBlockCounts(layout.dims, choice.ghost, options, limit);
    if (b[0] * b[1] * b[2] == 1) return choice;
    const std::string limitName = limitGiven ? "--memory-limit" : "half the available memory";
    if (b[0] * b[1] * b[2] > kMaxBlockCount)
      throw Error("encoding " + layout.source + " needs about " + formatBytes(need) +
                  " of memory, more than " + formatBytes(limit) + " (" + limitName +
                  "), and out of core it would take " + std::to_string(b[0] * b[1] * b[2]) +
                  " blocks, more than a multi-block model holds (" +
                  std::to_string(kMaxBlockCount) + ")");
    choice.note = "encoding " + layout.source + " in memory would need about " + formatBytes(need) +
                  ", more than " + formatBytes(limit) + " (" + limitName + "): encoding it in " +
                  std::to_string(b[0]) + "x" + std::to_string(b[1]) + "x" + std::to_string(b[2]) +
                  " blocks (--blocks auto), a multi-block model";
    choice.blocks = b;
  }
  requireBlockCounts(*choice.blocks, layout.dims);
  return choice;
}

nlohmann::json blockFitReportJson(const std::vector<FitReport>& reports,
                                  const std::vector<DomainBox>& regions, const Index3& blocks,
                                  int ghost, double seconds, std::int64_t peakBytes,
                                  double inputBytes, const std::string& output) {
  double worst = 0.0, fitSeconds = 0.0;
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < reports.size(); ++i) {
    worst = std::max(worst, reports[i].maxRelativeError());
    fitSeconds += reports[i].seconds;
    nlohmann::json j = fitReportJson(reports[i], "");
    const DomainBox& r = regions[i];
    j["region"] = {r.min[0], r.max[0], r.min[1], r.max[1], r.min[2], r.max[2]};
    list.push_back(j);
  }
  return {{"output", output},
          {"blocks", blocks},
          {"ghost_layers", ghost},
          {"max_relative_error", worst},
          {"fit_seconds", fitSeconds},
          {"seconds", seconds},
          {"input_megabytes_per_second", inputBytes / 1e6 / seconds},
          {"peak_memory_bytes", peakBytes},
          {"block_reports", list}};
}

}  // namespace mfadvr::app
