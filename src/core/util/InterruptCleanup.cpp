#include "core/util/InterruptCleanup.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace mfadvr {
namespace {

// Fixed storage, so that the signal handler only reads memory and calls unlink (both
// async-signal-safe). A slot's path is written before `used` is set and cleared after.
constexpr int kSlots = 16;
constexpr size_t kPathBytes = 4096;
char paths[kSlots][kPathBytes];
std::atomic<bool> claimed[kSlots];  // owned by a registration
std::atomic<bool> used[kSlots];     // its path is complete: the handler removes it

void onSignal(int signal) {
  for (int s = 0; s < kSlots; ++s)
    if (used[s].load()) ::unlink(paths[s]);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

}  // namespace

InterruptCleanup::InterruptCleanup(const std::string& path) {
  if (path.size() >= kPathBytes) return;
  for (int s = 0; s < kSlots; ++s) {
    // Claim a free slot: its path is written while the handler still skips it.
    bool expected = false;
    if (!claimed[s].compare_exchange_strong(expected, true)) continue;
    std::memcpy(paths[s], path.c_str(), path.size() + 1);
    used[s].store(true);
    slot_ = s;
    return;
  }
}

InterruptCleanup::~InterruptCleanup() {
  release();
}

void InterruptCleanup::release() {
  if (slot_ < 0) return;
  used[slot_].store(false);
  claimed[slot_].store(false);
  slot_ = -1;
}

void removeFilesOnInterrupt() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(signal, &action, nullptr);
}

}  // namespace mfadvr
