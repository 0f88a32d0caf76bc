// Files registered for removal on interrupt (core/util/InterruptCleanup.h): a child process
// that is sent SIGTERM mid-write leaves no temporary file behind; a committed file stays.
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "core/util/AtomicFile.h"
#include "core/util/InterruptCleanup.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

size_t filesIn(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
  return n;
}

TEST(InterruptCleanup, TemporaryFilesAreRemovedWhenTheProcessIsInterrupted) {
  const fs::path dir = test::scratchDir();
  const fs::path done = dir / "done.mfa", pending = dir / "pending.mfa";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    removeFilesOnInterrupt();
    writeFileAtomically(done, "committed");
    AtomicFileWriter writer(pending);  // interrupted before its commit
    writer.write("partial");
    const fs::path other = dir / "inflated";
    std::ofstream(other) << "scratch";
    InterruptCleanup scratch(other.string());
    ::raise(SIGTERM);
    ::_exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_TRUE(fs::exists(done));
  EXPECT_EQ(filesIn(dir), 1u);  // only the committed file
}

TEST(InterruptCleanup, ReleasedPathsAreKept) {
  const fs::path dir = test::scratchDir();
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    removeFilesOnInterrupt();
    const fs::path kept = dir / "kept";
    std::ofstream(kept) << "result";
    InterruptCleanup registration(kept.string());
    registration.release();
    ::raise(SIGINT);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status));
  EXPECT_TRUE(fs::exists(dir / "kept"));
}

}  // namespace
}  // namespace mfadvr
