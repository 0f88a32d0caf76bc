#pragma once
// What a job will need, checked against what the machine has before anything is allocated, so
// that a job too large fails at once with a clear message instead of "out of memory" (or the
// kernel's OOM killer) minutes later.
#include <cstdint>
#include <string>

namespace mfadvr {

// Memory the system can give this process now (Linux: MemAvailable of /proc/meminfo; else the
// physical memory); 0 when unknown.
std::int64_t availableMemoryBytes();

// The most memory this process has held so far (Linux: the peak resident set); 0 when unknown.
std::int64_t peakResidentBytes();

// "1.5 GB", "640 MB": for messages.
std::string formatBytes(std::int64_t bytes);

// Throws mfadvr::Error naming `what` and both figures when `bytes` exceeds the available memory
// (nothing happens when that is unknown).
void requireMemory(std::int64_t bytes, const std::string& what);

}  // namespace mfadvr
