// An OpenGL 3.3 core context to draw in, behind an interface that includes no GL header: each
// backend (OSMesa offscreen now, a GLFW window later) lives in its own .cpp.
#pragma once

#include <memory>
#include <string>

namespace render {

/// A GL entry point as a context hands it out, before it is cast to its real type.
using GlProc = void (*)();

class GlContext {
 public:
  virtual ~GlContext() = default;
  /// The address of the entry point `name` (e.g. "glClear"), or nullptr when it has none.
  virtual GlProc GetProcAddress(const char* name) const = 0;
};

/// An offscreen OpenGL 3.3 core context (OSMesa), made current on the calling thread. Draw into
/// a framebuffer object: the context's own buffer is a token 1x1. Returns nullptr and sets
/// `error` when Mesa cannot provide one.
std::unique_ptr<GlContext> CreateOffscreenContext(std::string& error);

}  // namespace render
