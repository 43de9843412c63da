// Compiling and linking a GLSL program, with the compiler's log as the error; the per-instance
// attributes of the instanced programs.
#pragma once

#include <cstddef>
#include <string>

#include "gl_functions.h"

namespace render {

/// Builds `program` from the two sources. `name` ("" or e.g. "part") tells in `error` which
/// program failed, with the compiler's or linker's log.
bool BuildProgram(const GlFunctions& fn, const char* vertex_source, const char* fragment_source,
                  const std::string& name, GLuint& program, std::string& error);

/// A new vertex array, left bound, whose attribute 0 is the unit quad's corners in `quad_buffer`
/// (two floats each): the shape every instanced program draws.
GLuint NewQuadArray(const GlFunctions& fn, GLuint quad_buffer);

/// NewQuadArray into `vertex_array`, and a new per-instance buffer into `instance_buffer`, left
/// bound for the program's SetInstanceAttribute calls.
void NewInstancedQuad(const GlFunctions& fn, GLuint quad_buffer, GLuint& vertex_array, GLuint& instance_buffer);

/// Points attribute `location` at a field (`offset` bytes in) of the Instance records in the
/// bound buffer, advancing once per instance.
template <typename Instance>
void SetInstanceAttribute(const GlFunctions& fn, GLuint location, GLint size, GLenum type, GLboolean normalized,
                          std::size_t offset) {
  fn.EnableVertexAttribArray(location);
  fn.VertexAttribPointer(location, size, type, normalized, sizeof(Instance), reinterpret_cast<const void*>(offset));
  fn.VertexAttribDivisor(location, 1);
}

}  // namespace render
