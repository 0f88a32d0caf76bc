#pragma once
// Whether, and into how many blocks, a grid is encoded: `encode --blocks/--ghost/--memory-limit`
// of the command line and the `blocks=`, `ghost=`, `memory_limit=` keywords of the Python module,
// with the same checks, the same automatic choice and the same block report.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/encode/Encoder.h"
#include "core/encode/FitReport.h"
#include "core/grid/StructuredGrid.h"
#include "core/model/DomainBox.h"

namespace mfadvr::app {

// The block options as given: blocks "" (none given), "auto", "B" or "BX,BY,BZ"; ghost < 0 (not
// given); memoryLimit "" (half the available memory) or a byte count ("8G", "512M", "2e9").
struct BlockRequest {
  std::string blocks;
  int ghost = -1;
  std::string memoryLimit;
};

// "8G", "512MB", "2e9": bytes, decimal units. Throws CLI::ValidationError naming `option`.
std::int64_t parseByteCount(const std::string& option, const std::string& text);

// Refuses combinations the block encoder does not take (--ghost without --blocks, blocks with
// --max-error); throws CLI::ValidationError.
void requireBlockOptions(const BlockRequest& request, const EncodeOptions& options, bool strict);

// The blocks to encode `layout` in: the given counts, 'auto', or, when none were given and an
// in-core encoding would need more than the memory limit, the automatic choice (with `note`
// saying so); no value for an in-core encoding. `options` must already have the grid's default
// degree and coding (EncodeCliOptions::fitDefaultDegreeToGrid, CodingCliOptions::applyGridDefault).
struct BlockChoice {
  std::optional<Index3> blocks;
  int ghost = 0;     // the ghost layers the blocks are fitted with
  std::string note;  // why blocks were chosen without being asked for, or empty
};
BlockChoice chooseBlocks(const StructuredGrid& layout, const BlockRequest& request,
                         const EncodeOptions& options);

// Throws CLI::ValidationError when an axis has fewer than 1 or more than (samples - 1) blocks.
void requireBlockCounts(const Index3& blocks, const Index3& dims);

// `encode --blocks --json`'s report: each block's fit report with its region, the worst error,
// times and the peak memory.
nlohmann::json blockFitReportJson(const std::vector<FitReport>& reports,
                                  const std::vector<DomainBox>& regions, const Index3& blocks,
                                  int ghost, double seconds, std::int64_t peakBytes,
                                  double inputBytes, const std::string& output);

}  // namespace mfadvr::app
