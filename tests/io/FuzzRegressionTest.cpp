// Every input the fuzzers found that crashed, hung or leaked (fuzz/regressions/), replayed
// through the same loaders in every build: each must now load or give an mfadvr::Error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "FileLoaderInput.h"
#include "TestSupport.h"

namespace mfadvr {
namespace {

TEST(FuzzRegression, FileLoaderFindingsLoadOrFailCleanly) {
  const std::filesystem::path dir =
      std::filesystem::path(MFADVR_SOURCE_DIR) / "fuzz" / "regressions" / "file_loaders";
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                          std::istreambuf_iterator<char>());
    SCOPED_TRACE(entry.path().filename().string());
    (void)fuzzing::loadFuzzInput(bytes.data(), bytes.size(), test::scratchDir());
    ++replayed;
  }
  EXPECT_GE(replayed, 4);
  std::printf("replayed %d fuzzer findings\n", replayed);
}

}  // namespace
}  // namespace mfadvr
