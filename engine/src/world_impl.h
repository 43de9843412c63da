// World's implementation: the bodies and the step's stages, each owning its scratch. Internal.
#pragma once

#include <cstdint>
#include <optional>
#include <variant>

#include "bodies.h"
#include "candidate_pairs.h"
#include "engine/world.h"
#include "forces/force_model.h"
#include "forces/springs.h"
#include "integrate.h"
#include "narrow_phase/narrow_phase.h"
#include "sleep.h"
#include "solver/sequential_impulse_solver.h"
#include "solver/substep_solver.h"

namespace engine {

namespace detail {
/// One of the contact solvers, chosen once, when the world is made.
using AnyContactSolver = std::variant<SubstepSolver, SequentialImpulseSolver>;
}  // namespace detail

struct World::Impl {
  explicit Impl(const WorldDef& def);

  detail::ForceModel Forces() const;
  /// Whether the chosen solver takes speculative contacts (a margin apart), or real overlap only.
  bool SpeculativeContacts() const;
  void UpdateSleep();

  WorldDef def;                       ///< with the automatic settings filled in
  detail::Bodies bodies;
  detail::SleepTable sleep;
  detail::Springs springs;
  detail::CandidatePairs candidates;  ///< the broad phase
  detail::NarrowPhase narrow_phase;   ///< this step's contacts
  detail::FreeMotion free_motion;     ///< the integrators' scratch
  detail::AnyContactSolver solver;    ///< the one WorldDef::solver chose
  std::int64_t step_count = 0;
  std::optional<NumericFault> fault;
};

}  // namespace engine
