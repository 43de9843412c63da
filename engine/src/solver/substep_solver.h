// The substep contact solver, after Erin Catto's "soft step" (Solver2D, 2024): an impact pass for
// bounces, then per substep integrate, warm start, solve, support stacks, move, push out.
// It owns its scratch; World calls Step once a step. Internal to the engine.
#pragma once

#include <cstdint>
#include <vector>

#include "forces/force_model.h"
#include "parallel/balanced_cuts.h"
#include "parallel/per_thread.h"
#include "solver/contact_graph_memo.h"
#include "solver/contact_order.h"
#include "solver/direct_solver.h"
#include "solver/pile_height.h"
#include "solver/shock_propagation.h"
#include "solver/shock_schedule.h"
#include "solver/substep_constraint.h"
#include "solver/substep_passes.h"
#include "solver/wide_constraints.h"
#include "solver/wide_passes.h"
#include "snapshot/byte_stream.h"
#include "step_context.h"

namespace engine::detail {

/// Which of the solver's optional mechanisms run this step, and why: decided once at the step's
/// start from the scene and the switches in WorldDef::substep_features.
struct SubstepPlan {
  bool impact_pass;        ///< restitution as impacts before the solve (switch)
  bool shock_propagation;  ///< gravity gives an up to support stacks along
  bool direct_solve;       ///< an island of turning bodies holds a large mass ratio
  bool energy_limit;       ///< no applied force acts: the contacts may only take energy out
  bool block_solver;       ///< two-point turning contacts solved together (switch)
  bool check_forces;       ///< forces beyond gravity act: they may overflow, checked each substep
  bool track_turning;      ///< a contact's body turns its points (TurnsAnchors): they follow how far it turned
  double h;                ///< the substep, s
  double inv_h;
  double push_out_rate;    ///< 1/s: the fraction of the overlap pushed out per second of a substep
  int passes;              ///< velocity passes per substep: WorldDef's, at least 2 in a deep pile
  /// The wide solver's passes, where every body is loaded (the warm start goes on whole) and
  /// either nothing turns and contacts go by colour, or every contact turns, in strip or colour order,
  /// with no island for the direct solve; null: the one-at-a-time passes.
  const WidePasses* wide;
};

class SubstepSolver {
 public:
  /// Contacts start a margin apart, so fast bodies are caught before they touch.
  static constexpr bool kSpeculative = true;
  /// Where something can turn, at least this many contacts go in strip order (or by colour where
  /// every moving body in contact is a circle, AllRound): the wide solver
  /// takes four strips side by side, and threads whole strips. Fewer stay in contact order, one
  /// chain: a strip then holds too few contacts to fill the lanes. (A turning pyramid of base 20
  /// has 590 contacts: 0.96 -> 0.74 ms/step in strips, drift after 10 s 2.21 -> 2.29 mm; base 40,
  /// 2 380 contacts: 4.43 -> 3.07 ms, drift 4.15 -> 5.31 mm, within the 1 cm the tests hold.)
  static constexpr std::size_t kMinStripContacts = 256;
  /// Where nothing turns, a pile taller than this many bodies (PileHeightInBodies) is solved with
  /// at least 2 velocity passes per substep: with 1, a tall rain of 10 000 circles (a column
  /// four times as tall as wide, about 140 bodies deep) kept creeping at 0.2 m/s and ended with
  /// 2.7 cm of overlap; one 72 deep (10 000 in a square box) ended with 6.8 mm.
  static constexpr double kDeepPile = 64.0;
  /// From this many constraints on, the shock rows are built on a second thread while the first
  /// resolves impacts and packs the lanes: below, the hand-off and fetching the rows from the
  /// other core cost more than it saves (at 2 048, a pour of 1 000 circles, 2 074 contacts, took
  /// 0.98-1.41 of one thread's time on two).
  static constexpr std::size_t kMinSideBySideConstraints = 4096;
  /// The constraints a thread fills at a time beside the shock levels.
  static constexpr std::uint32_t kConstraintsPerRun = 512;
  static_assert(kConstraintsPerRun == kPileRun, "the pile is measured in the runs the constraints are filled in");
  /// Fills in the automatic settings: 4 substeps of 1 pass for the axis-aligned game, 8 of 4
  /// with rotation (turning stacks couple their contacts, docs/solver.md).
  static void FillAutomaticSettings(WorldDef* def);

  void Step(StepContext& context);
  /// Whether every moving body in a contact (its bodies, NarrowPhase::ContactPairs) is a circle:
  /// its contacts push through its centre.
  static bool AllRound(std::span<const BodyPair> contacts, std::span<const BodyInfo> infos);
  /// Whether a body's turn moves its contact points off the line through its centre, so that
  /// its contacts' separations must follow the turn: a body that turns, and is not a circle
  /// (a circle's points lie on the line through its centre, whatever its turn).
  static bool TurnsAnchors(const BodyInfo& info);
  /// What carries over from step to step (the contacts the direct solve took last step), for
  /// snapshots (snapshot/world_snapshot.cpp).
  void Save(ByteWriter& out) const;
  bool Load(ByteReader& in, std::size_t slots);

 private:
  template <typename C>
  void Step(StepContext& context, std::vector<C>* constraints);
  SubstepPlan Plan(const StepContext& context);
  /// Whether shock propagation runs: switched on, and gravity gives an up.
  static bool ShockPropagates(const WorldDef& def);
  /// `passes`, or 2 where nothing turns and the pile stands taller than kDeepPile bodies:
  /// `measured` (the contacts' PileExtent), or measured here where it is null.
  static int PassesForPile(const StepContext& context, int passes, const PileExtent* measured = nullptr);
  /// Whether PassesForPile looks at the pile at all.
  static bool MeasuresPile(const WorldDef& def, int passes);
  /// Which bodies an applied force pushes (their contacts may carry a load); empty when every
  /// moving body is loaded (gravity, uniform or mutual).
  void FindLoadedBodies(const StepContext& context);
  /// How far each body has turned since the step's start, for the contacts' separations.
  void UpdateTurned(const StepContext& context);
  /// Leaves out a bounce's lag that would press either body into another past the slop.
  template <typename C>
  void DropClosingLags(const StepContext& context, std::span<const C> constraints, const StepStart& start);
  /// One substep. The push-out's move ends it, or, with `carry_push`, starts the next
  /// substep's free step (one pass over the bodies fewer); `push_carried`: the last substep's
  /// move is still to do.
  template <typename C>
  void Substep(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
               const StepStart& start, bool push_carried, bool carry_push);
  /// The substep's warm start, velocity passes and push-out over the constraints, one at a time
  /// or in SIMD lanes (plan.wide); each pass goes group by group, large groups over the threads.
  template <typename C>
  void WarmStartPass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                     const StepStart& start);
  /// `first_pass`: the substep's first velocity pass (the wide turning lanes keep what it works
  /// out from the moves for the later ones).
  template <typename C>
  void SolvePass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                 const StepStart& start, bool first_pass);
  template <typename C>
  void PushOutPass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                   const StepStart& start, PushVelocities push);
  /// Calls pass(first, count) on runs of the wide solver's blocks for C, group by group: on
  /// several threads, a colour order's groups cut by the bodies they move (BodyCut).
  template <typename C, typename Pass>
  void ForEachBlockRun(WorkerPool& pool, Pass&& pass);
  /// Turning blocks (C) in strip order on one thread: twin(one, two) on the even and the odd
  /// strips (the first two groups, which share no moving body) side by side, then pass(first,
  /// count) on the rest; returns false, calling neither, anywhere else.
  template <typename C, typename TwinPass, typename Pass>
  bool TwinStrips(WorkerPool& pool, TwinPass&& twin, Pass&& pass);
  /// ForEachBlockRun for the passes that have twins (the warm start, the velocity passes and the
  /// push-out): turning blocks (C) that share no moving body go side by side, twin(one, two), the
  /// rest one after another, pass(first, count). On one thread in strip order, the even and the
  /// odd strips (TwinStrips); in colour order, each colour's part of a run cut in two halves
  /// (ColourHalves).
  template <typename C, typename TwinPass, typename Pass>
  void ForEachBlockRunSideBySide(WorkerPool& pool, TwinPass&& twin, Pass&& pass);

  std::vector<Vec2> accelerations_;
  std::vector<double> angular_accelerations_;
  ContactOrder order_;                                  ///< the solve order: by colour or as found
  std::vector<SubstepConstraint> substep_constraints_;  ///< where something can turn
  std::vector<LinearConstraint> linear_constraints_;    ///< where nothing can
  WideConstraints wide_;                                ///< linear_constraints_ in blocks (SubstepPlan::wide)
  WideTurningConstraints wide_turning_;                 ///< substep_constraints_ in blocks: strips or colours
  std::vector<double> impact_lags_;                     ///< per contact (ResolveImpacts)
  /// Per contact, its restitution, written as the constraints are prepared beside the colouring
  /// (constraints_prepared_), for AnyImpact.
  std::vector<double> contact_restitutions_;
  std::vector<std::uint32_t> lag_first_, lag_fill_, lag_contacts_;  ///< DropClosingLags' contacts by body
  std::vector<std::uint8_t> loaded_;                    ///< per body: an applied force acts
  std::vector<Vec2> warm_free_;                         ///< WarmStartImpulses' storage
  std::vector<double> warm_free_angular_;
  std::vector<double> angles_before_;
  std::vector<Rot> turned_;                             ///< per body: MakeRot(turns_)
  std::vector<double> turns_;                           ///< per body: its angle less angles_before_, as last seen
  /// Per body: it has no inverse inertia (its turn stays Rot{}); read from the infos once a step
  /// rather than at every UpdateTurned.
  std::vector<std::uint8_t> unturned_;
  /// UpdateTurned's, per thread: the bodies of its share whose turn changed and can turn.
  std::vector<PerThread<std::vector<BodyIndex>>> turning_now_;
  std::vector<Vec2> push_velocities_;                   ///< PushVelocities' storage
  std::vector<double> push_angular_velocities_;
  std::vector<std::uint8_t> pushed_;
  DirectSolver direct_solver_;                          ///< islands with a large mass ratio
  ShockScratch shock_scratch_;
  /// The contact graph order_ and the shock levels were last found from (by colour, in a world
  /// that cannot turn): a step with the same graph keeps them.
  ContactGraphMemo graph_;
  /// This step's graph is the last one's: order_ and the levels are kept.
  bool same_graph_ = false;
  bool shock_levels_built_ = false;                     ///< this step's levels found beside the colouring
  bool constraints_prepared_ = false;                   ///< and the constraints filled after it
  std::vector<PileExtent> pile_runs_;  ///< per run of the constraints filled beside the levels
  int pile_passes_ = 1;  ///< this step's velocity passes (PassesForPile), found beside the colouring
  std::vector<ShockRow> shock_rows_;
  std::vector<Vec2> moved_;                             ///< per body: MeasureMoves, as last made
  /// Where the packing pass (ForEachThreadsShare) cuts each colour: the worker's half of the
  /// 4 000-circle pour's took 96 kcyc a step against the first thread's 78, at the middle.
  BalancedCuts pack_cuts_;
  ShockSchedule shock_schedule_;                        ///< shock_rows_ shared among the threads
};

}  // namespace engine::detail
