// The GL side of drawing a PartBatch: its shader program, vertex array and texture buffer.
#pragma once

#include <string>

#include "gl_functions.h"
#include "part_batch.h"

namespace render {

class PartProgram {
 public:
  /// Builds the program and its buffers; the unit quad comes from `quad_buffer` (a triangle
  /// strip of four corners). False with `error` set when something fails.
  bool Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error);
  /// Frees what Create made (GL ignores names never made).
  void Destroy(const GlFunctions& fn);

  /// The most texels one batch may hold: the texture buffer's limit, and what a float index
  /// reaches exactly.
  std::size_t MaxTexels() const { return max_texels_; }

  /// Draws the batch's instances in order over what the framebuffer holds (blending set up by
  /// the caller). `view_half_size` in metres; `spokes`: circles show their angle.
  void Draw(const GlFunctions& fn, const PartBatch& batch, float view_half_width,
            float view_half_height, float pixel_size, bool spokes);

 private:
  GLuint program_ = 0;
  GLint view_half_size_location_ = -1;
  GLint pixel_size_location_ = -1;
  GLint spokes_location_ = -1;
  GLuint vertex_array_ = 0;
  GLuint instance_buffer_ = 0;
  GLuint texel_buffer_ = 0;
  GLuint texture_ = 0;
  std::size_t max_texels_ = 0;
};

}  // namespace render
