#pragma once
// Debian's VTK 9.1 renders through an X window even off screen, and aborts the process when it
// cannot open the display. Check first, so that the user gets an mfadvr::Error instead.

namespace mfadvr {

// Throws mfadvr::Error, saying to run under `xvfb-run -a`, when no X display can be opened.
// Does nothing when VTK was built without X.
void requireRenderDisplay();

}  // namespace mfadvr
