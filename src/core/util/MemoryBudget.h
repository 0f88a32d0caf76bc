#pragma once
// What a job will need, checked against what the machine has before anything is allocated, so
// that a job too large fails at once with a clear message instead of "out of memory" (or the
// kernel's OOM killer) minutes later.
#include <cstdint>
#include <string>

namespace mfadvr {

// Memory the system can give this process now: the least of MemAvailable (/proc/meminfo; else
// the physical memory), what the process's cgroup v2 limit leaves (memory.max - memory.current:
// a container's or a batch job's limit) and the environment variable MFADVR_MEMORY_LIMIT (a
// user's cap, e.g. "8G"; an invalid value is an Error); 0 when unknown.
std::int64_t availableMemoryBytes();

// "8G", "512M", "512MB", "1.5e9": bytes (K, M, G, T are powers of 1000, as formatBytes prints
// them; a B after the unit is optional).
// Throws mfadvr::Error for anything else, or for less than one byte.
std::int64_t parseByteCount(const std::string& text);

// The most memory this process has held so far (Linux: the peak resident set); 0 when unknown.
std::int64_t peakResidentBytes();

// "1.5 GB", "640 MB": for messages.
std::string formatBytes(std::int64_t bytes);

// Throws mfadvr::Error naming `what` and both figures when `bytes` exceeds the available memory
// (nothing happens when that is unknown).
void requireMemory(std::int64_t bytes, const std::string& what);

}  // namespace mfadvr
