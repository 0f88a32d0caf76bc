#include "io/VolumeSeriesReader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "core/grid/SampleRange.h"
#include "core/util/Error.h"
#include "io/InflatedPayload.h"
#include "io/NetcdfVolumeReader.h"
#include "io/RawVolumeSource.h"
#include "io/StreamedVolumeReader.h"

namespace mfadvr {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The volume extensions a numbered series may use (header formats first: a folder of .nhdr
// files with their .raw payloads is a series of .nhdr files).
const std::vector<std::string>& seriesExtensions() {
  static const std::vector<std::string> e = {".nrrd", ".nhdr", ".vti",    ".vtk", ".mha",
                                             ".mhd",  ".nii",  ".nii.gz", ".raw"};
  return e;
}

std::string volumeExtension(const std::string& name) {
  const std::string l = lower(name);
  for (const auto& e : seriesExtensions())
    if (endsWith(l, e) && !(e == ".nii" && endsWith(l, ".nii.gz"))) return e;
  return {};
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

double parseTime(const std::string& text, const std::string& where) {
  try {
    size_t used = 0;
    const double t = std::stod(text, &used);
    if (used != text.size() || !std::isfinite(t)) throw std::invalid_argument("");
    return t;
  } catch (const std::exception&) {
    throw Error(where + ": time '" + text + "' is not a finite number");
  }
}

// Relative file names of a collection are relative to the collection's folder.
std::string beside(const fs::path& collection, const std::string& file) {
  const fs::path f(file);
  return (f.is_absolute() ? f : collection.parent_path() / f).string();
}

using Steps = CollectionSteps;

Steps parsePvd(const std::string& text, const std::string& input) {
  if (text.find("<VTKFile") == std::string::npos || text.find("Collection") == std::string::npos)
    throw Error(input + ": not a ParaView collection (no <VTKFile type=\"Collection\">)");
  static const std::regex dataSet(R"(<DataSet\b([^>]*)>)");
  static const std::regex attribute(R"(([A-Za-z_]+)\s*=\s*"([^"]*)\")");
  Steps s;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataSet);
       it != std::sregex_iterator(); ++it) {
    const std::string attrs = (*it)[1];
    std::map<std::string, std::string> a;
    for (auto at = std::sregex_iterator(attrs.begin(), attrs.end(), attribute);
         at != std::sregex_iterator(); ++at)
      a[(*at)[1]] = (*at)[2];
    if (a.count("part") && a["part"] != "0")
      throw Error(input + ": collections of several parts per time step are not supported (part " +
                  a["part"] + ")");
    if (!a.count("file")) throw Error(input + ": a <DataSet> has no file attribute");
    const std::string where = input + ", step " + std::to_string(s.files.size());
    s.times.push_back(a.count("timestep") ? parseTime(a["timestep"], where)
                                          : static_cast<double>(s.files.size()));
    s.files.push_back(beside(input, a["file"]));
  }
  if (s.files.empty()) throw Error(input + ": the collection lists no <DataSet>");
  return s;
}

Steps parseSeriesJson(const std::string& text, const std::string& input) {
  Steps s;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    const nlohmann::json& files = j.at("files");
    if (!files.is_array()) throw Error(input + ": \"files\" must be an array");
    for (const auto& f : files) {
      if (!f.is_object() || !f.contains("name") || !f.at("name").is_string())
        throw Error(input + ": each entry of \"files\" needs a \"name\" string");
      s.files.push_back(beside(input, f.at("name").get<std::string>()));
      if (f.contains("time")) {
        if (!f.at("time").is_number())
          throw Error(input + ": the time of " + s.files.back() + " is not a number");
        s.times.push_back(f.at("time").get<double>());
      } else {
        s.times.push_back(static_cast<double>(s.times.size()));
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(input + ": not a valid .series file (" + e.what() + ")");
  }
  if (s.files.empty()) throw Error(input + ": the series lists no files");
  return s;
}

// One printf conversion %d, %Nd or %0Nd in the file name.
const std::regex& patternConversion() {
  static const std::regex re(R"(%(0?)(\d*)d)");
  return re;
}

bool isPattern(const std::string& input) {
  const std::string name = fs::path(input).filename().string();
  return std::regex_search(name, patternConversion());
}

std::string regexEscape(const std::string& s) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(s, special, R"(\$&)");
}

// Numbered files: by number, with a constant stride.
Steps numberedSteps(const std::string& source, std::map<std::int64_t, std::string> byNumber,
                    const std::string& example) {
  if (byNumber.size() < 2)
    throw Error(source + ": " +
                (byNumber.empty() ? "no file matches" : "only one file matches (" + example + ")") +
                "; a series needs at least two steps");
  std::int64_t stride = 0;
  for (auto it = std::next(byNumber.begin()); it != byNumber.end(); ++it) {
    const std::int64_t d = it->first - std::prev(it)->first;
    stride = stride == 0 ? d : std::min(stride, d);
  }
  Steps s;
  const std::int64_t first = byNumber.begin()->first, last = byNumber.rbegin()->first;
  for (std::int64_t n = first; n <= last; n += stride) {
    const auto it = byNumber.find(n);
    if (it == byNumber.end())
      throw Error(source + ": step " + std::to_string(n) + " is missing (the files run from " +
                  std::to_string(first) + " to " + std::to_string(last) + " in steps of " +
                  std::to_string(stride) + ")");
    s.files.push_back(it->second);
    s.times.push_back(static_cast<double>(n));
  }
  if (static_cast<std::int64_t>(s.files.size()) != static_cast<std::int64_t>(byNumber.size()))
    throw Error(source +
                ": the file numbers are not evenly spaced; list the steps in a .pvd or "
                ".series file");
  return s;
}

Steps readPattern(const std::string& input) {
  const fs::path p(input);
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  const std::string name = p.filename().string();
  std::smatch m;
  std::regex_search(name, m, patternConversion());
  const std::string prefix = m.prefix(), suffix = m.suffix();
  if (std::regex_search(suffix, patternConversion()))
    throw Error(input + ": a series pattern takes one %d");
  // Zero-padded widths match at least that many digits; others any number of them.
  std::string digits = "\\d+";
  if (m[1].length() > 0 && m[2].length() > 0) digits = "\\d{" + m[2].str() + ",}";
  std::string expression = "^";
  expression += regexEscape(prefix);
  expression += "(" + digits + ")";
  expression += regexEscape(suffix);
  expression += "$";
  const std::regex files(expression);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw Error(input + ": folder " + dir.string() + " not found");
  std::map<std::int64_t, std::string> byNumber;
  std::string example;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string f = e.path().filename().string();
    std::smatch fm;
    if (!std::regex_match(f, fm, files) || fm[1].length() > 15) continue;
    byNumber[std::stoll(fm[1])] = (p.parent_path() / f).string();
    example = f;
  }
  return numberedSteps(input, std::move(byNumber), example);
}

// A directory's numbered volume files of one (prefix, suffix) group.
std::optional<Steps> readDirectory(const std::string& input, bool strict) {
  std::error_code ec;
  std::map<std::pair<std::string, std::string>, std::map<std::int64_t, std::string>> groups;
  std::set<std::string> extensions;
  bool dicom = false;
  static const std::regex numbered(R"(^(.*?)(\d+)([^0-9]*)$)");
  for (const auto& e : fs::directory_iterator(input, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const std::string f = e.path().filename().string();
    const std::string ext = volumeExtension(f);
    if (lower(f).ends_with(".dcm")) dicom = true;
    if (ext.empty()) continue;
    const std::string stem = f.substr(0, f.size() - ext.size());
    std::smatch m;
    if (!std::regex_match(stem, m, numbered) || m[2].length() > 15) continue;
    extensions.insert(ext);
    groups[{m[1], std::string(m[3]) + f.substr(f.size() - ext.size())}][std::stoll(m[2])] =
        (fs::path(input) / f).string();
  }
  if (dicom || groups.empty()) {
    if (strict) throw Error(input + ": holds no numbered volume files (name_000.nrrd, ...)");
    return std::nullopt;
  }
  // Header formats with their raw payloads beside them: the headers are the series.
  if (extensions.size() > 1 && extensions.count(".raw"))
    for (auto it = groups.begin(); it != groups.end();)
      it = volumeExtension(it->first.second) == ".raw" ? groups.erase(it) : std::next(it);
  if (groups.size() > 1) {
    std::string names;
    for (const auto& [key, files] : groups)
      names += (names.empty() ? "" : ", ") + key.first + "N" + key.second;
    throw Error(
        input + ": holds several numbered series (" + names +
        "); name one with a pattern such as " +
        (fs::path(input) / (groups.begin()->first.first + "%d" + groups.begin()->first.second))
            .string());
  }
  const auto& only = *groups.begin();
  return numberedSteps(input, only.second, only.second.begin()->second);
}

// The steps of one file that holds them all (StreamedVolumeReader.h, TimeStepsInFile): each
// read a whole volume at a time from its place in the file; gzip-coded steps are inflated once,
// all together, to a temporary file when the first is asked for (memory stays one step's).
class StepsInFileSeries final : public VolumeSeries {
 public:
  StepsInFileSeries(std::string path, TimeStepsInFile steps, const VolumeLoadOptions& options)
      : path_(std::move(path)), steps_(std::move(steps)) {
    steps_.layout.origin = options.origin.value_or(steps_.layout.origin);
    steps_.layout.spacing = options.spacing.value_or(steps_.layout.spacing);
  }
  int size() const override { return static_cast<int>(steps_.times.size()); }
  double time(int step) const override { return steps_.times[static_cast<size_t>(step)]; }
  std::string stepName(int step) const override {
    return "step " + std::to_string(step) + " of " + path_;
  }
  std::string source() const override { return path_; }
  void replaceTimes(std::vector<double> times) { steps_.times = std::move(times); }

  StructuredGrid load(int step) const override {
    RawSampleLayout file = steps_.file;
    if (steps_.gzipAt >= 0) {
      if (!inflated_)
        inflated_ = std::make_unique<TemporaryFile>(inflateToTemporaryFile(
            file.path, steps_.gzipAt, file.offset, steps_.stepBytes * size(), path_));
      file.path = inflated_->path();
      file.offset = 0;
    }
    file.offset += steps_.stepBytes * step;
    RawVolumeSource source(file, steps_.layout);
    StructuredGrid grid = source.read(wholeRange(steps_.layout.dims));
    grid.notes = steps_.layout.notes;
    grid.source = path_;
    return grid;
  }

 private:
  std::string path_;
  TimeStepsInFile steps_;
  mutable std::unique_ptr<TemporaryFile> inflated_;
};

// The time steps of a NetCDF variable, each read when it is asked for.
class NetcdfSeries final : public VolumeSeries {
 public:
  NetcdfSeries(NetcdfVolume volume, const VolumeLoadOptions& options) : volume_(std::move(volume)) {
    volume_.layout.origin = options.origin.value_or(volume_.layout.origin);
    volume_.layout.spacing = options.spacing.value_or(volume_.layout.spacing);
  }
  int size() const override { return static_cast<int>(volume_.times.size()); }
  double time(int step) const override { return volume_.times[static_cast<size_t>(step)]; }
  std::string stepName(int step) const override {
    return "step " + std::to_string(step) + " of " + volume_.path;
  }
  std::string source() const override { return volume_.path; }
  void replaceTimes(std::vector<double> times) { volume_.times = std::move(times); }
  StructuredGrid load(int step) const override { return readNetcdfStep(volume_, step); }

 private:
  NetcdfVolume volume_;
};

// `times` (encode --times) for the `steps` steps of `input`, as many as there are.
std::vector<double> checkedTimes(std::vector<double> times, size_t steps,
                                 const std::string& input) {
  if (times.size() != steps)
    throw Error("--times gives " + std::to_string(times.size()) + " times for the " +
                std::to_string(steps) + " steps of " + input);
  return times;
}

}  // namespace

CollectionSteps parseCollection(const std::string& text, const std::string& path, bool json) {
  return json ? parseSeriesJson(text, path) : parsePvd(text, path);
}

FileVolumeSeries::FileVolumeSeries(std::string source, std::vector<std::string> files,
                                   std::vector<double> times, VolumeLoadOptions options)
    : source_(std::move(source)),
      files_(std::move(files)),
      times_(std::move(times)),
      options_(std::move(options)) {
  if (files_.size() != times_.size())
    throw Error(source_ + ": " + std::to_string(times_.size()) + " times for " +
                std::to_string(files_.size()) + " steps");
}

StructuredGrid FileVolumeSeries::load(int step) const {
  const std::string& f = files_[static_cast<size_t>(step)];
  std::error_code ec;
  if (!fs::exists(f, ec))
    throw Error(source_ + ": step " + std::to_string(step) + " (" + f + ") does not exist");
  return loadStructuredVolume(f, options_);
}

bool isVolumeSeriesInput(const std::string& input, const FieldSelection& field) {
  const std::string l = lower(input);
  if (endsWith(l, ".pvd") || endsWith(l, ".series")) return true;
  if (l.rfind("builtin:", 0) == 0) return false;
  std::error_code ec;
  if (fs::is_regular_file(input, ec)) {
    // A file of several time steps; a damaged header is left to the volume reader's error.
    try {
      if (isNetcdfPath(input)) return describeNetcdfVolume(input, field).times.size() > 1;
      return describeTimeStepsInFile(input).has_value();
    } catch (const Error&) {
      return false;
    }
  }
  if (fs::is_directory(input, ec)) return readDirectory(input, false).has_value();
  return !fs::exists(input, ec) && isPattern(input);
}

std::unique_ptr<VolumeSeries> openVolumeSeries(const std::string& input,
                                               const VolumeLoadOptions& options,
                                               std::optional<std::vector<double>> times) {
  const std::string l = lower(input);
  std::error_code ec;
  if (fs::is_regular_file(input, ec) && isNetcdfPath(input)) {
    auto series =
        std::make_unique<NetcdfSeries>(describeNetcdfVolume(input, options.field), options);
    if (series->size() < 2) throw Error(input + ": holds one volume, not a time series");
    if (times)
      series->replaceTimes(
          checkedTimes(std::move(*times), static_cast<size_t>(series->size()), input));
    return series;
  }
  if (fs::is_regular_file(input, ec) && !endsWith(l, ".pvd") && !endsWith(l, ".series")) {
    if (options.field.chosen())
      throw Error(input + ": a file of time steps holds one field; --field does not apply");
    std::optional<TimeStepsInFile> inFile = describeTimeStepsInFile(input);
    if (!inFile) throw Error(input + ": holds one volume, not a time series");
    auto series = std::make_unique<StepsInFileSeries>(input, std::move(*inFile), options);
    if (times)
      series->replaceTimes(
          checkedTimes(std::move(*times), static_cast<size_t>(series->size()), input));
    return series;
  }
  Steps s;
  if (endsWith(l, ".pvd"))
    s = parsePvd(readText(input), input);
  else if (endsWith(l, ".series"))
    s = parseSeriesJson(readText(input), input);
  else if (fs::is_directory(input, ec))
    s = *readDirectory(input, true);
  else if (isPattern(input))
    s = readPattern(input);
  else
    throw Error(input +
                ": not a time series (a .pvd or .series file, a name_%03d pattern or a "
                "folder of numbered volumes)");
  if (times) s.times = checkedTimes(std::move(*times), s.files.size(), input);
  return std::make_unique<FileVolumeSeries>(input, std::move(s.files), std::move(s.times), options);
}

}  // namespace mfadvr
