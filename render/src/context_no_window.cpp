// Stands in for the GLFW window backend in a build without GLFW: `ballbox play` then says so.
#include "render/window.h"

namespace render {

bool WindowSupportBuilt() { return false; }

std::unique_ptr<Window> Window::Open(int, int, const std::string&, Failure& failure,
                                     std::string& error) {
  failure = Failure::kNotBuilt;
  error = "this ballbox was built without GLFW, so it cannot open windows";
  return nullptr;
}

}  // namespace render
