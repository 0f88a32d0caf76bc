#include "core/render/CellPyramid.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace mfadvr {

CellPyramid buildCellPyramid(const int cells[3], const std::uint8_t* cellBytes, bool greatest) {
  CellPyramid out;
  // The levels' sizes, then each level from the one below, one layer of blocks per task.
  std::int64_t size = 0;
  const int* below = cells;
  while (out.levels < kMaxEmptyLevels &&
         (out.levels == 0 || below[0] > 1 || below[1] > 1 || below[2] > 1)) {
    EmptyLevelView& L = out.level[out.levels++];
    for (int a = 0; a < 3; ++a) L.count[a] = (below[a] + 1) / 2;
    L.offset = size;
    size += std::int64_t(L.count[0]) * L.count[1] * L.count[2];
    below = L.count;
  }
  out.bytes.assign(static_cast<size_t>(size), 0);
  for (int l = 0; l < out.levels; ++l) {
    const EmptyLevelView& L = out.level[l];
    const std::uint8_t* from = l == 0 ? cellBytes : out.bytes.data() + out.level[l - 1].offset;
    const int* n = l == 0 ? cells : out.level[l - 1].count;
    std::uint8_t* level = out.bytes.data() + L.offset;
    tbb::parallel_for(0, L.count[2], [&](int k) {
      for (int j = 0; j < L.count[1]; ++j)
        for (int i = 0; i < L.count[0]; ++i) {
          std::uint8_t r = greatest ? 0 : 255;
          for (int kk = 2 * k; kk < std::min(2 * k + 2, n[2]); ++kk)
            for (int jj = 2 * j; jj < std::min(2 * j + 2, n[1]); ++jj)
              for (int ii = 2 * i; ii < std::min(2 * i + 2, n[0]); ++ii) {
                const std::uint8_t b =
                    from[ii + std::int64_t(n[0]) * (jj + std::int64_t(n[1]) * kk)];
                r = greatest ? std::max(r, b) : std::min(r, b);
              }
          level[i + std::int64_t(L.count[0]) * (j + std::int64_t(L.count[1]) * k)] = r;
        }
    });
  }
  return out;
}

}  // namespace mfadvr
