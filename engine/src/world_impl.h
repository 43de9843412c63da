// World's implementation: the bodies, the step's stages and their scratch. Internal.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "broad_phase/broad_phase.h"
#include "engine/world.h"
#include "solver/substep_constraint.h"
#include "solver/seed_solver.h"

namespace engine {

namespace detail {
struct FreeMotion;
struct ForceModel;
struct DirectSolver;
struct ShockRow;
struct ShockScratch;
}  // namespace detail

struct World::Impl {
  explicit Impl(const WorldDef& def);

  void Step();
  BodyId CreateBody(const BodyDef& def);
  AABB BodyBounds(BodyId id) const;
  void FindCandidatePairs();
  void BuildContacts();
  void StepSeed();
  void StepSubstep();
  template <typename C>
  void StepSubstep(std::vector<C>* constraints);
  void UpdateSleep();
  bool CheckFinite();
  template <typename Constraint>
  void MarkPushed(const std::vector<Constraint>& constraints);
  bool ForcesBeyondGravity() const;
  void UpdateTurned();
  double Reach(BodyId id) const;
  detail::ForceModel Forces() const;

  WorldDef def_;
  std::vector<BodyState> states_;
  std::vector<BodyInfo> infos_;
  std::vector<SpringDef> springs_;
  std::size_t damped_bodies_ = 0;
  std::size_t turnable_bodies_ = 0;
  std::vector<SpringDef> acting_springs_;
  std::int64_t step_count_ = 0;
  std::optional<NumericFault> fault_;
  std::vector<double> rest_time_;
  std::vector<std::uint8_t> awake_;
  std::vector<std::uint32_t> island_;
  std::vector<PairQuota> quotas_;
  std::size_t crowded_bodies_ = 0;
  std::uint64_t dropped_pairs_ = 0;
  std::uint32_t most_charged_ = 0;

  std::vector<AABB> bounds_;
  std::vector<double> reach_;
  std::vector<BodyPair> pairs_;
  std::vector<Contact> contacts_;
  std::vector<Contact> previous_contacts_;
  std::vector<Vec2> positions_before_;
  std::unique_ptr<detail::FreeMotion> free_motion_;
  std::vector<Vec2> accelerations_;
  std::vector<double> angular_accelerations_;
  std::vector<std::uint8_t> pushed_;
  std::vector<Vec2> push_velocities_;
  std::vector<double> push_angular_velocities_;
  std::vector<std::uint8_t> loaded_;
  std::vector<Vec2> warm_free_;
  std::vector<double> warm_free_angular_;
  std::vector<double> angles_before_;
  std::vector<Rot> turned_;
  std::vector<ContactConstraint> seed_constraints_;
  std::vector<std::uint64_t> body_colours_;
  std::vector<std::uint32_t> contact_slot_;
  std::vector<SubstepConstraint> substep_constraints_;
  std::vector<LinearConstraint> linear_constraints_;
  std::vector<double> impact_lags_;
  std::unique_ptr<detail::DirectSolver> direct_solver_;
  std::unique_ptr<detail::ShockScratch> shock_scratch_;
  std::vector<detail::ShockRow> shock_rows_;
  BroadPhase broad_phase_;
};

}  // namespace engine
