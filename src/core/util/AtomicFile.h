#pragma once
// Writes a whole file so that readers see either the old file or the complete new one.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/util/InterruptCleanup.h"

namespace mfadvr {

// A file written under a temporary name beside its target (mode 0644 once committed) and
// renamed over the target by commit(); destroyed uncommitted, it removes the temporary file.
// Errors throw mfadvr::Error naming the target and the system's reason.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(std::filesystem::path target);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view bytes);
  // Overwrites bytes already written, from `offset` on (a header completed at the end).
  void writeAt(std::uint64_t offset, std::string_view bytes);
  // The temporary file, for writers that open a path themselves (VTK's writers): they write it
  // in place of write(), then commit() publishes it.
  const std::filesystem::path& temporaryPath() const { return temporary_; }
  // Flushes to disk and renames the temporary file over the target.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& what);
  std::filesystem::path target_, temporary_;
  int fd_ = -1;
  bool committed_ = false;
  std::optional<InterruptCleanup> cleanup_;  // removes the temporary file on Ctrl-C
};

// Throws mfadvr::Error (naming the path and the system's reason) on failure and leaves no
// temporary file behind.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace mfadvr
