// An offscreen GL context and a renderer in it, for the render tests.
#pragma once

#include <catch2/catch.hpp>

#include <memory>
#include <string>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"
#include "render/renderer.h"

namespace testing {

/// The context is created first and destroyed last: the renderer's GL objects live in it.
struct OffscreenGl {
  std::unique_ptr<render::GlContext> context;
  std::unique_ptr<render::Renderer> renderer;
};

inline OffscreenGl MakeOffscreenGl(int width, int height) {
  OffscreenGl gl;
  std::string error;
  gl.context = render::CreateOffscreenContext(error);
  INFO(error);
  REQUIRE(gl.context);
  gl.renderer = render::Renderer::Create(*gl.context, width, height, error);
  INFO(error);
  REQUIRE(gl.renderer);
  return gl;
}

/// One frame of `world` through `camera`, read back.
inline render::Image DrawFrame(OffscreenGl& gl, const engine::World& world, const std::vector<render::Color>& colors,
                               const render::Camera& camera) {
  gl.renderer->Draw(world, colors, camera);
  render::Image image;
  gl.renderer->ReadImage(image);
  REQUIRE(image.width == gl.renderer->Width());
  REQUIRE(image.height == gl.renderer->Height());
  REQUIRE(image.rgb.size() == static_cast<std::size_t>(image.width * image.height * 3));
  return image;
}

/// A world where nothing falls, turning or not: what a frame shows is where bodies were put.
inline engine::WorldDef Still(bool rotation) {
  engine::WorldDef def;
  def.gravity = {0.0, 0.0};
  def.rotation = rotation;
  return def;
}

}  // namespace testing
