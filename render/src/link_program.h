// The GL side of drawing LinkLines: a program that draws each segment as an anti-aliased
// capsule on an instanced quad, first every rim, then every line, so that where the segments of
// a zig-zag meet no rim cuts into a line.
#pragma once

#include <string>

#include "gl_functions.h"
#include "link_lines.h"

namespace render {

class LinkProgram {
 public:
  /// Builds the program and its buffers; the unit quad comes from `quad_buffer` (a triangle
  /// strip of four corners). False with `error` set when something fails.
  bool Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error);
  /// Frees what Create made (GL ignores names never made).
  void Destroy(const GlFunctions& fn);

  /// Draws the lines over what the framebuffer holds (blending set up by the caller); nothing,
  /// not even a state change, when there are none. `view_half_size` in metres.
  void Draw(const GlFunctions& fn, const LinkLines& lines, float view_half_width,
            float view_half_height, float pixel_size);

 private:
  GLuint program_ = 0;
  GLint view_half_size_location_ = -1;
  GLint pixel_size_location_ = -1;
  GLint grow_location_ = -1;
  GLint halo_location_ = -1;
  GLint halo_color_location_ = -1;
  GLuint vertex_array_ = 0;
  GLuint instance_buffer_ = 0;
};

}  // namespace render
