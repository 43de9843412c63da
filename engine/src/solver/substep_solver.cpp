// The substep solver's step: what it decides once, then the substeps, each a list of passes.
#include "solver/substep_solver.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>

#include "engine/portable_math.h"
#include "solver/constraint_groups.h"
#include "solver/impact.h"
#include "solver/pushed_bodies.h"

namespace engine::detail {

namespace {

/// Against gravity, for a world with gravity.
Vec2 Up(const WorldDef& def) { return -def.gravity / Length(def.gravity); }

}  // namespace

void SubstepSolver::FillAutomaticSettings(WorldDef* def) {
  if (def->substeps == 0) def->substeps = def->rotation ? 8 : 4;
  const bool automatic_passes = def->velocity_iterations == 0;
  if (automatic_passes) def->velocity_iterations = def->rotation ? 4 : 1;
  if (def->circle_velocity_iterations == 0) {
    def->circle_velocity_iterations = automatic_passes && def->rotation ? 2 : def->velocity_iterations;
  }
}

void SubstepSolver::Step(StepContext& context) {
  // Where nothing can turn, the compact constraints in colour order: shock propagation makes
  // the solve indifferent to order there, and the colour order runs faster. Turning stacks need
  // their passes to converge, which contact order does better where a scene is built bottom-up:
  // a turning pyramid of base 40 drifts 6.7 mm in 10 s in contact order against 2.2 cm by colour.
  // Contact order is one chain, which neither lanes nor threads can share; piles keep it within
  // upright strips, which they can (StripContacts). A circle's contacts push through its centre,
  // so where every moving body in contact is one, there is no turning stack to build bottom-up:
  // colour order (the 2000-circle turning pour ends 10 s with 5.0 mm of overlap either way).
  shock_levels_built_ = false;  // this step's, below, or else the constraints give them
  constraints_prepared_ = false;
  // Turning worlds take 4 passes already (their circles alone, circle_velocity_iterations).
  pile_passes_ = context.def.velocity_iterations;
  // Who touches whom is read from the contacts' bodies alone (NarrowPhase::ContactPairs): an
  // eighteenth of the memory, little of it from another core.
  assert(context.contact_pairs.size() == context.contacts.size());
  same_graph_ = false;
  if (context.can_turn) {
    graph_.Forget();  // order_ and the levels found otherwise, or not at all
    if (context.contacts.size() >= kMinStripContacts) {
      if (context.def.substep_features.colour_order && AllRound(context.contact_pairs, context.infos)) {
        order_.ByColour(context.contact_pairs, context.infos);
        if (context.joints == nullptr) pile_passes_ = context.def.circle_velocity_iterations;
      } else {
        order_.InStrips(context.contacts, context.infos, context.states, context.def.gravity, &context.pool);
      }
    } else {
      order_.AsFound(context.contacts.size());
    }
    Step(context, &substep_constraints_);
  } else {
    // A pile at rest keeps its contact graph from step to step, and with it the colour order
    // and the shock levels, which depend on nothing else: they are kept (a pyramid of base 40
    // spent 7 % of its step finding them again).
    const bool by_colour = context.def.substep_features.colour_order;
    same_graph_ = by_colour && graph_.Same(context.contact_pairs, context.infos);
    if (!by_colour) graph_.Forget();
    const auto order = [&] {
      if (same_graph_) return;
      if (by_colour) {
        order_.ByColour(context.contact_pairs, context.infos);
      } else {
        order_.AsFound(context.contacts.size());
      }
    };
    // Shock propagation's levels need only who touches whom: found beside the colouring. On one
    // thread too, the same order: the pile is then measured as the constraints are prepared,
    // not in a pass over the contacts of its own (a 4 000-circle pour's solver 3 345 -> 3 191
    // kcyc a step).
    shock_levels_built_ = ShockPropagates(context.def) && context.contacts.size() >= kMinSideBySideConstraints;
    if (shock_levels_built_) {
      // The constraints, in the colours' order, are filled by whichever thread is free once the
      // colouring is done (PrepareLinearConstraints), and the pile measured run by run as they
      // are: on its own, on either thread, it kept the other waiting.
      const auto levels = [&] {
        if (!same_graph_) BuildShockLevels<BodyPair>(context.contact_pairs, context.infos, &shock_scratch_);
      };
      const auto contacts = static_cast<std::uint32_t>(context.contacts.size());
      linear_constraints_.resize(contacts);
      contact_restitutions_.resize(contacts);
      const bool measure_pile = MeasuresPile(context.def, pile_passes_);
      pile_runs_.assign(measure_pile ? (contacts + kConstraintsPerRun - 1) / kConstraintsPerRun : 0, PileExtent{});
      const auto prepare = [&](std::uint32_t begin, std::uint32_t end) {
        PrepareLinearConstraints(context.contacts, order_.slot, context.infos, linear_constraints_, begin, end,
                                 contact_restitutions_);
        if (measure_pile) {
          pile_runs_[begin / kConstraintsPerRun] =
              MeasurePile(context.contacts.subspan(begin, end - begin), context.infos, context.states, Up(context.def));
        }
      };
      context.pool.RunSideBySideThenShareAfterFirst(order, levels, contacts, kConstraintsPerRun, prepare);
      constraints_prepared_ = true;
      PileExtent pile;
      for (const PileExtent& run : pile_runs_) pile.Merge(run);
      pile_passes_ = PassesForPile(context, pile_passes_, &pile);
    } else {
      order();
      pile_passes_ = PassesForPile(context, pile_passes_);  // reads positions alone
    }
    Step(context, &linear_constraints_);
  }
}

bool SubstepSolver::AllRound(std::span<const BodyPair> contacts, std::span<const BodyInfo> infos) {
  const auto round = [&](BodyIndex body) {
    return HasInfiniteMass(infos[body]) || infos[body].shape.type == ShapeType::kCircle;
  };
  return std::ranges::all_of(contacts, [&](const BodyPair& c) { return round(c.a) && round(c.b); });
}

bool SubstepSolver::TurnsAnchors(const BodyInfo& info) {
  return info.inv_inertia != 0.0 && info.shape.type != ShapeType::kCircle;
}

bool SubstepSolver::ShockPropagates(const WorldDef& def) {
  return def.substep_features.shock_propagation && Length(def.gravity) > 0.0;
}

SubstepPlan SubstepSolver::Plan(const StepContext& context) {
  const WorldDef& def = context.def;
  const SubstepFeatures& features = def.substep_features;
  SubstepPlan plan{};
  plan.impact_pass = features.impact_pass;
  plan.shock_propagation = ShockPropagates(def);
  plan.direct_solve = false;  // known once the constraints are built (PrepareDirectSolve)
  FindLoadedBodies(context);
  // Nothing loaded at all: a closed world without applied forces.
  const bool all_loaded = loaded_.empty();
  // Joints do work (a motor drives, a limit stops): the contacts' energy bound would count it.
  plan.energy_limit = !all_loaded && context.joints == nullptr &&
                      std::find(loaded_.begin(), loaded_.end(), 1) == loaded_.end();
  plan.block_solver = features.block_solver;
  plan.check_forces = context.forces.BeyondGravity();
  // How far bodies turned is for the contacts' separations, and only where a turn moves a
  // contact's points (TurnsAnchors): a jointed net without contacts, or a pile of circles,
  // would turn every body twice a substep for nothing. (Counting a circle's turn in, a disc
  // rolling at 5 m/s found ρ(1 − cos θ) of room each step and sank 5.9 mm into the floor.)
  plan.track_turning = def.rotation && std::ranges::any_of(context.contact_pairs, [&](const BodyPair& c) {
    return TurnsAnchors(context.infos[c.a]) || TurnsAnchors(context.infos[c.b]);
  });
  plan.h = def.dt / def.substeps;
  plan.inv_h = 1.0 / plan.h;
  // Remove the same fraction of the overlap per step as the sequential-impulse solver does,
  // spread over the substeps: 1 − (1 − f)^(1/n) of it each substep, so the push-out speed is
  // that times the overlap / h.
  plan.push_out_rate = (1.0 - NthRoot(1.0 - def.position_correction, def.substeps)) * plan.inv_h;
  plan.wide = nullptr;  // known once the constraints are built (Step)
  plan.passes = pile_passes_;  // at least 2 in a deep pile: PassesForPile
  return plan;
}

// One Gauss-Seidel pass carries a deep pile's weight down only over many substeps; turning
// worlds take 4 passes already.
int SubstepSolver::PassesForPile(const StepContext& context, int passes, const PileExtent* measured) {
  const WorldDef& def = context.def;
  if (!MeasuresPile(def, passes)) return passes;
  const double height = measured ? measured->HeightInBodies()
                                 : PileHeightInBodies(context.contacts, context.infos, context.states, Up(def));
  return height > kDeepPile ? 2 : passes;
}

bool SubstepSolver::MeasuresPile(const WorldDef& def, int passes) {
  return !def.rotation && passes < 2 && Length(def.gravity) > 0.0;
}

template <typename C>
void SubstepSolver::Step(StepContext& context, std::vector<C>* constraints_vector) {
  const WorldDef& def = context.def;
  const std::size_t n = context.states.size();
  // What free flight would do to each body this step: the impact pass places bounces with it.
  accelerations_.resize(n);
  angular_accelerations_.resize(n);
  context.forces.Evaluate(context.states, accelerations_, angular_accelerations_);

  // The impact pass's first look (AnyImpact), where the constraints are prepared here: taken
  // as each is, while its contact and bodies are at hand.
  ImpactLook look{accelerations_, def};
  const bool looked = !constraints_prepared_ && def.substep_features.impact_pass;
  ConstraintKinds kinds;  // what the turning constraints hold, found as they are prepared
  if (!constraints_prepared_) {
    PrepareSubstepConstraints(context.contacts, order_.slot, context.infos, context.states, constraints_vector,
                              &context.pool, looked ? &look : nullptr, &kinds);
  }
  const std::span<C> constraints = *constraints_vector;
  SubstepPlan plan = Plan(context);
  const bool all_turn = !kinds.not_turning.load(std::memory_order_relaxed);
  if constexpr (kCanTurn<C>) {
    assert(!constraints_prepared_);  // so `kinds` is this step's
    plan.direct_solve = def.substep_features.direct_solve &&
                        PrepareDirectSolve(constraints, context.infos, &direct_solver_,
                                           kinds.heavy.load(std::memory_order_relaxed));
    // Shock propagation takes only pairs that cannot turn: where every contact turns (every
    // moving body can), it has nothing to do.
    plan.shock_propagation &= !all_turn;
  }
  constexpr std::uint32_t kBlocksPerRun = 64;
  // In lanes, from here to the substeps' end (the scaled warm start sums over all contacts, and
  // the direct solve takes its islands whole: one at a time). The axis-aligned blocks are laid
  // out here, and filled (PackBlocks) with the shock rows or by whichever thread is free.
  const bool lanes = def.substep_features.lanes != 1 && loaded_.empty();
  std::uint32_t blocks_to_pack = 0;
  if constexpr (!kCanTurn<C>) {
    if (lanes && def.substep_features.colour_order) {
      plan.wide = &WidePassesFor(def.substep_features.lanes);
      wide_.Layout(order_);
      blocks_to_pack = static_cast<std::uint32_t>(wide_.blocks.size());
    }
  }
  const auto pack_blocks = [&](std::uint32_t begin, std::uint32_t end) {
    if constexpr (!kCanTurn<C>) wide_.PackBlocks(constraints, order_, begin, end);
  };
  if (plan.shock_propagation) {  // stacks are supported against gravity: its direction is up
    // The levels of the last step's graph hold where it is this step's (same_graph_): its
    // constraints, prepared from the same contacts, give the same distances as its pairs did.
    if (!shock_levels_built_ && !same_graph_) BuildShockLevels<C>(constraints, context.infos, &shock_scratch_);
    bool rows_written = false;
    if constexpr (!kCanTurn<C>) {
      // One pass over the constraints for the blocks and the rows, each thread on the middle-cut
      // share of every colour (ForEachThreadsShare), close to the share it will solve first (the
      // passes cut by the bodies, BodyCut, which needs the packed blocks), so that most stay in
      // its core's cache: packed by whichever thread was free, half of them came from the other
      // core at the first pass. (On one thread the rows first, then the packing, was once
      // faster; now the one pass is, by a little: the solver 3 292 -> 3 265 kcyc a step.)
      if (blocks_to_pack > 0) {
        const ShockRowWriter<C> rows(constraints, Up(def), &shock_scratch_);
        ForEachThreadsShare(context.pool, wide_.order, [&](std::uint32_t begin, std::uint32_t end) {
          for (std::uint32_t run = begin; run < end; run += kBlocksPerRun) {  // its constraints still cached
            const std::uint32_t run_end = std::min(end, run + kBlocksPerRun);
            pack_blocks(run, run_end);
            rows.Write(wide_.FirstConstraint(run, order_), wide_.FirstConstraint(run_end, order_));
          }
        }, kBlockLanes, &pack_cuts_);
        blocks_to_pack = 0;
        rows_written = true;
      }
    }
    if (!rows_written) WriteShockRows<C>(constraints, Up(def), &shock_scratch_, &context.pool);
    SortShockRows(&shock_scratch_, &shock_rows_, &context.pool);
  }
  // Two tasks side by side, then any blocks' packing shared: the shock schedule only reads the
  // rows, the impacts only write velocities and the lanes only their blocks.
  const auto shock_plan = [&] {
    if (plan.shock_propagation) {
      shock_schedule_.Plan(shock_rows_, context.states.size(), context.pool.Threads());
    }
  };
  // Bounces first, where any pair bounces (most steps of a settled pile have none): looked for
  // as the constraints were prepared here, or else (prepared beside the colouring, with the
  // restitutions written apart) by the threads on their own parts of the contacts (`pool`), or
  // on one thread beside the shock plan.
  const auto any_bounce = [&](WorkerPool* pool) {
    if (!plan.impact_pass) return false;
    if (looked) return look.found.load();
    return AnyImpact<C>(constraints, order_.slot, context.contacts, contact_restitutions_, context.states,
                        accelerations_, def, pool);
  };
  const auto resolve_impacts = [&](bool bounces) {
    impact_lags_.clear();
    if (bounces) {
      ResolveImpacts(constraints, order_.slot, context.contacts, context.states, accelerations_, def, &impact_lags_);
    }
  };
  bool pack_turning = false;
  if constexpr (kCanTurn<C>) {
    pack_turning = lanes && !plan.direct_solve && WideTurningConstraints::Fits(order_, all_turn);
    if (pack_turning) plan.wide = &WidePassesFor(def.substep_features.lanes);
  }
  const auto pack_turning_blocks = [&] {
    if constexpr (kCanTurn<C>) {
      if (pack_turning) wide_turning_.Pack(constraints, order_);
    }
  };
  const auto cut_by_bodies = [&] {
    if (plan.wide && context.pool.Threads() > 1) {  // the passes' shares: by the bodies they move
      if constexpr (kCanTurn<C>) {
        if (wide_turning_.order.strips == 0) wide_turning_.CutByBodies(n, context.pool.Threads());
      } else {
        wide_.CutByBodies(n, context.pool.Threads());
      }
    }
  };
  if (plan.shock_propagation && constraints.size() >= kMinSideBySideConstraints) {
    // The shock plan on one thread; the look for bounces, the bounces and the cut on the other,
    // which had waited out most of the plan (120 kcyc a step of the 4 000-circle pour) after
    // looking on both threads (48).
    const auto impacts = [&] {
      resolve_impacts(any_bounce(nullptr));
      pack_turning_blocks();
      if (blocks_to_pack == 0) cut_by_bodies();  // the blocks are packed
    };
    context.pool.RunSideBySideThenShare(impacts, shock_plan, blocks_to_pack, kBlocksPerRun, pack_blocks);
    if (blocks_to_pack > 0) cut_by_bodies();
  } else {
    const bool bounces = any_bounce(&context.pool);
    if (pack_turning && constraints.size() >= kMinSideBySideConstraints) {
      if (order_.strips == 0) {
        // A colour order's blocks packed by both threads, each its middle-cut share of every
        // colour (ForEachThreadsShare), close to the share it will solve (BodyCut), as the
        // axis-aligned blocks are: packed whole on the worker beside the impacts, which most
        // steps have none of, they kept thread 0 waiting 650 kcyc a step of the turning
        // 4 000-circle pour.
        resolve_impacts(bounces);
        wide_turning_.Layout(order_);
        ForEachThreadsShare(context.pool, wide_turning_.order, [&](std::uint32_t begin, std::uint32_t end) {
          if constexpr (kCanTurn<C>) wide_turning_.PackBlocks(constraints, order_, begin, end);
        }, kBlockLanes, &pack_cuts_);
      } else {
        // The packing only reads the constraints, the impacts only write velocities (and lags).
        context.pool.RunSideBySide([&] { resolve_impacts(bounces); }, pack_turning_blocks);
      }
    } else {
      shock_plan();
      resolve_impacts(bounces);
      pack_turning_blocks();
      if (blocks_to_pack > 0) pack_blocks(0, blocks_to_pack);
    }
    cut_by_bodies();
  }
  push_velocities_.resize(n);
  push_angular_velocities_.resize(n);
  moved_.resize(n);
  ClearPush({push_velocities_, push_angular_velocities_}, &context.pool);  // each move by push clears them after
  if (plan.track_turning) {
    angles_before_.resize(n);
    turned_.resize(n);
    unturned_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      angles_before_[i] = context.states[i].angle;
      unturned_[i] = !TurnsAnchors(context.infos[i]);
    }
    turns_.assign(n, std::numeric_limits<double>::quiet_NaN());  // no turn worked out yet
    UpdateTurned(context);  // nothing has turned yet this step
  }
  // Without turns (no contact's body turns its points) the anchors stay fixed for the step.
  const StepStart start{context.start_positions,
                        plan.track_turning ? std::span<const Rot>(turned_) : std::span<const Rot>()};
  // Nothing reads positions between a substep's push-out and the next substep's free step,
  // except the turns' update.
  bool push_carried = false;
  for (int substep = 0; substep < def.substeps; ++substep) {
    const bool carry_push = substep + 1 < def.substeps && !plan.track_turning;
    Substep(context, constraints, plan, start, push_carried, carry_push);
    if (context.fault) return;
    push_carried = carry_push;
  }
  if (context.joints) {
    context.joints->End();
    // A bounce's lag moves the pair after the substeps, where no joint would pull it back: a
    // link of a whipping chain came off its joint by 14 cm for a step. Jointed bodies bounce
    // without it.
    const std::span<const std::uint8_t> joined = context.joints->Joined();
    for (std::size_t i = 0; i < impact_lags_.size(); ++i) {
      if (joined[context.contacts[i].a] || joined[context.contacts[i].b]) impact_lags_[i] = 0.0;
    }
  }
  DropClosingLags<C>(context, constraints, start);
  ApplyImpactLags<C>(constraints, order_.slot, impact_lags_, context.states);
  // The impulses to the contacts, for next step's warm start: from the lanes where they are.
  if (!plan.wide) {
    StoreImpulses<C>(constraints, order_.slot, context.contacts, &context.pool);
  } else if constexpr (kCanTurn<C>) {
    wide_turning_.StoreImpulses(order_.slot, context.contacts, &context.pool);
  } else {
    wide_.StoreImpulses(order_.slot, context.contacts, &context.pool);
  }
}

template <typename C>
void SubstepSolver::Substep(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                            const StepStart& start, bool push_carried, bool carry_push) {
  const WorldDef& def = context.def;
  const std::span<BodyState> states = context.states;
  const double h = plan.h, inv_h = plan.inv_h;
  const WarmStartImpulses warm{warm_free_, warm_free_angular_};
  const PushVelocities push{push_velocities_, push_angular_velocities_};

  // The lanes and shock propagation measure separations from the bodies' moves.
  const bool lanes_measure = plan.wide != nullptr;
  const MoveMeasure measure{context.start_positions, moved_};
  FreeStep(def.integrator, context.forces, states, h, &context.free_motion, &context.pool,
           push_carried ? &push : nullptr, lanes_measure || plan.shock_propagation ? &measure : nullptr);
  // Forces beyond gravity may overflow: name the body before contacts spread it. (Gravity
  // alone cannot; the check at the step's end catches anything else.)
  if (plan.check_forces && context.StopIfNonFinite()) return;
  const double energy_before = plan.energy_limit ? KineticEnergy(states, context.infos) : 0.0;
  JointSolver* joints = context.joints;
  if (joints) joints->Begin(states, h, true);  // springs, then the joints' warm start
  WarmStartPass(context, constraints, plan, start);
  for (int pass = 0; pass < plan.passes; ++pass) {
    if (joints) joints->Solve(states, inv_h);
    SolvePass(context, constraints, plan, start, pass == 0);
  }
  if constexpr (kCanTurn<C>) {
    if (plan.direct_solve) SolveDirect(&direct_solver_, constraints, states, start, inv_h);
  }
  if (joints) joints->SolveDirect(states, inv_h);
  if (plan.energy_limit) LimitContactEnergy(constraints, states, context.infos, energy_before, warm);
  // Which bodies the contacts pushed, from the impulses (the shock pass leaves them alone).
  if (plan.wide && def.integrator != Integrator::kSemiImplicitEuler) {
    if constexpr (kCanTurn<C>) {
      MarkPushedWide(wide_turning_, states.size(), &pushed_);
    } else {
      MarkPushedWide(wide_.blocks, states.size(), &pushed_);
    }
  } else {
    MarkPushed<C>(constraints, def.integrator, states.size(), &pushed_);
  }
  if (joints) joints->MarkBodies(&pushed_);
  // Shared shock propagation goes band after band where a pile's ids rise with its height: each
  // thread moves its share of the bodies as soon as no later band will touch them, instead of
  // waiting for the last band and for two more hand-offs.
  const bool moves_after_bands = plan.shock_propagation && shock_schedule_.SharedAmong(context.pool) &&
                                 !plan.track_turning && states.size() >= kMinSharedBodies;
  if (moves_after_bands) {
    const int threads = context.pool.Threads();
    auto move_share = [&, threads](int band) {
      const BodyIndex begin = ShareBegin(states.size(), threads, band);
      const BodyIndex end = ShareBegin(states.size(), threads, band + 1);
      MoveBodiesIn(def.integrator, states, context.moving, pushed_, def.rotation, context.free_motion, h, begin, end,
                   lanes_measure ? &measure : nullptr);
    };
    shock_schedule_.Run(context.pool, shock_rows_, states, moved_, inv_h, def.linear_slop, JobRef(move_share));
  } else {
    if (plan.shock_propagation) shock_schedule_.Run(context.pool, shock_rows_, states, moved_, inv_h, def.linear_slop);
    MoveBodies(def.integrator, states, context.moving, pushed_, def.rotation, context.free_motion, h, &context.pool,
               lanes_measure ? &measure : nullptr);
    if (plan.track_turning) UpdateTurned(context);
  }
  PushOutPass(context, constraints, plan, start, push);
  if constexpr (kCanTurn<C>) {
    if (plan.direct_solve) {
      PushOutDirect(&direct_solver_, constraints, states, start, push, plan.push_out_rate,
                    def.max_push_out_speed, def.linear_slop);
    }
  }
  if (joints) joints->PushOut(states, push, inv_h, def.velocity_iterations);
  if (!carry_push) MoveByPush(states, push, def.rotation, h, &context.pool);
  if (plan.track_turning) UpdateTurned(context);
}

// The passes over all contacts go group by group, each large group shared among the threads:
// `pass` takes a part of the constraints, or of their blocks in the wide solver (the first block
// and how many).
template <typename C, typename Pass>
void SubstepSolver::ForEachBlockRun(WorkerPool& pool, Pass&& pass) {
  const auto runs = [&](auto& wide) {
    const auto part = [&](std::uint32_t begin, std::uint32_t end) { pass(begin, std::size_t{end - begin}); };
    if (pool.Threads() > 1 && wide.order.strips == 0) {
      ForEachGroupByBodies(pool, wide.order, wide.body_cut, part, kBlockLanes);
    } else {
      ForEachGroup(pool, wide.order, part, kBlockLanes);
    }
  };
  if constexpr (kCanTurn<C>) {
    runs(wide_turning_);
  } else {
    runs(wide_);
  }
}

// The two runs of strips are two chains of blocks, each waiting for the velocities the block
// before it wrote: worked on side by side, each runs while the other waits (wide_twin.inl). The
// turning pyramid of base 40 on one thread 1.70 -> 1.48 ms/step (1.77 -> 1.56 with AVX2's 16
// registers alone).
template <typename C, typename TwinPass, typename Pass>
bool SubstepSolver::TwinStrips(WorkerPool& pool, TwinPass&& twin, Pass&& pass) {
  if constexpr (!kCanTurn<C>) return false;
  const ContactOrder& order = wide_turning_.order;
  if (order.strips != 2 || !GroupsStayOnOneThread(pool, order, kBlockLanes)) return false;
  const std::span<const std::uint32_t> ends = order.group_ends;  // the even strips', the odd, the edges', the rest
  const auto run = [&](std::uint32_t begin, std::uint32_t end) {
    return TurningRun{wide_turning_.blocks.data() + begin, wide_turning_.second_points.data() + begin,
                      std::size_t{end - begin}};
  };
  twin(run(0, ends[0]), run(ends[0], ends[1]));
  std::uint32_t rest = ends[1];
  if (wide_turning_.edges_apart) {  // the even edges and the odd ones side by side as well
    twin(run(ends[1], wide_turning_.odd_edges_begin), run(wide_turning_.odd_edges_begin, ends[2]));
    rest = ends[2];
  }
  pass(rest, std::size_t{ends.back() - rest});
  return true;
}

template <typename C, typename TwinPass, typename Pass>
void SubstepSolver::ForEachBlockRunSideBySide(WorkerPool& pool, TwinPass&& twin, Pass&& pass) {
  if constexpr (kCanTurn<C>) {
    if (TwinStrips<C>(pool, twin, pass)) return;
    if (wide_turning_.order.strips == 0) {
      ForEachBlockRun<C>(pool, [&](std::uint32_t first, std::size_t count) {
        ColourHalves(wide_turning_, first, count, twin, pass);
      });
      return;
    }
  }
  ForEachBlockRun<C>(pool, pass);
}

template <typename C>
void SubstepSolver::WarmStartPass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                                  const StepStart& start) {
  const std::span<BodyState> states = context.states;
  if (plan.wide) {
    const auto pass = [&](std::uint32_t first, std::size_t count) {
      if constexpr (kCanTurn<C>) {
        plan.wide->turning_warm_start(wide_turning_.blocks.data() + first, wide_turning_.second_points.data() + first,
                                      count, states.data());
      } else {
        plan.wide->warm_start(wide_.blocks.data() + first, count, states.data());
      }
    };
    const auto twin = [&](TurningRun one, TurningRun two) {
      plan.wide->turning_warm_start_twin(one, two, states.data());
    };
    ForEachBlockRunSideBySide<C>(context.pool, twin, pass);
  } else if (loaded_.empty()) {
    ForEachGroup(context.pool, order_, [&](std::uint32_t begin, std::uint32_t end) {
      WarmStartAll(constraints.subspan(begin, end - begin), states);
    });
  } else {  // the force-free contacts' scale sums over all of them: one thread
    WarmStart(constraints, states, context.infos, loaded_, start, plan.inv_h,
              WarmStartImpulses{warm_free_, warm_free_angular_});
  }
}

template <typename C>
void SubstepSolver::SolvePass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                              const StepStart& start, bool first_pass) {
  const std::span<BodyState> states = context.states;
  if (plan.wide) {
    const Rot* turned = start.turned.empty() ? nullptr : start.turned.data();  // null: no turns
    const auto pass = [&](std::uint32_t first, std::size_t count) {
      if constexpr (kCanTurn<C>) {
        plan.wide->turning_solve(wide_turning_.blocks.data() + first, wide_turning_.second_points.data() + first, count,
                                 states.data(), moved_.data(), turned, plan.inv_h, plan.block_solver, first_pass);
      } else {
        plan.wide->solve(wide_.blocks.data() + first, count, states.data(), moved_.data(), plan.inv_h);
      }
    };
    const auto twin = [&](TurningRun one, TurningRun two) {
      plan.wide->turning_solve_twin(one, two, states.data(), moved_.data(), turned, plan.inv_h, plan.block_solver,
                                    first_pass);
    };
    ForEachBlockRunSideBySide<C>(context.pool, twin, pass);
    return;
  }
  ForEachGroup(context.pool, order_, [&](std::uint32_t begin, std::uint32_t end) {
    SolveContacts(constraints.subspan(begin, end - begin), states, start, plan.inv_h, plan.block_solver);
  });
}

template <typename C>
void SubstepSolver::PushOutPass(StepContext& context, std::span<C> constraints, const SubstepPlan& plan,
                                const StepStart& start, PushVelocities push) {
  const WorldDef& def = context.def;
  const std::span<BodyState> states = context.states;
  if (plan.wide) {
    const Rot* turned = start.turned.empty() ? nullptr : start.turned.data();  // null: no turns
    const auto pass = [&](std::uint32_t first, std::size_t count) {
      if constexpr (kCanTurn<C>) {
        plan.wide->turning_push_out(wide_turning_.blocks.data() + first, wide_turning_.second_points.data() + first,
                                    count, moved_.data(), turned, push.linear.data(), push.angular.data(),
                                    plan.push_out_rate, def.max_push_out_speed, def.linear_slop);
      } else {
        plan.wide->push_out(wide_.blocks.data() + first, count, moved_.data(), push.linear.data(),
                            plan.push_out_rate, def.max_push_out_speed, def.linear_slop);
      }
    };
    const auto twin = [&](TurningRun one, TurningRun two) {
      plan.wide->turning_push_out_twin(one, two, moved_.data(), turned, push.linear.data(), push.angular.data(),
                                       plan.push_out_rate, def.max_push_out_speed, def.linear_slop);
    };
    ForEachBlockRunSideBySide<C>(context.pool, twin, pass);
    return;
  }
  ForEachGroup(context.pool, order_, [&](std::uint32_t begin, std::uint32_t end) {
    PushOut(constraints.subspan(begin, end - begin), states, start, push, plan.push_out_rate,
            def.max_push_out_speed, def.linear_slop);
  });
}

void SubstepSolver::FindLoadedBodies(const StepContext& context) {
  // Gravity (uniform or mutual) loads every moving body; otherwise a spring loads the bodies it
  // pulls. Drag and damping only slow a body down and load nothing. With the energy limit off,
  // every body counts as loaded: the warm start then goes on whole everywhere.
  const WorldDef& def = context.def;
  const bool all_loaded = def.gravity != Vec2{} || def.gravitational_constant != 0.0 ||
                          !context.forces.applied_forces.empty() || !def.substep_features.energy_limit;
  const std::size_t n = context.states.size();
  loaded_.assign(all_loaded ? 0 : n, 0);
  warm_free_.resize(all_loaded ? 0 : n);
  warm_free_angular_.resize(all_loaded || !def.rotation ? 0 : n);
  if (all_loaded) return;
  for (const Spring& spring : context.forces.springs) {
    loaded_[spring.body_a] = context.moving[spring.body_a];
    if (spring.body_b) loaded_[*spring.body_b] = context.moving[*spring.body_b];
  }
  // A joint's bodies may carry a load too (a motor pushes, a spring pulls).
  if (context.joints) context.joints->MarkBodies(&loaded_);
}

// A bounce's lag moves the pair after the substeps, where no contact would stop it: moved into a
// third body, a body stays in it. In a tall rain of circles the lags pressed the pile 44 cm deep
// into itself (circles 50 cm across), and it took seconds to come apart. A lag that would
// close another contact of either body past the slop is left out: that bounce keeps its speed
// and starts where the contact holds it.
template <typename C>
void SubstepSolver::DropClosingLags(const StepContext& context, std::span<const C> constraints,
                                    const StepStart& start) {
  if (std::none_of(impact_lags_.begin(), impact_lags_.end(), [](double lag) { return lag != 0.0; })) return;
  const std::size_t n = context.states.size();
  // Each body's contacts, by index, from the contacts' bodies alone (8 bytes a contact; read from
  // the contacts themselves, 152, this pass had 37 of a perf profile's 8 000 samples of the
  // 4 000-circle pour on one thread, against 13 now).
  const std::span<const BodyPair> pairs = context.contact_pairs;
  lag_first_.assign(n + 1, 0);
  for (const BodyPair& c : pairs) ++lag_first_[c.a + 1], ++lag_first_[c.b + 1];
  for (std::size_t i = 0; i < n; ++i) lag_first_[i + 1] += lag_first_[i];
  lag_contacts_.resize(lag_first_[n]);
  lag_fill_.assign(lag_first_.begin(), lag_first_.end() - 1);
  for (std::uint32_t i = 0; i < pairs.size(); ++i) {
    lag_contacts_[lag_fill_[pairs[i].a]++] = i;
    lag_contacts_[lag_fill_[pairs[i].b]++] = i;
  }
  const double slop = context.def.linear_slop;
  // Whether moving `body` by `shift` takes another of its contacts than `bouncing` past the slop.
  const auto closes = [&](BodyIndex body, Vec2 shift, std::uint32_t bouncing) {
    for (std::uint32_t k = lag_first_[body]; k < lag_first_[body + 1]; ++k) {
      const std::uint32_t j = lag_contacts_[k];
      if (j == bouncing) continue;
      const C& c = constraints[order_.slot[j]];
      const double closing = (c.a == body ? 1.0 : -1.0) * Dot(shift, c.normal);
      if (!(closing > 0.0)) continue;
      for (int p = 0; p < PointCount(c); ++p) {
        if (CurrentSeparation(c, Point(c, p), context.states, start) - closing < -slop) return true;
      }
    }
    return false;
  };
  for (std::uint32_t i = 0; i < impact_lags_.size(); ++i) {
    if (impact_lags_[i] == 0.0) continue;
    const C& c = constraints[order_.slot[i]];
    const double share = impact_lags_[i] * (1.0 / (c.inv_mass_a + c.inv_mass_b));
    if ((c.inv_mass_a != 0.0 && closes(c.a, -(share * c.inv_mass_a) * c.normal, i)) ||
        (c.inv_mass_b != 0.0 && closes(c.b, (share * c.inv_mass_b) * c.normal, i))) {
      impact_lags_[i] = 0.0;
    }
  }
}

// A body's turn is worked out again only where it changed (after the push-out, most bodies'
// did not): MakeRot is the most costly part of a turning substep outside the passes. Each thread
// notes the bodies of its share (as the moves before it cut them) whose turn changed, then works
// out their rotations in lanes (WidePasses::rotations): one at a time, with the branches on each
// angle's quadrant, the turning pyramid of base 40 spent 4 % of its step there.
void SubstepSolver::UpdateTurned(const StepContext& context) {
  const std::size_t n = context.states.size();
  const int threads = n >= kMinSharedBodies ? context.pool.Threads() : 1;
  const WidePasses& lanes = WidePassesFor(context.def.substep_features.lanes);
  turning_now_.resize(static_cast<std::size_t>(threads));
  const auto share = [&](int thread) {
    const BodyIndex begin = ShareBegin(n, threads, thread), end = ShareBegin(n, threads, thread + 1);
    std::vector<BodyIndex>& turning = turning_now_[static_cast<std::size_t>(thread)].value;
    turning.resize(end - begin);
    std::size_t count = 0;
    for (BodyIndex i = begin; i < end; ++i) {
      const double turn = context.states[i].angle - angles_before_[i];
      if (std::bit_cast<std::uint64_t>(turn) == std::bit_cast<std::uint64_t>(turns_[i])) continue;
      turns_[i] = turn;
      if (unturned_[i]) {
        turned_[i] = Rot{};
        continue;
      }
      turning[count++] = i;
    }
    lanes.rotations(turns_.data(), 1, turning.data(), count, turned_.data());
  };
  if (threads == 1) {
    share(0);
  } else {
    context.pool.RunOnAll(share);
  }
}

}  // namespace engine::detail
