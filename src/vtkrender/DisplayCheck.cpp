#include "vtkrender/DisplayCheck.h"

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

#include "core/util/Error.h"

#ifdef MFADVR_VTK_USES_X11
#include <X11/Xlib.h>
#endif

namespace mfadvr {

void requireRenderDisplay() {
#ifdef MFADVR_VTK_USES_X11
  // One connection, opened once and kept for the life of the process. An X server without
  // -noreset (Xvfb as xvfb-run starts it) resets when its last client disconnects, and refuses
  // connections for a moment while it does; VTK aborts on such a refusal. Holding a connection
  // means that no render window of this process closing can trigger a reset before the next
  // one connects. The first attempt retries briefly in case a previous process's disconnect has
  // just started one.
  static std::mutex mutex;
  static Display* display = nullptr;
  const std::lock_guard<std::mutex> lock(mutex);
  if (display) return;
  const char* name = std::getenv("DISPLAY");
  for (int attempt = 0; attempt < 10 && !display; ++attempt) {
    display = XOpenDisplay(nullptr);
    if (!display && name && *name) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (!name || !*name) break;
  }
  if (display) return;
  throw Error(std::string("VTK's renderers need an X display, and none can be opened (DISPLAY=") +
              (name && *name ? name : "unset") +
              "): run under a virtual display, e.g. `xvfb-run -a mfadvr ...`");
#endif
}

}  // namespace mfadvr
