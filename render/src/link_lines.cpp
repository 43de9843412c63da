// Springs as zig-zags and joints as Box2D draws them (body A's centre to its anchor, anchor to
// anchor, anchor to body B's centre, a dot on each anchor), sized in pixels.
#include "link_lines.h"

namespace render {
namespace {

using engine::Vec2;

/// A smaller dot at each end of a spring and at a grab's target.
constexpr double kEndDotPixels = 2.5;

// Hands World::Draw's springs and joints to the lines; bodies are not asked for (shapes off).
class LinkCollector final : public engine::DebugDraw {
 public:
  explicit LinkCollector(LinkLines& lines) : lines_(lines) {}
  void DrawSpring(Vec2 a, Vec2 b) override { lines_.AddSpring(a, b); }
  void DrawJoint(engine::JointType type, Vec2 center_a, Vec2 anchor_a, Vec2 anchor_b,
                 Vec2 center_b) override {
    lines_.AddJoint(type, center_a, anchor_a, anchor_b, center_b);
  }

 private:
  LinkLines& lines_;
};

}  // namespace

void LinkLines::Build(const engine::World& world, const Camera& camera, double pixel_size,
                      LinkLayers layers) {
  instances_.clear();
  origin_ = camera.center;
  pixel_size_ = pixel_size;
  if (!layers.springs && !layers.joints) return;
  engine::DrawOptions options;
  options.shapes = false;
  options.springs = layers.springs;
  options.joints = layers.joints;
  LinkCollector collector(*this);
  world.Draw(collector, options);
}

void LinkLines::AddSpring(Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double length = engine::Length(d);
  // The zig-zag keeps its number of corners as the spring stretches, as a coil keeps its turns;
  // a straight lead at each end shows where it is attached.
  if (length <= 2.0 * pixel_size_) {
    AddSegment(a, b, 0.5 * kLinkLinePixels, kSpringColor);
  } else {
    const Vec2 side = (kSpringAmplitudePixels * pixel_size_ / length) * engine::LeftPerp(d);
    constexpr double kLead = 0.1;  // of the length, at each end
    Vec2 previous = a + kLead * d;
    AddSegment(a, previous, 0.5 * kLinkLinePixels, kSpringColor);
    for (int k = 0; k < kSpringZigs; ++k) {
      const double t = kLead + (1.0 - 2.0 * kLead) * (k + 0.5) / kSpringZigs;
      const Vec2 corner = a + t * d + (k % 2 == 0 ? 1.0 : -1.0) * side;
      AddSegment(previous, corner, 0.5 * kLinkLinePixels, kSpringColor);
      previous = corner;
    }
    const Vec2 lead_end = a + (1.0 - kLead) * d;
    AddSegment(previous, lead_end, 0.5 * kLinkLinePixels, kSpringColor);
    AddSegment(lead_end, b, 0.5 * kLinkLinePixels, kSpringColor);
  }
  AddDot(a, kEndDotPixels, kSpringColor);
  AddDot(b, kEndDotPixels, kSpringColor);
}

void LinkLines::AddJoint(engine::JointType type, Vec2 center_a, Vec2 anchor_a, Vec2 anchor_b,
                         Vec2 center_b) {
  if (type == engine::JointType::kTarget) {
    // The mouse's pull: from the grabbed point to where it is pulled (anchor_a is the target).
    AddSegment(anchor_b, anchor_a, 0.5 * kLinkLinePixels, kGrabColor);
    AddDot(anchor_b, kLinkDotPixels, kGrabColor);
    AddDot(anchor_a, kEndDotPixels, kGrabColor);
    return;
  }
  AddSegment(center_a, anchor_a, 0.5 * kLinkLinePixels, kJointColor);
  AddSegment(anchor_a, anchor_b, 0.5 * kLinkLinePixels, kJointColor);
  AddSegment(anchor_b, center_b, 0.5 * kLinkLinePixels, kJointColor);
  // A revolute or weld joint's anchors coincide: one dot, the hinge.
  AddDot(anchor_a, kLinkDotPixels, kJointColor);
  AddDot(anchor_b, kLinkDotPixels, kJointColor);
}

void LinkLines::AddSegment(Vec2 a, Vec2 b, double radius_pixels, Color color) {
  LinkInstance instance{};
  // Relative to the camera in double before going to float, as the bodies are.
  instance.a[0] = static_cast<float>(a.x - origin_.x);
  instance.a[1] = static_cast<float>(a.y - origin_.y);
  instance.b[0] = static_cast<float>(b.x - origin_.x);
  instance.b[1] = static_cast<float>(b.y - origin_.y);
  instance.radius = static_cast<float>(radius_pixels * pixel_size_);
  instance.color[0] = color.r;
  instance.color[1] = color.g;
  instance.color[2] = color.b;
  instance.color[3] = 255;
  instances_.push_back(instance);
}

void LinkLines::AddDot(Vec2 p, double radius_pixels, Color color) {
  AddSegment(p, p, radius_pixels, color);
}

}  // namespace render
