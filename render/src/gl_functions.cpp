// Fills the GL function table through the context, entry point by entry point.
#include "gl_functions.h"

namespace render {

bool LoadGlFunctions(const GlContext& context, GlFunctions& gl, std::string& error) {
#define BALLBOX_GL_LOAD(type, name)                                          \
  gl.name = reinterpret_cast<type>(context.GetProcAddress("gl" #name));      \
  if (gl.name == nullptr) {                                                  \
    error = "the OpenGL context has no entry point gl" #name;                \
    return false;                                                            \
  }
  BALLBOX_GL_FUNCTIONS(BALLBOX_GL_LOAD)
#undef BALLBOX_GL_LOAD
  return true;
}

}  // namespace render
