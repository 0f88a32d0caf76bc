#include "core/util/AtomicFile.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "core/util/Error.h"

namespace mfadvr {

AtomicFileWriter::AtomicFileWriter(std::filesystem::path target) : target_(std::move(target)) {
  const std::filesystem::path dir =
      target_.has_parent_path() ? target_.parent_path() : std::filesystem::path(".");
  std::string tmpl = (dir / (target_.filename().string() + ".tmp.XXXXXX")).string();
  fd_ = mkstemp(tmpl.data());
  if (fd_ < 0) throw Error("cannot write " + target_.string() + ": " + std::strerror(errno));
  temporary_ = tmpl;
  cleanup_.emplace(temporary_.string());
}

AtomicFileWriter::~AtomicFileWriter() {
  if (committed_) return;
  if (fd_ >= 0) ::close(fd_);
  ::unlink(temporary_.c_str());
}

void AtomicFileWriter::fail(const std::string& what) {
  const int err = errno;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temporary_.c_str());
  committed_ = true;  // nothing left to clean up
  throw Error("cannot write " + target_.string() + ": " + what + ": " + std::strerror(err));
}

void AtomicFileWriter::write(std::string_view bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      fail("write failed");
    }
    done += static_cast<size_t>(w);
  }
}

void AtomicFileWriter::writeAt(std::uint64_t offset, std::string_view bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t w =
        ::pwrite(fd_, bytes.data() + done, bytes.size() - done, static_cast<off_t>(offset + done));
    if (w < 0) {
      if (errno == EINTR) continue;
      fail("write failed");
    }
    done += static_cast<size_t>(w);
  }
}

void AtomicFileWriter::commit() {
  // mkstemp creates 0600 files; give the result the usual permissions for a data file.
  ::fchmod(fd_, 0644);
  if (::fsync(fd_) != 0) fail("fsync failed");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("close failed");
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) fail("rename failed");
  committed_ = true;
  cleanup_.reset();
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFileWriter file(path);
  file.write(bytes);
  file.commit();
}

}  // namespace mfadvr
