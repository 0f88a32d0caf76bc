#pragma once
// Gzip-compressed samples (NRRD's gzip encoding, .nii.gz) inflated once, as a stream, into a
// temporary file, so that they can be read a box at a time like uncompressed samples: memory
// stays bounded by zlib's buffers, the disk holds the samples once.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/util/InterruptCleanup.h"

namespace mfadvr {

// A file in the temporary folder (TMPDIR, else /tmp), removed when this object goes. On Linux a
// file already opened stays readable after its removal.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string path)
      : path_(std::move(path)), cleanup_(std::make_unique<InterruptCleanup>(path_)) {}
  ~TemporaryFile();
  TemporaryFile(TemporaryFile&& other) noexcept
      : path_(std::move(other.path_)), cleanup_(std::move(other.cleanup_)) {
    other.path_.clear();
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  TemporaryFile& operator=(TemporaryFile&&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::unique_ptr<InterruptCleanup> cleanup_;  // removes the file on Ctrl-C
};

// Told how many bytes of the stream are inflated so far, out of how many are needed (the
// skipped ones and the samples): a few hundred times at most, and once at the end (done ==
// total). It may throw to stop the inflation; the temporary file is then removed and the
// exception goes on to the caller.
using InflateProgress = std::function<void(std::int64_t done, std::int64_t total)>;

// Inflates the gzip stream of `file` that starts at byte `gzipAt` (concatenated members are
// one stream), drops its first `skip` bytes and writes the next `bytes` to a temporary file.
// Throws mfadvr::Error naming `what` when the stream is corrupt or ends early, or when the
// temporary folder lacks the room (the message names TMPDIR). Inflating takes seconds per
// gigabyte: `progress`, when set, hears how far it is.
TemporaryFile inflateToTemporaryFile(const std::string& file, std::int64_t gzipAt,
                                     std::int64_t skip, std::int64_t bytes, const std::string& what,
                                     const InflateProgress& progress = {});

}  // namespace mfadvr
