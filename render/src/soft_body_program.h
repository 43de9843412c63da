// The GL side of drawing a SoftBodyMesh: a program that shades each pixel from its signed
// distance to the outline, as the body shaders do (a fill, a darker band inside the edge, an
// edge anti-aliased over one pixel), over plain triangles.
#pragma once

#include <string>

#include "gl_functions.h"
#include "soft_body_mesh.h"

namespace render {

class SoftBodyProgram {
 public:
  /// Builds the program and its buffers. False with `error` set when something fails.
  bool Create(const GlFunctions& fn, std::string& error);
  /// Frees what Create made (GL ignores names never made).
  void Destroy(const GlFunctions& fn);

  /// Draws the mesh over what the framebuffer holds (blending set up by the caller); nothing,
  /// not even a state change, when it is empty. `view_half_size` in metres.
  void Draw(const GlFunctions& fn, const SoftBodyMesh& mesh, float view_half_width,
            float view_half_height, float pixel_size);

 private:
  GLuint program_ = 0;
  GLint view_half_size_location_ = -1;
  GLint pixel_size_location_ = -1;
  GLuint vertex_array_ = 0;
  GLuint vertex_buffer_ = 0;
};

}  // namespace render
