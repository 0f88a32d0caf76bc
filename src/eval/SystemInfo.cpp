#include "eval/SystemInfo.h"

#include <vtkVersion.h>
#include <Eigen/Core>
#include <fstream>
#include <thread>

#include <oneapi/tbb/version.h>

namespace mfadvr::eval {

namespace {

// The value of the first line of `path` that starts with `key`, after its separator.
std::string fieldOf(const std::string& path, const std::string& key, char separator) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      const auto at = line.find(separator);
      if (at == std::string::npos) continue;
      std::string v = line.substr(at + 1);
      v.erase(0, v.find_first_not_of(" \t\""));
      while (!v.empty() && (v.back() == '"' || v.back() == ' ')) v.pop_back();
      return v;
    }
  return "unknown";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> systemDescription() {
  std::string memory = fieldOf("/proc/meminfo", "MemTotal", ':');
  return {
      {"CPU", fieldOf("/proc/cpuinfo", "model name", ':')},
      {"hardware threads", std::to_string(std::thread::hardware_concurrency())},
      {"memory", memory},
      {"OS", fieldOf("/etc/os-release", "PRETTY_NAME", '=')},
      {"compiler", std::string(
#if defined(__clang__)
                       "clang "
#elif defined(__GNUC__)
                       "gcc "
#endif
                       ) +
                       __VERSION__},
      {"mfadvr", MFADVR_VERSION},
      {"VTK", vtkVersion::GetVTKVersion()},
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION)},
      {"oneTBB", std::to_string(TBB_VERSION_MAJOR) + "." + std::to_string(TBB_VERSION_MINOR)},
  };
}

}  // namespace mfadvr::eval
