#pragma once
// In sanitizer builds, LeakSanitizer ignores what the calling thread allocates while one of
// these is alive. It wraps the calls into VTK's OpenGL window (rendering, read-back, closing):
// Mesa, GLX and X11 keep process-lifetime allocations there that they never free, and their
// drivers are unloaded before the leak check, so that a suppressions file cannot name them.
// Our own code outside these calls stays checked. In other builds it does nothing.
#if defined(__SANITIZE_ADDRESS__)
#define MFADVR_HAS_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define MFADVR_HAS_LSAN 1
#endif
#endif

#ifdef MFADVR_HAS_LSAN
#include <sanitizer/lsan_interface.h>
#endif

namespace mfadvr {

class LeakCheckPause {
 public:
#ifdef MFADVR_HAS_LSAN
  LeakCheckPause() {
    __lsan_disable();
  }
  ~LeakCheckPause() {
    __lsan_enable();
  }
#else
  LeakCheckPause() {}
#endif
  LeakCheckPause(const LeakCheckPause&) = delete;
  LeakCheckPause& operator=(const LeakCheckPause&) = delete;
};

}  // namespace mfadvr
