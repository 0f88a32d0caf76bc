#include "core/util/MemoryBudget.h"

#include <sys/resource.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

std::int64_t availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::int64_t kb = 0;
  std::string unit;
  while (meminfo >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::int64_t>(pages) * size : 0;
}

std::string formatBytes(std::int64_t bytes) {
  char b[32];
  const double v = static_cast<double>(bytes);
  if (v >= 1e9)
    std::snprintf(b, sizeof b, "%.1f GB", v / 1e9);
  else if (v >= 1e6)
    std::snprintf(b, sizeof b, "%.0f MB", v / 1e6);
  else
    std::snprintf(b, sizeof b, "%.0f KB", v / 1e3);
  return b;
}

std::int64_t peakResidentBytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::int64_t>(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

void requireMemory(std::int64_t bytes, const std::string& what) {
  const std::int64_t available = availableMemoryBytes();
  if (available <= 0 || bytes <= available) return;
  throw Error(what + " needs about " + formatBytes(bytes) + " of memory; " +
              formatBytes(available) + " are available");
}

}  // namespace mfadvr
