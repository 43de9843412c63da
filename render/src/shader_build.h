// Compiling and linking a GLSL program, with the compiler's log as the error.
#pragma once

#include <string>

#include "gl_functions.h"

namespace render {

/// Builds `program` from the two sources. `name` ("" or e.g. "part") tells in `error` which
/// program failed, with the compiler's or linker's log.
bool BuildProgram(const GlFunctions& fn, const char* vertex_source, const char* fragment_source,
                  const std::string& name, GLuint& program, std::string& error);

}  // namespace render
