#include "io/headers/HeaderText.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr::headers {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

bool hasControlCharacters(const std::string& line) {
  return std::any_of(line.begin(), line.end(), [](char c) {
    return static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r';
  });
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::int64_t parseCount(const std::string& text) {
  std::int64_t v = -1;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || v < 0) return -1;
  return v;
}

std::int64_t product(const std::vector<std::int64_t>& counts) {
  std::int64_t p = 1;
  for (std::int64_t c : counts) {
    if (c == 0) return 0;
    if (p > std::numeric_limits<std::int64_t>::max() / c)
      return std::numeric_limits<std::int64_t>::max();
    p *= c;
  }
  return p;
}

std::int64_t times(std::int64_t a, std::int64_t b) {
  return product({a, b});
}

std::string grouped(std::int64_t v) {
  std::string digits = std::to_string(v), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string dimsText(const std::vector<std::int64_t>& counts) {
  std::string out;
  for (size_t i = 0; i < counts.size(); ++i) out += (i ? " x " : "") + std::to_string(counts[i]);
  return out;
}

std::int64_t fileSize(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? -1 : static_cast<std::int64_t>(size);
}

std::string readHead(const std::string& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string out(bytes, '\0');
  in.read(out.data(), static_cast<std::streamsize>(bytes));
  out.resize(static_cast<size_t>(in.gcount()));
  return out;
}

std::string readTail(const std::string& path, std::int64_t size, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  const std::int64_t start = std::max<std::int64_t>(0, size - static_cast<std::int64_t>(bytes));
  in.seekg(start);
  std::string out(static_cast<size_t>(size - start), '\0');
  in.read(out.data(), static_cast<std::streamsize>(out.size()));
  out.resize(static_cast<size_t>(in.gcount()));
  return out;
}

// Whether the gzip data of `path` from byte `offset` on is complete and inflates to at least
// `expected` bytes. The last 4 bytes of a gzip stream hold the uncompressed size (mod 2^32):
// when they match, the stream ends where it should (the common, cheap case). Otherwise, e.g.
// for several concatenated gzip members, the data is inflated to find out; zlib checks each
// member's CRC on the way.
void requireCompleteGzip(const std::string& path, const std::string& format,
                         const std::string& file, std::int64_t offset, std::int64_t expected) {
  const std::int64_t size = fileSize(file);
  if (size < 0) return;
  if (size - offset >= 18) {
    const std::string tail = readTail(file, size, 4);
    const std::uint32_t isize =
        std::uint32_t(std::uint8_t(tail[0])) | std::uint32_t(std::uint8_t(tail[1])) << 8 |
        std::uint32_t(std::uint8_t(tail[2])) << 16 | std::uint32_t(std::uint8_t(tail[3])) << 24;
    if (isize == static_cast<std::uint32_t>(expected)) return;
  }
  std::ifstream in(file, std::ios::binary);
  in.seekg(offset);
  z_stream z{};
  if (inflateInit2(&z, 15 + 32) != Z_OK) return;  // gzip or zlib header
  std::vector<char> input(1 << 16);
  std::vector<unsigned char> output(1 << 16);
  const auto refill = [&] {
    in.read(input.data(), static_cast<std::streamsize>(input.size()));
    z.next_in = reinterpret_cast<Bytef*>(input.data());
    z.avail_in = static_cast<uInt>(in.gcount());
  };
  std::int64_t total = 0;
  int status = Z_OK;
  for (;;) {
    if (z.avail_in == 0) refill();
    if (z.avail_in == 0) break;  // out of input before the stream's end: cut off
    z.next_out = output.data();
    z.avail_out = static_cast<uInt>(output.size());
    status = inflate(&z, Z_NO_FLUSH);
    total += static_cast<std::int64_t>(output.size() - z.avail_out);
    if (status == Z_STREAM_END) {
      if (z.avail_in == 0) refill();
      if (z.avail_in == 0) break;  // the clean end
      inflateReset(&z);            // another gzip member follows
      status = Z_OK;
    } else if (status != Z_OK && status != Z_BUF_ERROR) {
      break;
    }
  }
  const std::string message = z.msg ? z.msg : "the stream ends early";
  inflateEnd(&z);
  if (status != Z_STREAM_END) {
    throw Error("cannot read " + path + " as " + format +
                ": its gzip data is cut off or corrupt (" + message + " after " + grouped(total) +
                " bytes)");
  }
  if (total < expected) {
    throw Error("cannot read " + path + " as " + format + ": its gzip data inflates to " +
                grouped(total) + " bytes, but the header declares " + grouped(expected));
  }
}

DataFileSize dataFilesBeside(const std::string& path) {
  return [dir = fs::path(path).parent_path()](const std::string& name) {
    const fs::path p(name);
    return fileSize((p.is_absolute() ? p : dir / p).string());
  };
}

DeclaredPayload besideHeader(DeclaredPayload payload, const std::string& path) {
  if (payload.file.empty() || payload.file == path) return payload;
  const fs::path file(payload.file);
  if (!file.is_absolute()) payload.file = (fs::path(path).parent_path() / file).string();
  return payload;
}

void requireData(const std::string& path, const std::string& format, const std::string& declared,
                 std::int64_t samples, std::int64_t sampleBytes, Encoding encoding,
                 std::int64_t available, const std::string& where) {
  if (available < 0) return;
  const std::int64_t bytes = times(samples, sampleBytes);
  std::string need;
  bool fits = true;
  switch (encoding) {
    case Encoding::Binary:
      fits = bytes <= available;
      need = grouped(bytes) + " bytes";
      break;
    case Encoding::ExactBinary:
      fits = bytes == available;
      need = grouped(bytes) + " bytes";
      break;
    case Encoding::Hex:
      fits = times(bytes, 2) <= available;
      need = grouped(times(bytes, 2)) + " hex digits";
      break;
    case Encoding::Ascii:
      // n values need at least n digits and n - 1 separators.
      fits = samples <= 0 || times(samples, 2) - 1 <= available;
      need = "at least " + grouped(std::max<std::int64_t>(0, times(samples, 2) - 1)) +
             " characters of text";
      break;
    case Encoding::Deflate:
      fits = bytes <= times(available, kMaxDeflateRatio);
      need =
          grouped(bytes) + " bytes, more than " + grouped(available) + " compressed bytes can hold";
      break;
    case Encoding::Unknown:
      return;
  }
  if (fits) return;
  throw Error("cannot read " + path + " as " + format + ": the header declares " + declared + " (" +
              need + "), but " + where + " holds " + (available < bytes ? "only " : "") +
              grouped(available) + " bytes; the file is " +
              (available < bytes ? "truncated" : "longer than declared") +
              " or its header is wrong");
}

}  // namespace mfadvr::headers
