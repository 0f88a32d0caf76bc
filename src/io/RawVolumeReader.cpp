#include "io/RawVolumeReader.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <regex>
#include <sstream>

#include "core/util/Error.h"
#include "core/util/MemoryBudget.h"

namespace mfadvr {
namespace {

struct SampleType {
  const char* name;
  int size;
};

constexpr SampleType kSampleTypes[] = {{"uint8", 1},  {"int8", 1},  {"uint16", 2},  {"int16", 2},
                                       {"uint32", 4}, {"int32", 4}, {"float32", 4}, {"float64", 8}};

std::string joinedSampleTypes() {
  std::string out;
  for (const auto& t : rawSampleTypes()) out += (out.empty() ? "" : ", ") + t;
  return out;
}

std::string conventionText() {
  return "a .raw file carries no header, so its name must say the grid size and sample type: "
         "NAME_XxYxZ_TYPE.raw (e.g. fuel_64x64x64_uint8.raw), X varying fastest, "
         "little-endian, TYPE one of " +
         joinedSampleTypes();
}

// Raw files are little-endian by convention; only a big-endian host has to swap.
template <typename T>
T loadLittleEndian(const unsigned char* bytes) {
  unsigned char buf[sizeof(T)];
  if constexpr (std::endian::native == std::endian::little) {
    std::memcpy(buf, bytes, sizeof(T));
  } else {
    for (size_t b = 0; b < sizeof(T); ++b) buf[b] = bytes[sizeof(T) - 1 - b];
  }
  T value;
  std::memcpy(&value, buf, sizeof(T));
  return value;
}

template <typename T>
void convertSamples(const unsigned char* bytes, size_t count, float* out) {
  for (size_t n = 0; n < count; ++n)
    out[n] = static_cast<float>(loadLittleEndian<T>(bytes + n * sizeof(T)));
}

void convertSamples(const std::string& dtype, const unsigned char* bytes, size_t count,
                    float* out) {
  if (dtype == "uint8") return convertSamples<std::uint8_t>(bytes, count, out);
  if (dtype == "int8") return convertSamples<std::int8_t>(bytes, count, out);
  if (dtype == "uint16") return convertSamples<std::uint16_t>(bytes, count, out);
  if (dtype == "int16") return convertSamples<std::int16_t>(bytes, count, out);
  if (dtype == "uint32") return convertSamples<std::uint32_t>(bytes, count, out);
  if (dtype == "int32") return convertSamples<std::int32_t>(bytes, count, out);
  if (dtype == "float32") return convertSamples<float>(bytes, count, out);
  if (dtype == "float64") return convertSamples<double>(bytes, count, out);
  throw Error("internal: no conversion for raw sample type " + dtype);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

const std::vector<std::string>& rawSampleTypes() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& t : kSampleTypes) v.emplace_back(t.name);
    return v;
  }();
  return names;
}

int rawSampleSize(const std::string& dtype) {
  for (const auto& t : kSampleTypes)
    if (dtype == t.name) return t.size;
  return 0;
}

std::optional<RawVolumeName> parseRawVolumeName(const std::string& path) {
  const std::string file = std::filesystem::path(path).filename().string();
  // Greedy NAME so that a name which itself contains _AxBxC_ still takes the last one.
  static const std::regex pattern(
      R"(^(.+)_([0-9]+)[xX]([0-9]+)[xX]([0-9]+)_([A-Za-z0-9]+)\.[rR][aA][wW]$)");
  std::smatch m;
  if (!std::regex_match(file, m, pattern)) return std::nullopt;
  RawVolumeName out;
  out.name = m[1].str();
  for (int a = 0; a < 3; ++a) {
    const std::string digits = m[a + 2].str();
    const auto [end, ec] =
        std::from_chars(digits.data(), digits.data() + digits.size(), out.dims[a]);
    if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  }
  out.dtype = m[5].str();
  std::transform(out.dtype.begin(), out.dtype.end(), out.dtype.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

StructuredGrid readRawVolume(const std::string& path) {
  const auto parsed = parseRawVolumeName(path);
  if (!parsed) throw Error(path + ": not a recognised raw volume name; " + conventionText());
  const int sampleSize = rawSampleSize(parsed->dtype);
  if (sampleSize == 0) {
    throw Error(path + ": unknown sample type '" + parsed->dtype +
                "' in the file name; expected one of " + joinedSampleTypes());
  }
  const Index3& dims = parsed->dims;
  std::int64_t expectedBytes = sampleSize;
  for (int a = 0; a < 3; ++a) {
    if (dims[a] < 1) {
      throw Error(path + ": the file name gives a grid of " + std::to_string(dims[0]) + "x" +
                  std::to_string(dims[1]) + "x" + std::to_string(dims[2]) +
                  " samples; every dimension must be at least 1");
    }
    if (__builtin_mul_overflow(expectedBytes, dims[a], &expectedBytes))
      throw Error(path + ": the grid size in the file name is too large");
  }

  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw Error("cannot open " + path + ": " + std::strerror(errno));
  std::error_code ec;
  const auto fileBytes = std::filesystem::file_size(path, ec);
  if (ec) throw Error("cannot read the size of " + path + ": " + ec.message());
  if (static_cast<std::uintmax_t>(expectedBytes) != fileBytes) {
    std::ostringstream m;
    m << path << ": file size is " << fileBytes << " bytes, but the name promises " << dims[0]
      << "x" << dims[1] << "x" << dims[2] << " " << parsed->dtype << " samples = " << expectedBytes
      << " bytes (raw files have no header, so the sizes must match exactly)";
    throw Error(m.str());
  }

  StructuredGrid grid;
  grid.dims = dims;
  grid.source = path;
  grid.sampleType = parsed->dtype;
  grid.inputBytes = expectedBytes;
  requireMemory(std::int64_t(sizeof(float)) * grid.sampleCount(),
                "reading " + path + " (its samples are held as float32)");
  grid.values.resize(static_cast<size_t>(grid.sampleCount()));

  // Chunked so that a large volume does not need a second full-size byte buffer.
  constexpr size_t kChunkSamples = size_t{1} << 20;
  std::vector<unsigned char> buffer(kChunkSamples * static_cast<size_t>(sampleSize));
  size_t done = 0;
  while (done < grid.values.size()) {
    const size_t count = std::min(kChunkSamples, grid.values.size() - done);
    const size_t want = count * static_cast<size_t>(sampleSize);
    if (std::fread(buffer.data(), 1, want, file.get()) != want) {
      const std::string why = std::ferror(file.get()) ? std::strerror(errno) : "unexpected end";
      throw Error("cannot read " + path + ": " + why);
    }
    convertSamples(parsed->dtype, buffer.data(), count, grid.values.data() + done);
    done += count;
  }
  return grid;
}

}  // namespace mfadvr
