#include "io/InflatedPayload.h"

#include <fcntl.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

void writeAll(int fd, const unsigned char* data, size_t size, const std::string& path) {
  while (size > 0) {
    const ssize_t w = ::write(fd, data, size);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
    data += w;
    size -= static_cast<size_t>(w);
  }
}

}  // namespace

TemporaryFile::~TemporaryFile() {
  if (path_.empty()) return;
  std::error_code ec;
  fs::remove(path_, ec);
}

TemporaryFile inflateToTemporaryFile(const std::string& file, std::int64_t gzipAt,
                                     std::int64_t skip, std::int64_t bytes, const std::string& what,
                                     const InflateProgress& progress) {
  std::error_code ec;
  const fs::path folder = fs::temp_directory_path(ec);
  if (ec) throw Error("inflating " + what + ": no temporary folder (" + ec.message() + ")");
  const fs::space_info space = fs::space(folder, ec);
  if (!ec && static_cast<std::int64_t>(space.available) < bytes) {
    throw Error("inflating " + what + " to read it block by block needs " + formatBytes(bytes) +
                " in the temporary folder " + folder.string() + ", which has " +
                formatBytes(static_cast<std::int64_t>(space.available)) +
                " free; set TMPDIR to a folder on a larger disk");
  }
  std::string name = (folder / "mfadvr-inflated-XXXXXX").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
    throw Error("inflating " + what + ": cannot create a file in " + folder.string() + ": " +
                std::strerror(errno));
  TemporaryFile out(name);
  std::ifstream in(file, std::ios::binary);
  in.seekg(gzipAt);
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) {  // gzip or zlib header
    ::close(fd);
    throw Error("inflating " + what + ": zlib could not start");
  }
  std::vector<char> input(1 << 16);
  std::vector<unsigned char> output(1 << 20);
  std::int64_t seen = 0, written = 0;
  // Progress is told at each 1/256 of the stream needed, not at every buffer.
  std::int64_t toldStep = 0;
  int status = Z_OK;
  try {
    while (written < bytes) {
      if (z.avail_in == 0) {
        in.read(input.data(), static_cast<std::streamsize>(input.size()));
        z.next_in = reinterpret_cast<Bytef*>(input.data());
        z.avail_in = static_cast<uInt>(in.gcount());
        if (z.avail_in == 0) break;
      }
      z.next_out = output.data();
      z.avail_out = static_cast<uInt>(output.size());
      status = inflate(&z, Z_NO_FLUSH);
      if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR) break;
      const std::int64_t got = static_cast<std::int64_t>(output.size() - z.avail_out);
      // The part of this output after the skipped bytes and before the end of the samples.
      const std::int64_t from = std::clamp<std::int64_t>(skip - seen, 0, got);
      const std::int64_t to = std::min<std::int64_t>(got, skip + bytes - seen);
      if (to > from) writeAll(fd, output.data() + from, static_cast<size_t>(to - from), name);
      written += std::max<std::int64_t>(0, to - from);
      seen += got;
      if (progress) {
        // The skipped bytes take as long to inflate as the written ones.
        const std::int64_t needed = skip + bytes, done = std::min(seen, needed);
        const std::int64_t step = done * 256 / needed;
        if (step > toldStep || written >= bytes) {
          toldStep = step;
          progress(written >= bytes ? needed : done, needed);
        }
      }
      if (status == Z_STREAM_END) {
        inflateReset(&z);  // another gzip member may follow
        status = Z_OK;
      }
    }
  } catch (...) {
    inflateEnd(&z);
    ::close(fd);
    throw;
  }
  const std::string message = z.msg ? z.msg : "the stream ends early";
  inflateEnd(&z);
  if (::close(fd) != 0) throw Error("cannot write " + name + ": " + std::strerror(errno));
  if (written < bytes) {
    throw Error("cannot read " + what + ": its gzip data is cut off or corrupt (" + message +
                " after " + std::to_string(seen) + " inflated bytes, " +
                std::to_string(skip + bytes) + " needed)");
  }
  return out;
}

}  // namespace mfadvr
