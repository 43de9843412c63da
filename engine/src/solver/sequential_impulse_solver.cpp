// The sequential-impulse contact solver. Rotation-free: impulses act at the centres (angular terms come with
// rotation). Accumulated impulses are clamped per step, which is what makes Coulomb's cone and
// "push, never pull" hold across passes.
#include "solver/sequential_impulse_solver.h"

#include "solver/pushed_bodies.h"

#include <algorithm>
#include <cmath>

namespace engine::detail {

void PrepareContacts(std::span<const Contact> contacts, std::span<const BodyState> states,
                     std::span<const BodyInfo> infos, double restitution_threshold,
                     std::vector<ImpulseConstraint>* constraints) {
  constraints->clear();
  constraints->reserve(contacts.size());
  for (const Contact& c : contacts) {
    ImpulseConstraint cc;
    cc.a = c.a;
    cc.b = c.b;
    cc.normal = c.manifold.normal;
    cc.inv_mass_sum = infos[c.a].inv_mass + infos[c.b].inv_mass;
    cc.friction = c.friction;
    cc.point_count = c.manifold.point_count;
    const double approach = Dot(states[c.b].velocity - states[c.a].velocity, cc.normal);
    // Bounce only off real impacts: below the threshold a resting body would buzz.
    const double target = approach < -restitution_threshold ? -c.restitution * approach : 0.0;
    for (int i = 0; i < cc.point_count; ++i) cc.points[i] = {target, 0.0, 0.0};
    constraints->push_back(cc);
  }
}

void SolveVelocities(std::span<ImpulseConstraint> constraints, std::span<BodyState> states,
                     std::span<const BodyInfo> infos, int iterations) {
  for (int pass = 0; pass < iterations; ++pass) {
    for (ImpulseConstraint& cc : constraints) {
      BodyState& a = states[cc.a];
      BodyState& b = states[cc.b];
      const double inv_a = infos[cc.a].inv_mass;
      const double inv_b = infos[cc.b].inv_mass;
      const Vec2 n = cc.normal;
      const Vec2 t = LeftPerp(n);
      for (int i = 0; i < cc.point_count; ++i) {
        ImpulsePoint& p = cc.points[i];

        const double tangent_speed = Dot(b.velocity - a.velocity, t);
        const double max_friction = cc.friction * p.normal_impulse;
        const double new_tangent =
            Clamp(p.tangent_impulse - tangent_speed / cc.inv_mass_sum, -max_friction, max_friction);
        const double dt_impulse = new_tangent - p.tangent_impulse;
        p.tangent_impulse = new_tangent;
        a.velocity -= (dt_impulse * inv_a) * t;
        b.velocity += (dt_impulse * inv_b) * t;

        const double normal_speed = Dot(b.velocity - a.velocity, n);
        const double new_normal = std::max(
            p.normal_impulse + (p.target_normal_velocity - normal_speed) / cc.inv_mass_sum, 0.0);
        const double dn_impulse = new_normal - p.normal_impulse;
        p.normal_impulse = new_normal;
        a.velocity -= (dn_impulse * inv_a) * n;
        b.velocity += (dn_impulse * inv_b) * n;
      }
    }
  }
}

void CorrectPositions(std::span<const Contact> contacts, std::span<const Vec2> positions_before,
                      std::span<BodyState> states, std::span<const BodyInfo> infos,
                      double linear_slop, double correction_fraction) {
  for (const Contact& c : contacts) {
    BodyState& a = states[c.a];
    BodyState& b = states[c.b];
    const Vec2 n = c.manifold.normal;
    // Without rotation every point of a body moves alike, so the overlap now is the measured
    // overlap less how far the bodies have since moved apart along the normal.
    const double moved_apart =
        Dot((b.position - positions_before[c.b]) - (a.position - positions_before[c.a]), n);
    double depth = 0.0;
    for (int i = 0; i < c.manifold.point_count; ++i) {
      depth = std::max(depth, c.manifold.points[i].depth - moved_apart);
    }
    const double inv_a = infos[c.a].inv_mass;
    const double inv_b = infos[c.b].inv_mass;
    const double push = correction_fraction * std::max(depth - linear_slop, 0.0) / (inv_a + inv_b);
    a.position -= (push * inv_a) * n;
    b.position += (push * inv_b) * n;
  }
}

void SequentialImpulseSolver::FillAutomaticSettings(WorldDef* def) {
  if (def->velocity_iterations == 0) def->velocity_iterations = 10;
}

void SequentialImpulseSolver::Step(StepContext& context) {
  const WorldDef& def = context.def;
  FreeStep(def.integrator, context.forces, context.states, def.dt, &context.free_motion);
  if (context.StopIfNonFinite()) return;  // the forces overflowed: name the body now
  PrepareContacts(context.contacts, context.states, context.infos, def.restitution_threshold,
                  &constraints_);
  JointSolver* joints = context.joints;
  if (!joints) {
    SolveVelocities(constraints_, context.states, context.infos, def.velocity_iterations);
  } else {
    // The joints' rows go first in every pass, as in the substep solver.
    joints->Begin(context.states, def.dt, false);
    for (int pass = 0; pass < def.velocity_iterations; ++pass) {
      joints->Solve(context.states, 1.0 / def.dt);
      SolveVelocities(constraints_, context.states, context.infos, 1);
    }
    joints->SolveDirect(context.states, 1.0 / def.dt);
  }
  MarkPushed<ImpulseConstraint>(constraints_, def.integrator, context.states.size(), &pushed_);
  if (joints) joints->MarkBodies(&pushed_);
  MoveBodies(def.integrator, context.states, context.moving, pushed_, def.rotation,
             context.free_motion, def.dt);
  CorrectPositions(context.contacts, context.start_positions, context.states, context.infos,
                   def.linear_slop, def.position_correction);
  if (joints) {
    // The joints' errors, projected out the way the overlap is: by a position change that
    // leaves the velocities alone.
    push_linear_.assign(context.states.size(), Vec2{});
    push_angular_.assign(def.rotation ? context.states.size() : 0, 0.0);
    const PushVelocities push{push_linear_, push_angular_};
    joints->PushOut(context.states, push, 1.0 / def.dt, def.velocity_iterations);
    joints->End();
    MoveByPush(context.states, push, def.rotation, def.dt);
  }
}

}  // namespace engine::detail
