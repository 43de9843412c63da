// Whether a display is there to open a window on, from the environment alone: no window-system
// call, so a machine without one learns it before any window or GL work.
#include <cstdlib>

#include "render/window.h"

namespace render {

bool DisplayConfigured(std::string& reason) {
  // GLFW 3.3 on Debian is built for X11 only (XWayland sets DISPLAY on Wayland desktops).
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || display[0] == '\0') {
    reason = display == nullptr ? "DISPLAY is not set" : "DISPLAY is empty";
    return false;
  }
  return true;
}

}  // namespace render
