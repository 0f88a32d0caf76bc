#include "io/RawVolumeReader.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <memory>
#include <regex>
#include <sstream>

#include "core/util/Error.h"

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

std::unique_ptr<RawVolumeSource> openRawVolume(const std::string& path) {
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
  // Raw files are little-endian by convention.
  return std::make_unique<RawVolumeSource>(RawSampleLayout{path, 0, parsed->dtype, false}, grid);
}

StructuredGrid readRawVolume(const std::string& path) {
  auto source = openRawVolume(path);
  return source->readUnchecked(wholeRange(source->layout().dims));
}

}  // namespace mfadvr
