// Box2D 2.4.1 (Debian's libbox2d-dev) behind the benchmark's engine interface: 8 velocity and
// 3 position iterations (its documented recommendation), warm starting and continuous on, no sleep;
// revolute joints through b2RevoluteJointDef::Initialize.
#include <box2d/box2d.h>

#include <memory>
#include <string>
#include <vector>

#include "bench/peers/peer_engines.h"

namespace peers {

namespace {

constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;

class Box2dEngine : public PhysicsEngine {
 public:
  std::string Name() const override { return "Box2D 2.4.1"; }

  std::string Settings(const SceneSpec&) const override {
    return std::to_string(kVelocityIterations) + " velocity / " + std::to_string(kPositionIterations) +
           " position iterations, float";
  }

  void Build(const SceneSpec& scene) override {
    bodies_.clear();
    world_ = std::make_unique<b2World>(b2Vec2(static_cast<float>(scene.gravity.x), static_cast<float>(scene.gravity.y)));
    world_->SetAllowSleeping(false);
    dt_ = static_cast<float>(scene.dt);
    for (const BodySpec& spec : scene.bodies) {
      b2BodyDef def;
      def.type = spec.is_static ? b2_staticBody : b2_dynamicBody;
      def.position.Set(static_cast<float>(spec.position.x), static_cast<float>(spec.position.y));
      def.linearVelocity.Set(static_cast<float>(spec.velocity.x), static_cast<float>(spec.velocity.y));
      def.fixedRotation = !scene.rotation;
      def.allowSleep = false;
      b2Body* body = world_->CreateBody(&def);
      b2FixtureDef fixture;
      fixture.density = 1.0f;
      fixture.friction = static_cast<float>(scene.friction);
      fixture.restitution = static_cast<float>(scene.restitution);
      fixture.filter.groupIndex = static_cast<int16>(-spec.group);
      b2PolygonShape box;
      b2CircleShape circle;
      if (spec.kind == Kind::kBox) {
        // Box2D rounds every polygon by b2_polygonRadius (1 cm) and collides the rounded outline:
        // a box that much smaller has the scene's outline (boxes would otherwise rest 1.5 cm apart).
        const float hx = static_cast<float>(spec.half.x) - b2_polygonRadius;
        const float hy = static_cast<float>(spec.half.y) - b2_polygonRadius;
        if (spec.as_polygon) {
          // The same square through the general polygon path (b2PolygonShape::Set computes its hull).
          const b2Vec2 corners[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
          box.Set(corners, 4);
        } else {
          box.SetAsBox(hx, hy);
        }
        fixture.shape = &box;
      } else {
        circle.m_radius = static_cast<float>(spec.radius);
        fixture.shape = &circle;
      }
      body->CreateFixture(&fixture);
      if (!spec.is_static) {
        b2MassData mass;
        mass.mass = static_cast<float>(spec.mass);
        mass.center.SetZero();
        mass.I = static_cast<float>(spec.inertia);
        body->SetMassData(&mass);
      }
      bodies_.push_back(body);
    }
    for (const JointSpec& j : scene.joints) {
      b2RevoluteJointDef def;  // collideConnected false by default: the pair stops colliding, as in ballbox
      def.Initialize(bodies_[j.body_a], bodies_[j.body_b],
                     b2Vec2(static_cast<float>(j.anchor.x), static_cast<float>(j.anchor.y)));
      world_->CreateJoint(&def);
    }
  }

  void Step() override { world_->Step(dt_, kVelocityIterations, kPositionIterations); }

  std::size_t JointCount() const override { return static_cast<std::size_t>(world_->GetJointCount()); }

  void Read(std::vector<State>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const b2Body* b = bodies_[i];
      out[i] = {{b->GetPosition().x, b->GetPosition().y},
                {b->GetLinearVelocity().x, b->GetLinearVelocity().y},
                b->GetAngle(),
                b->GetAngularVelocity()};
    }
  }

 private:
  std::unique_ptr<b2World> world_;
  std::vector<b2Body*> bodies_;
  float dt_ = 1.0f / 60.0f;
};

}  // namespace

std::unique_ptr<PhysicsEngine> MakeBox2dEngine() { return std::make_unique<Box2dEngine>(); }

}  // namespace peers
