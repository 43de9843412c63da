// A window with an OpenGL 3.3 core context for `ballbox play`, behind a header with no GL or
// GLFW include: the GLFW backend lives in context_glfw.cpp alone (context_no_window.cpp stands
// in for it in a build without GLFW).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/context.h"

namespace render {

/// What happened in a window, in the order it happened.
struct WindowEvent {
  enum class Type {
    kKey,        ///< a key went down (or repeats while held)
    kMouseDown,  ///< a mouse button went down
    kMouseUp,    ///< a mouse button went up
    kMouseMove,  ///< the cursor moved (successive moves between two TakeEvents come as one)
    kClose,      ///< the user asked the window to close
  };
  Type type = Type::kKey;
  /// kKey: "space", "escape", "backspace", or for a printable key the character it types on the user's
  /// keyboard layout, lower case ("s", "."). Other keys are not reported.
  std::string key;
  bool repeat = false;  ///< kKey: the key is held and the system repeats it
  int button = 0;       ///< kMouseDown, kMouseUp: 0 left, 1 right, 2 middle
  /// Mouse events: where the cursor was, in framebuffer pixels from the top-left corner of the
  /// window's drawing area (continuous: (0, 0) is that corner). Window coordinates are scaled
  /// by framebuffer / window size, so this matches PixelRect on high-DPI screens too.
  double x = 0.0;
  double y = 0.0;
};

/// Whether this build can open windows at all (it was built with GLFW).
bool WindowSupportBuilt();

/// Whether there is a display to open a window on, judged from the environment alone, before
/// any window-system or GL work. False with the reason (e.g. "DISPLAY is not set").
bool DisplayConfigured(std::string& reason);

class Window : public GlContext {
 public:
  /// Why Open failed.
  enum class Failure {
    kNone,
    kNotBuilt,   ///< built without GLFW
    kNoDisplay,  ///< the window system cannot be reached (no X server at DISPLAY)
    kNoContext,  ///< a display, but no window with an OpenGL 3.3 core context on it
  };

  /// Opens a resizable window whose drawing area is `width` × `height` screen coordinates, with
  /// its GL context current on this thread. One window at a time. Returns nullptr and sets
  /// `failure` and `error` (a message without "error: ") when it cannot.
  static std::unique_ptr<Window> Open(int width, int height, const std::string& title,
                                      Failure& failure, std::string& error);
  ~Window() override = default;

  /// The drawing area's size in pixels (may differ from screen coordinates on high-DPI screens).
  virtual void FramebufferSize(int& width, int& height) const = 0;
  virtual void SetTitle(const std::string& title) = 0;
  /// Shows what was drawn into the default framebuffer.
  virtual void SwapBuffers() = 0;
  /// Waits up to `seconds` for input (0: only looks), then returns every event since the last
  /// call. Returns at once when events are already waiting.
  virtual std::vector<WindowEvent> TakeEvents(double seconds) = 0;
};

}  // namespace render
