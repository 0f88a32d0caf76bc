#include "core/render/RenderMemory.h"

#include <algorithm>

namespace mfadvr {

std::int64_t modelRenderBytes(const ModelFileSummary& m) {
  std::int64_t cells = 1;
  for (int a = 0; a < 3; ++a) cells *= std::max<std::int64_t>(m.controlCounts[a] - m.degree[a], 1);
  const std::int64_t flags = cells + cells / 7 + 1;
  return loadedModelBytes(m) + 2 * 4 * cells + flags;
}

std::int64_t sceneRenderBytes(std::span<const ModelFileSummary> models) {
  std::int64_t total = 0, largestFile = 0;
  for (const ModelFileSummary& m : models) {
    total += modelRenderBytes(m);
    largestFile = std::max(largestFile, static_cast<std::int64_t>(m.fileBytes));
  }
  return total + largestFile;
}

}  // namespace mfadvr
