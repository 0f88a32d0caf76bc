#pragma once
// Files to remove when the program is interrupted (Ctrl-C, SIGTERM, SIGHUP): the temporary file
// of an atomic write and the inflated copy of compressed input, which can be gigabytes for an
// out-of-core encode. Destructors remove them on every other way out; a signal skips those, so
// the program's entry point installs removeFilesOnInterrupt() and the owners register here.
#include <string>

namespace mfadvr {

// A registered path (up to a fixed number at once; a path past that, or longer than the slot,
// is simply not removed on interrupt). Unregistering is the owner's job, before it renames or
// removes the file itself.
class InterruptCleanup {
 public:
  explicit InterruptCleanup(const std::string& path);
  ~InterruptCleanup();
  InterruptCleanup(const InterruptCleanup&) = delete;
  InterruptCleanup& operator=(const InterruptCleanup&) = delete;
  // Forgets the path (the file was committed or removed).
  void release();

 private:
  int slot_ = -1;
};

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the registered files, then end
// the program as the signal would have.
void removeFilesOnInterrupt();

}  // namespace mfadvr
