#include "core/render/RenderMemory.h"

#include "core/util/MemoryBudget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mfadvr {

namespace {
// Headers not yet checked against their files may claim 2^60 control points: sums saturate here
// instead of wrapping around.
constexpr std::int64_t kCap = std::numeric_limits<std::int64_t>::max() / 4;
}  // namespace

std::int64_t modelRenderBytes(const ModelFileSummary& m, bool extremeBounds) {
  double cells = 1.0;
  for (int a = 0; a < 3; ++a)
    cells *= static_cast<double>(std::max<std::int64_t>(m.controlCounts[a] - m.degree[a], 1));
  const double flags = cells + std::floor(cells / 7.0) + 1.0;
  const double bounds = extremeBounds ? 2.0 * flags : 0.0;  // an upper and a lower byte
  const double bytes = static_cast<double>(loadedModelBytes(m)) + flags + bounds;
  return bytes < static_cast<double>(kCap) ? static_cast<std::int64_t>(bytes) : kCap;
}

std::int64_t sceneRenderBytes(std::span<const ModelFileSummary> models, bool extremeBounds) {
  std::int64_t total = 0, largestFile = 0;
  for (const ModelFileSummary& m : models) {
    total = std::min(kCap, total + modelRenderBytes(m, extremeBounds));
    if (!m.readInPlace) largestFile = std::max(largestFile, static_cast<std::int64_t>(m.fileBytes));
  }
  return total + largestFile;
}

void requireSceneRenderMemory(std::span<const ModelFileSummary> models, const std::string& what,
                              const std::string& detail, bool extremeBounds) {
  double points = 0.0;
  for (const ModelFileSummary& m : models)
    points += static_cast<double>(m.controlCounts[0]) * static_cast<double>(m.controlCounts[1]) *
              static_cast<double>(m.controlCounts[2]);
  char count[32];
  std::snprintf(count, sizeof count, "%.3g", points);
  requireMemory(sceneRenderBytes(models, extremeBounds), what + " (" + count + " control points" + detail + ")");
}

}  // namespace mfadvr
