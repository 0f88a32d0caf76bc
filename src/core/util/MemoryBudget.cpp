#include "core/util/MemoryBudget.h"

#include <sys/resource.h>

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/util/Error.h"

namespace mfadvr {

namespace {

std::int64_t memAvailable() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::int64_t kb = 0;
  std::string unit;
  while (meminfo >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<std::int64_t>(pages) * size : 0;
}

// A number from a one-line file (cgroup v2 files); -1 for "max", a missing file or other text.
std::int64_t numberIn(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text)) return -1;
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  return ec == std::errc() && end == text.data() + text.size() ? v : -1;
}

// What the limits of this process's cgroup v2 and of the groups above it (a container's or a
// batch job's) let it still allocate; -1 when none is set.
std::int64_t cgroupHeadroom() {
  std::ifstream self("/proc/self/cgroup");
  std::string line, group;
  while (std::getline(self, line))
    if (line.rfind("0::", 0) == 0) group = line.substr(3);
  if (group.empty() || group[0] != '/') group.assign(1, '/');
  std::int64_t headroom = -1;
  for (;;) {
    const std::string dir = "/sys/fs/cgroup" + (group == "/" ? std::string() : group);
    const std::int64_t limit = numberIn(dir + "/memory.max");
    if (limit >= 0) {
      const std::int64_t left = std::max<std::int64_t>(
          0, limit - std::max<std::int64_t>(numberIn(dir + "/memory.current"), 0));
      if (headroom < 0 || left < headroom) headroom = left;
    }
    if (group == "/") break;
    group.resize(std::max<size_t>(group.rfind('/'), 1));  // the parent ("/x" -> "/")
  }
  return headroom;
}

}  // namespace

std::int64_t parseByteCount(const std::string& text) {
  double v = 0.0;
  const char* end = text.data() + text.size();
  // "512MB" as "512M"; a bare "B" after the number is bytes.
  if (end != text.data() && (end[-1] == 'B' || end[-1] == 'b')) --end;
  const auto [at, ec] = std::from_chars(text.data(), end, v);
  double scale = 1.0;
  if (ec == std::errc() && at + 1 == end) {
    switch (*at) {
      case 'K':
      case 'k':
        scale = 1e3;
        break;
      case 'M':
      case 'm':
        scale = 1e6;
        break;
      case 'G':
      case 'g':
        scale = 1e9;
        break;
      case 'T':
      case 't':
        scale = 1e12;
        break;
      default:
        scale = 0.0;
    }
  } else if (ec != std::errc() || at != end) {
    scale = 0.0;
  }
  const double bytes = v * scale;
  if (!(scale > 0.0 && bytes >= 1.0 && bytes < 9e18))
    throw Error("'" + text +
                "' is not a memory size (bytes, or a number with K, M, G or T: 8G, 512MB)");
  return static_cast<std::int64_t>(bytes);
}

std::int64_t availableMemoryBytes() {
  std::int64_t available = memAvailable();
  const std::int64_t headroom = cgroupHeadroom();
  if (headroom >= 0 && (available <= 0 || headroom < available)) available = headroom;
  if (const char* limit = std::getenv("MFADVR_MEMORY_LIMIT"); limit && *limit) {
    std::int64_t bytes = 0;
    try {
      bytes = parseByteCount(limit);
    } catch (const Error& e) {
      throw Error(std::string("MFADVR_MEMORY_LIMIT: ") + e.what());
    }
    if (available <= 0 || bytes < available) available = bytes;
  }
  return available;
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
