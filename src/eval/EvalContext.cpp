#include "eval/EvalContext.h"

#include <cstdio>
#include <iostream>

#include "core/image/PngFile.h"

namespace mfadvr::eval {

EvalContext::EvalContext(EvalOptions options)
    : options_(std::move(options)), start_(std::chrono::steady_clock::now()) {}

double EvalContext::elapsedSeconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void EvalContext::log(const std::string& line) const {
  if (!options_.progress) return;
  char stamp[32];
  const double s = elapsedSeconds();
  std::snprintf(stamp, sizeof stamp, "[%3d:%02d] ", static_cast<int>(s) / 60,
                static_cast<int>(s) % 60);
  std::cerr << stamp << line << std::endl;
}

std::filesystem::path EvalContext::path(const std::string& relative) const {
  const std::filesystem::path p = options_.out / relative;
  std::filesystem::create_directories(p.parent_path());
  return p;
}

std::string EvalContext::writeImage(const std::string& relative, const Image8& image) const {
  writePng(path(relative).string(), image);
  return relative;
}

std::filesystem::path EvalContext::dataFile(const std::string& name) const {
  if (options_.dataDir.empty()) return {};
  const std::filesystem::path p = options_.dataDir / name;
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) ? p : std::filesystem::path{};
}

std::string EvalContext::missingDataNote(const std::vector<std::string>& names) const {
  if (names.empty()) return {};
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  return "Not found in the data folder (`" + options_.dataDir.string() + "`), skipped: " + list +
         ".\n\n";
}

}  // namespace mfadvr::eval
