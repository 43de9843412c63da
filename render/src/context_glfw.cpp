// The window backend through GLFW (X11 on Debian): a window, its GL 3.3 core context and its
// input. GLFW_INCLUDE_NONE keeps <GL/gl.h> out; GL calls go through the renderer's table only.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <utility>

#include "render/window.h"

namespace render {
namespace {

// GLFW reports failures through a callback rather than return values; keep the last one so
// Open can say what went wrong (e.g. "X11: Failed to open display :77").
std::string& LastGlfwError() {
  static std::string message;
  return message;
}

void RememberGlfwError(int, const char* description) {
  LastGlfwError() = description != nullptr ? description : "unknown GLFW error";
}

class GlfwWindow final : public Window {
 public:
  explicit GlfwWindow(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, OnKey);
    glfwSetMouseButtonCallback(window_, OnMouseButton);
    glfwSetCursorPosCallback(window_, OnCursorMove);
  }
  ~GlfwWindow() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  GlProc GetProcAddress(const char* name) const override {
    return reinterpret_cast<GlProc>(glfwGetProcAddress(name));
  }

  void FramebufferSize(int& width, int& height) const override {
    glfwGetFramebufferSize(window_, &width, &height);
  }

  void SetTitle(const std::string& title) override { glfwSetWindowTitle(window_, title.c_str()); }

  void SwapBuffers() override { glfwSwapBuffers(window_); }

  std::vector<WindowEvent> TakeEvents(double seconds) override {
    // glfwWaitEventsTimeout wants a positive, finite time; a second is long enough to wait
    // for anything here, and NaN or less than nothing means "just look".
    if (seconds > 0.0) {
      glfwWaitEventsTimeout(std::min(seconds, 1.0));
    } else {
      glfwPollEvents();
    }
    if (glfwWindowShouldClose(window_)) {
      // Reported once; the caller decides whether closing ends anything.
      glfwSetWindowShouldClose(window_, GLFW_FALSE);
      WindowEvent close;
      close.type = WindowEvent::Type::kClose;
      events_.push_back(close);
    }
    return std::exchange(events_, {});
  }

 private:
  static GlfwWindow& Self(GLFWwindow* window) {
    return *static_cast<GlfwWindow*>(glfwGetWindowUserPointer(window));
  }

  static void OnKey(GLFWwindow* window, int key, int scancode, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
    WindowEvent event;
    event.type = WindowEvent::Type::kKey;
    event.repeat = action == GLFW_REPEAT;
    if (key == GLFW_KEY_SPACE) {
      event.key = "space";
    } else if (key == GLFW_KEY_ESCAPE) {
      event.key = "escape";
    } else if (key == GLFW_KEY_BACKSPACE) {
      event.key = "backspace";
    } else if (const char* name = glfwGetKeyName(key, scancode); name != nullptr) {
      // GLFW's key tokens name US-layout positions; the key's name is what it types on the
      // user's layout, so "S" means the key marked S everywhere.
      event.key = name;
      std::transform(event.key.begin(), event.key.end(), event.key.begin(),
                     [](unsigned char c) { return c < 0x80 ? std::tolower(c) : c; });
    } else {
      return;
    }
    Self(window).events_.push_back(std::move(event));
  }

  static void OnMouseButton(GLFWwindow* window, int button, int action, int) {
    if (action != GLFW_PRESS && action != GLFW_RELEASE) return;
    WindowEvent event;
    event.type = action == GLFW_PRESS ? WindowEvent::Type::kMouseDown : WindowEvent::Type::kMouseUp;
    event.button = button;
    GlfwWindow& self = Self(window);
    // Where the cursor was when the button changed: the last move reported before it, in event
    // order. glfwGetCursorPos would say where it is by the time events are read, which after a
    // quick press-and-drag is already the drag's end.
    double x = self.cursor_x_;
    double y = self.cursor_y_;
    if (!self.cursor_known_) glfwGetCursorPos(window, &x, &y);
    ToFramebuffer(window, x, y, event);
    self.events_.push_back(std::move(event));
  }

  static void OnCursorMove(GLFWwindow* window, double x, double y) {
    GlfwWindow& self = Self(window);
    self.cursor_known_ = true;
    self.cursor_x_ = x;
    self.cursor_y_ = y;
    std::vector<WindowEvent>& events = self.events_;
    // Only where the cursor ended up matters between two looks: one event, not hundreds.
    if (events.empty() || events.back().type != WindowEvent::Type::kMouseMove) {
      WindowEvent event;
      event.type = WindowEvent::Type::kMouseMove;
      events.push_back(std::move(event));
    }
    ToFramebuffer(window, x, y, events.back());
  }

  // The cursor comes in screen coordinates; pictures are laid out in framebuffer pixels.
  static void ToFramebuffer(GLFWwindow* window, double x, double y, WindowEvent& event) {
    int window_width = 0;
    int window_height = 0;
    int framebuffer_width = 0;
    int framebuffer_height = 0;
    glfwGetWindowSize(window, &window_width, &window_height);
    glfwGetFramebufferSize(window, &framebuffer_width, &framebuffer_height);
    event.x = window_width > 0 ? x * framebuffer_width / window_width : x;
    event.y = window_height > 0 ? y * framebuffer_height / window_height : y;
  }

  GLFWwindow* window_;
  std::vector<WindowEvent> events_;
  bool cursor_known_ = false;  // a move was reported: cursor_x_, cursor_y_ hold where
  double cursor_x_ = 0.0;      // screen coordinates, as GLFW reports them
  double cursor_y_ = 0.0;
};

}  // namespace

bool WindowSupportBuilt() { return true; }

std::unique_ptr<Window> Window::Open(int width, int height, const std::string& title,
                                     Failure& failure, std::string& error) {
  glfwSetErrorCallback(RememberGlfwError);
  LastGlfwError().clear();
  if (glfwInit() != GLFW_TRUE) {
    failure = Failure::kNoDisplay;
    error = LastGlfwError().empty() ? "the window system could not start" : LastGlfwError();
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  // The renderer draws into its own framebuffer object; the window only receives copies.
  glfwWindowHint(GLFW_DEPTH_BITS, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 0);
  glfwWindowHint(GLFW_SAMPLES, 0);
  GLFWwindow* raw = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (raw == nullptr) {
    failure = Failure::kNoContext;
    error = "cannot open a window with an OpenGL 3.3 core context: " +
            (LastGlfwError().empty() ? std::string("GLFW gave no reason") : LastGlfwError());
    glfwTerminate();
    return nullptr;
  }
  glfwMakeContextCurrent(raw);
  // Wait for the display's refresh where the driver can; the game loop paces itself anyway.
  glfwSwapInterval(1);
  failure = Failure::kNone;
  return std::make_unique<GlfwWindow>(raw);
}

}  // namespace render
