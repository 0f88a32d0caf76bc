#include "io/InputFile.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void requireReadableFile(const std::string& path, const std::string& expected) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error("cannot open " + path + ": it is a directory, expected " + expected);
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error("cannot open " + path + ": " + std::strerror(errno));
  std::fclose(f);
}

void requireNonEmptyFile(const std::string& path, const std::string& expected) {
  // Every reader would fail on it, each in its own words (VTK's: "Premature EOF reading first
  // line!"); a detached header's data file is checked by the header's size checks.
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0 &&
      !ec)
    throw Error("cannot read " + path + ": the file is empty (0 bytes), expected " + expected);
}

std::vector<std::string> legacyVtkHeaderWords(const std::string& path, size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  std::istringstream lines(head);
  std::string line;
  std::vector<std::string> words;
  if (!std::getline(lines, line) || line.rfind("# vtk DataFile", 0) != 0) return words;
  std::getline(lines, line);  // the title, any text
  for (std::string w; words.size() < count && lines >> w;) {
    std::transform(w.begin(), w.end(), w.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    words.push_back(w);
  }
  return words;
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("cannot read " + path + ": " + std::strerror(errno));
  return text.str();
}

bool isNiftiPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".nii" || ext == ".hdr" || ext == ".img") return true;
  return ext == ".gz" && lowerExtension(path.substr(0, path.size() - 3)) == ".nii";
}

}  // namespace mfadvr
