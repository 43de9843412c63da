// The GL side of drawing ParticleSprites: one instanced quad per sprite, whose fragment shader
// fades the sprite's colour out from its centre; the alpha-blended sprites first, then the
// additive ones with their own blending.
#pragma once

#include <string>

#include "gl_functions.h"
#include "particle_sprites.h"

namespace render {

class SpriteProgram {
 public:
  /// Builds the program and its buffers; the unit quad comes from `quad_buffer` (a triangle
  /// strip of four corners). False with `error` set when something fails.
  bool Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error);
  /// Frees what Create made (GL ignores names never made).
  void Destroy(const GlFunctions& fn);

  /// Draws the sprites over what the bound framebuffer holds, setting the blending each group
  /// needs and leaving the usual alpha blending on; nothing, not even a state change, when
  /// there are none. `view_half_size` in metres.
  void Draw(const GlFunctions& fn, const ParticleSprites& sprites, float view_half_width,
            float view_half_height);

 private:
  // Uploads and draws one group with the blending already set.
  void DrawGroup(const GlFunctions& fn, const std::vector<SpriteInstance>& group);

  GLuint program_ = 0;
  GLint view_half_size_location_ = -1;
  GLuint vertex_array_ = 0;
  GLuint instance_buffer_ = 0;
};

}  // namespace render
