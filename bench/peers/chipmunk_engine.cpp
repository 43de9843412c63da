// Chipmunk 7.0.3 (Debian's libchipmunk-dev) behind the benchmark's engine interface: 10 solver
// iterations (its default), collision slop 5 mm like ballbox and Box2D, the default bounding-box tree;
// revolute joints as pivot joints.
#include <chipmunk/chipmunk.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/peers/peer_engines.h"

namespace peers {

namespace {

constexpr int kIterations = 10;
// Chipmunk's default slop is 0.1 (it is unit-free); the scenes are in metres.
constexpr double kCollisionSlop = 0.005;

// Debian's libchipmunk is built without NDEBUG, so its assertions run, and it announces that on
// stdout at the first cpSpaceNew. The tables go to stdout: the announcement is sent to /dev/null
// once, and the settings say it instead.
cpSpace* NewSpace() {
  static bool announced = false;
  if (announced) return cpSpaceNew();
  announced = true;
  std::fflush(stdout);
  const int saved = dup(STDOUT_FILENO), null = open("/dev/null", O_WRONLY);
  if (saved < 0 || null < 0) {
    if (saved >= 0) close(saved);
    if (null >= 0) close(null);
    return cpSpaceNew();
  }
  dup2(null, STDOUT_FILENO);
  close(null);
  cpSpace* space = cpSpaceNew();
  std::fflush(stdout);
  dup2(saved, STDOUT_FILENO);
  close(saved);
  return space;
}

class ChipmunkEngine : public PhysicsEngine {
 public:
  ~ChipmunkEngine() override { Free(); }

  std::string Name() const override { return "Chipmunk 7.0.3"; }

  std::string Settings(const SceneSpec&) const override {
    return std::to_string(kIterations) + " iterations, slop 5 mm, double, debug checks on (Debian's build)";
  }

  void Build(const SceneSpec& scene) override {
    Free();
    space_ = NewSpace();
    cpSpaceSetGravity(space_, cpv(scene.gravity.x, scene.gravity.y));
    cpSpaceSetIterations(space_, kIterations);
    cpSpaceSetCollisionSlop(space_, kCollisionSlop);
    dt_ = scene.dt;
    // Chipmunk multiplies the two shapes' friction and elasticity where ballbox and Box2D take
    // the geometric mean and the maximum: with one material per scene, the square roots give the
    // same value for every pair.
    const double friction = std::sqrt(scene.friction), elasticity = std::sqrt(scene.restitution);
    for (const BodySpec& spec : scene.bodies) {
      cpBody* body = nullptr;
      cpShape* shape = nullptr;
      if (spec.is_static) {
        body = cpSpaceGetStaticBody(space_);
        const cpBB box = cpBBNew(spec.position.x - spec.half.x, spec.position.y - spec.half.y,
                                 spec.position.x + spec.half.x, spec.position.y + spec.half.y);
        shape = spec.kind == Kind::kBox ? cpBoxShapeNew2(body, box, 0.0)
                                        : cpCircleShapeNew(body, spec.radius, cpv(spec.position.x, spec.position.y));
      } else {
        body = cpSpaceAddBody(space_, cpBodyNew(spec.mass, scene.rotation ? spec.inertia : INFINITY));
        cpBodySetPosition(body, cpv(spec.position.x, spec.position.y));
        cpBodySetVelocity(body, cpv(spec.velocity.x, spec.velocity.y));
        const cpVect corners[4] = {cpv(-spec.half.x, -spec.half.y), cpv(spec.half.x, -spec.half.y),
                                   cpv(spec.half.x, spec.half.y), cpv(-spec.half.x, spec.half.y)};
        shape = spec.kind == Kind::kCircle ? cpCircleShapeNew(body, spec.radius, cpvzero)
                : spec.as_polygon          ? cpPolyShapeNew(body, 4, corners, cpTransformIdentity, 0.0)
                                           : cpBoxShapeNew(body, 2 * spec.half.x, 2 * spec.half.y, 0.0);
        owned_bodies_.push_back(body);
      }
      cpShapeSetFriction(shape, friction);
      cpShapeSetElasticity(shape, elasticity);
      cpShapeSetFilter(shape, cpShapeFilterNew(static_cast<cpGroup>(spec.group), CP_ALL_CATEGORIES, CP_ALL_CATEGORIES));
      cpSpaceAddShape(space_, shape);
      shapes_.push_back(shape);
      bodies_.push_back(spec.is_static ? nullptr : body);
      static_positions_.push_back(spec.position);
    }
    // Every static shape hangs on the space's one static body, which sits at the origin unturned,
    // so a world point is also its point in that body's frame.
    const auto body_of = [&](std::size_t i) { return bodies_[i] != nullptr ? bodies_[i] : cpSpaceGetStaticBody(space_); };
    for (const JointSpec& j : scene.joints) {
      cpConstraint* joint = cpPivotJointNew(body_of(j.body_a), body_of(j.body_b), cpv(j.anchor.x, j.anchor.y));
      // Chipmunk's constraints leave their bodies colliding unless told; ballbox's and Box2D's do
      // not. (Against the static body this stops the link colliding with every static shape: the
      // joint scenes have only the anchor's.)
      cpConstraintSetCollideBodies(joint, cpFalse);
      cpSpaceAddConstraint(space_, joint);
      constraints_.push_back(joint);
    }
  }

  void Step() override { cpSpaceStep(space_, dt_); }

  std::size_t JointCount() const override {
    std::size_t count = 0;
    cpSpaceEachConstraint(space_, [](cpConstraint*, void* n) { ++*static_cast<std::size_t*>(n); }, &count);
    return count;
  }

  void Read(std::vector<State>& out) const override {
    out.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const cpBody* b = bodies_[i];
      if (b == nullptr) {
        out[i] = {static_positions_[i], {}, 0, 0};
        continue;
      }
      const cpVect p = cpBodyGetPosition(b), v = cpBodyGetVelocity(b);
      out[i] = {{p.x, p.y}, {v.x, v.y}, cpBodyGetAngle(b), cpBodyGetAngularVelocity(b)};
    }
  }

 private:
  // cpSpaceFree leaves the bodies and shapes to their owner.
  void Free() {
    if (space_ == nullptr) return;
    for (cpConstraint* joint : constraints_) {
      cpSpaceRemoveConstraint(space_, joint);
      cpConstraintFree(joint);
    }
    for (cpShape* shape : shapes_) {
      cpSpaceRemoveShape(space_, shape);
      cpShapeFree(shape);
    }
    for (cpBody* body : owned_bodies_) {
      cpSpaceRemoveBody(space_, body);
      cpBodyFree(body);
    }
    cpSpaceFree(space_);
    space_ = nullptr;
    constraints_.clear();
    shapes_.clear();
    owned_bodies_.clear();
    bodies_.clear();
    static_positions_.clear();
  }

  cpSpace* space_ = nullptr;
  double dt_ = 1.0 / 60.0;
  std::vector<cpConstraint*> constraints_;
  std::vector<cpShape*> shapes_;
  std::vector<cpBody*> owned_bodies_;
  std::vector<cpBody*> bodies_;  ///< scene order; nullptr for a static body
  std::vector<Vec2> static_positions_;
};

}  // namespace

std::unique_ptr<PhysicsEngine> MakeChipmunkEngine() { return std::make_unique<ChipmunkEngine>(); }

}  // namespace peers
