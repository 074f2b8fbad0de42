#include "sim/world.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/bits.h"
#include "core/wall_clock.h"
#include "sim/adaptive_step.h"
#include "sim/level_of_detail.h"

namespace pbm {
namespace {

using Clock = WallClock;

// The rates of every present subsystem at (t, q, v): the drive at t, then each rate hook in the
// order of its stage (forces, contact forces, controllers, dynamics, constraints, kinematics).
void evaluate_rates(const World& world, const Inputs& inputs, Workspace& ws, Real t, const VecX& q,
                    const VecX& v, VecX& q_dot, VecX& v_dot) {
  {
    const StageScope scope(ws.clock, StepStage::drive);
    evaluate_drive(*world.model, inputs, t, ws.drive);
  }
  ws.contacts = 0;
  const RateContext context{*world.model, inputs, ws, t, q, v, q_dot, v_dot};
  for (const World::BoundRate& hook : world.rates) {
    const StageScope scope(ws.clock, hook.stage, hook.subsystem);
    hook.run(context);
  }
}

// Euler's q-dot from the new velocities (6.1): every subsystem's second-order parts.
void evaluate_kinematic_rates(const World& world, Workspace& ws, const VecX& q, const VecX& v,
                              VecX& q_dot) {
  for (const Subsystem* subsystem : world.subsystems) {
    if (!subsystem->kinematic_rates) continue;
    const StageScope scope(ws.clock, StepStage::kinematics, subsystem->id);
    subsystem->kinematic_rates(*world.model, q, v, q_dot);
  }
}

// 0 x is 0 for every finite x and NaN for an infinite or NaN one, so the sum of 0 x over a
// vector is NaN exactly when one entry is not finite: one packed product and sum per two
// entries, where Eigen's allFinite (x - x, then a NaN test per entry) took 2.7% of a 1k-node
// ball's step.
bool finite_entries(const VecX& x) {
  return !std::isnan((0.0 * x.array()).sum());
}

bool all_finite(const State& s) {
  return finite_entries(s.q) && finite_entries(s.v);
}

// The first subsystem's account of what in a failed state is wrong.
std::string describe_failure(const World& world, const State& state) {
  for (const Subsystem* subsystem : world.subsystems) {
    if (!subsystem->describe_failure) continue;
    std::string failure = subsystem->describe_failure(*world.model, state);
    if (!failure.empty()) return failure;
  }
  return all_finite(state) ? std::string() : std::string("state became NaN or infinite");
}

// Energy the frame from state.time to t_end may legitimately gain besides potential energy
// (springs, moving obstacles, assembling constraints), summed in table order. `work`: the part
// that is work done by inputs that are no potential (moving obstacles, Baumgarte's feedback),
// which the run-level guard adds to what the run may gain; the bodies' part is a floor.
struct Allowance {
  Real floor = 0;
  Real work = 0;
};
Allowance energy_allowance(const World& world, const Inputs& inputs, const State& state, Real t_end,
                           Workspace& ws) {
  Allowance a;
  for (const Subsystem* subsystem : world.subsystems) {
    if (!subsystem->energy_allowance) continue;
    const Real part = subsystem->energy_allowance(*world.model, inputs, state, t_end, ws);
    a.floor += part;
    if (subsystem->id != SubsystemId::bodies) a.work += part;
  }
  return a;
}

Real total_energy(const FrameStats& s) {
  return s.kinetic + s.elastic + s.potential;
}

// The body or figure whose kinetic + elastic energy grew most in the frame ("body 'ball'",
// "figure 'arm'").
std::string part_that_gained(const Model& model, const FrameStats& before,
                             const FrameStats& after) {
  std::string best;
  Real most = -1e300;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Real gain = after.bodies[b].kinetic + after.bodies[b].elastic - before.bodies[b].kinetic -
                      before.bodies[b].elastic;
    if (gain > most) {
      most = gain;
      best = "body '" + model.bodies[b].name + "'";
    }
  }
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const Real gain = after.figures[f].kinetic + after.figures[f].elastic -
                      before.figures[f].kinetic - before.figures[f].elastic;
    if (gain > most) {
      most = gain;
      best = "figure '" + model.figures[f].model.name + "'";
    }
  }
  return best;
}

// Names the body or figure whose energy grew most out of line ("body 'ball'"), or "" (the growth
// is then the whole's).
std::string part_that_grew(const Model& model, const FrameStats& before, const FrameStats& after,
                           Real e0, Real e1) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    if (after.bodies[b].kinetic + after.bodies[b].elastic >
        before.bodies[b].kinetic + before.bodies[b].elastic + 0.5 * (e1 - e0)) {
      return "body '" + model.bodies[b].name + "'";
    }
  }
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    if (after.figures[f].kinetic > before.figures[f].kinetic + 0.5 * (e1 - e0)) {
      return "figure '" + model.figures[f].model.name + "'";
    }
  }
  return {};
}

}  // namespace

bool World::has(SubsystemId id) const {
  return std::any_of(subsystems.begin(), subsystems.end(),
                     [id](const Subsystem* s) { return s->id == id; });
}

World make_world(const Model& model) {
  World world;
  world.model = &model;
  for (const Subsystem& subsystem : subsystem_table()) {
    if (subsystem.present && !subsystem.present(model)) continue;
    world.subsystems.push_back(&subsystem);
    for (const RateHook& hook : subsystem.rates) {
      if (hook.run) world.rates.push_back({hook.stage, subsystem.id, hook.run});
    }
    for (const SubstepHook& hook : subsystem.substep) {
      if (hook.run && (!hook.present || hook.present(model))) {
        world.substeps.push_back({hook.stage, subsystem.id, hook.run});
      }
    }
  }
  // By stage, and within a stage in table order.
  std::stable_sort(world.rates.begin(), world.rates.end(),
                   [](const auto& a, const auto& b) { return a.stage < b.stage; });
  std::stable_sort(world.substeps.begin(), world.substeps.end(),
                   [](const auto& a, const auto& b) { return a.stage < b.stage; });
  return world;
}

void init_workspace(const World& world, Workspace& ws) {
  const Model& model = *world.model;
  for (const Subsystem* subsystem : world.subsystems) {
    if (subsystem->size_workspace) subsystem->size_workspace(model, ws);
  }
  ws.integrator.resize(model.n_q, model.n_v);
  ws.last_measured.valid = false;
  evaluate_drive(model, Inputs{}, 0, ws.drive);
  ws.clock.reset();
}

bool advance_substep(const World& world, const Inputs& inputs, State& state, Real dt, Workspace& ws,
                     int& evaluations, const StageObserver* observer) {
  const Model& model = *world.model;
  const SubstepContext context{model, inputs, ws, state, dt};
  ws.body_collision_stats = BodyCollisionStats{};
  ws.segment_body_stats = SegmentBodyStats{};
  auto hook = world.substeps.begin();
  for (; hook != world.substeps.end() && hook->stage < StepStage::integrate; ++hook) {
    if (observer) (*observer)(hook->stage, hook->subsystem, false, state, ws);
    {
      const StageScope scope(ws.clock, hook->stage, hook->subsystem);
      hook->run(context);
    }
    if (observer) (*observer)(hook->stage, hook->subsystem, true, state, ws);
  }
  IntegrationStats istats;
  bool ok = true;
  {
    const StageScope scope(ws.clock, StepStage::integrate);
    auto rates = [&](Real t, const VecX& q, const VecX& v, VecX& q_dot, VecX& v_dot) {
      evaluate_rates(world, inputs, ws, t, q, v, q_dot, v_dot);
    };
    auto kinematic = [&](const VecX& q, const VecX& v, VecX& q_dot) {
      evaluate_kinematic_rates(world, ws, q, v, q_dot);
    };
    switch (model.solver.integrator) {
      case IntegratorKind::euler:
      case IntegratorKind::implicit:  // the bodies' rates are the backward-Euler increment
        euler_step(rates, kinematic, state.time, dt, state.q, state.v, ws.integrator, istats);
        break;
      case IntegratorKind::rk4:
        rk4_step(rates, state.time, dt, state.q, state.v, ws.integrator, istats);
        break;
      case IntegratorKind::rk45:
        ok = rk45_advance(rates, state.time, dt, model.solver.tolerance, state.q, state.v,
                          state.rk45_step, ws.integrator, istats);
        break;
    }
  }
  evaluations += istats.evaluations;
  state.time += dt;
  // A state the integrator left NaN or infinite goes no further: the corrections after the step
  // (collision searches over the bodies' positions) assume finite input, and the guard retries
  // the frame from its start anyway.
  if (!all_finite(state)) return false;
  // After the step: unit quaternions, then collisions between bodies (5.2.2), with obstacles
  // (5.2.1: no node is left inside an obstacle by another body), within a body.
  for (; hook != world.substeps.end(); ++hook) {
    if (observer) (*observer)(hook->stage, hook->subsystem, false, state, ws);
    {
      const StageScope scope(ws.clock, hook->stage, hook->subsystem);
      hook->run(context);
    }
    if (observer) (*observer)(hook->stage, hook->subsystem, true, state, ws);
  }
  state.contact_nodes = ws.contacts;
  return ok && all_finite(state);
}

void measure_state(const World& world, const Inputs& inputs, const State& state, Workspace& ws,
                   FrameStats& stats) {
  const Model& model = *world.model;
  const StageScope scope(ws.clock, StepStage::measure);
  stats.time = state.time;
  stats.min_distance = 1e300;
  stats.hinge_energy = 0;
  stats.constraint_violation = 0;
  stats.bodies.resize(model.bodies.size());
  stats.figures.resize(model.figures.size());
  evaluate_drive(model, inputs, state.time, ws.drive);
  for (const Subsystem* subsystem : world.subsystems) {
    if (!subsystem->measure) continue;
    const StageScope hook(ws.clock, StepStage::measure, subsystem->id);
    subsystem->measure(model, inputs, state, ws, stats);
  }
  stats.kinetic = stats.elastic = stats.potential = 0;
  for (const BodyFrameStats& body : stats.bodies) {
    stats.kinetic += body.kinetic;
    stats.elastic += body.elastic;
    stats.potential += body.potential;
  }
  for (const FigureFrameStats& figure : stats.figures) {
    stats.kinetic += figure.kinetic;
    stats.potential += figure.potential - figure.work;
    stats.elastic += figure.elastic;
  }
  if (world.has(SubsystemId::constraints)) stats.elastic += stats.hinge_energy;
}

FrameResult advance_frame(const World& world, const Inputs& inputs, State& state, Workspace& ws,
                          FrameStats& stats) {
  const Model& model = *world.model;
  FrameResult result;
  const auto wall0 = Clock::now();
  ws.clock.reset();
  const Real frame_dt = 1.0 / model.solver.fps;
  const Real t_end = (std::round(state.time * model.solver.fps) + 1.0) / model.solver.fps;
  FrameStats& before = ws.before;
  const Workspace::Measured& last = ws.last_measured;
  if (last.valid && last.time == state.time && same_bits(last.q, state.q) &&
      same_bits(last.v, state.v)) {
    before = last.stats;  // ws.drive and the bodies' kinematics are still at this state too
  } else {
    measure_state(world, inputs, state, ws, before);
  }
  // Levels of detail for the whole frame, its retries included (sim/level_of_detail.h): a body
  // put to sleep changed its state, which is measured again.
  LevelStats levels;
  if (auto_levels_present(model) && choose_levels(model, state, ws, levels)) {
    measure_state(world, inputs, state, ws, before);
  }
  const int base_substeps =
      std::max(1, static_cast<int>(std::ceil(frame_dt / frame_substep(model, state) - 1e-9)));
  const Allowance allowance = energy_allowance(world, inputs, state, t_end, ws);
  const Real floor = allowance.floor;
  state.energy_scale = std::max(state.energy_scale, before.kinetic + before.elastic);
  // The drive depends on time only through tracks and the springs' windows.
  const bool timed_drive = !model.tracks.empty() || !model.springs.empty();
  state.liquid_work = 0;  // each attempt starts from frame_start: its own work only
  ws.frame_start = state;
  if (timed_drive) {
    state.time = t_end;
    measure_state(world, inputs, state, ws, ws.start_at_end_drive);
    state.time = ws.frame_start.time;
  }
  const bool adaptive = adaptive_steps(model);
  int rejected = 0;  // over every attempt: the work the estimate threw away
  for (int attempt = 0; attempt <= model.solver.max_retries; ++attempt) {
    // What the liquids' substeps cost, this attempt's (every measurement of the frame reads it).
    for (LiquidStepStats& steps : ws.liquid_steps) steps = LiquidStepStats{};
    const int substeps = base_substeps << attempt;
    const Real h = frame_dt / substeps;
    bool ok = true;
    int evaluations = 0;
    int done = 0;
    for (int k = 0; k < substeps && ok; ++k) {
      // End of sec. 5.2.2: smaller steps while in contact, back to h after.
      const bool last_substep = k + 1 == substeps;
      if (adaptive) {
        // The error estimate chooses the lengths within h (sim/adaptive_step.h).
        const AdaptiveResult a =
            advance_adaptive(world, inputs, state, h, last_substep, ws, evaluations);
        ok = a.ok;
        done += a.accepted;
        rejected += a.rejected;
      } else if (model.solver.contact_step_reduction && state.contact_nodes > 0) {
        const int m = static_cast<int>(std::ceil(1.0 / model.solver.contact_dt_factor - 1e-9));
        for (int j = 0; j < m && ok; ++j) {
          ws.substep_ends_frame = last_substep && j + 1 == m;
          ok = advance_substep(world, inputs, state, h / m, ws, evaluations);
        }
        done += m;
      } else {
        ws.substep_ends_frame = last_substep;
        ok = advance_substep(world, inputs, state, h, ws, evaluations);
        ++done;
      }
    }
    ws.substep_ends_frame = true;
    FrameStats& after = ws.after;
    std::string failure;
    if (!ok && all_finite(state)) {
      failure = "the rk45 integrator's step size underflowed (solver.tolerance " +
                std::to_string(model.solver.tolerance) + ")";
    } else if (failure = describe_failure(world, state); !failure.empty()) {
    } else {
      if (timed_drive) {
        state.time = ws.frame_start.time;
        measure_state(world, inputs, state, ws, ws.end_at_start_drive);
      }
      state.time = t_end;
      measure_state(world, inputs, state, ws, after);
      const Real e0 = before.kinetic + before.elastic;
      const Real e1 = after.kinetic + after.elastic;
      const Real allowed =
          model.solver.energy_growth_bound *
          (e0 + std::abs(after.potential - before.potential) + floor + std::abs(state.liquid_work));
      if (!(e1 <= allowed)) {
        failure = "kinetic+elastic energy grew from " + std::to_string(e0) + " J to " +
                  std::to_string(e1) + " J in one frame";
        const std::string part = part_that_grew(model, before, after, e0, e1);
        if (!part.empty()) failure = part + ": " + failure;
      } else {
        // The run-level guard: the total energy's growth over the frame beyond the work of the
        // inputs, accumulated while positive. A drive that depends on time (tracks moving
        // spring targets, rest shapes, gravity; springs switching on) works through the
        // potential's explicit change, integrated over the frame by the trapezoid rule on its
        // two ends; moving obstacles and Baumgarte's feedback by their allowances; the liquids'
        // push on bodies by the work it did (State::liquid_work).
        Real drive_work = 0;
        if (timed_drive) {
          drive_work = 0.5 * (total_energy(after) - total_energy(ws.end_at_start_drive) +
                              total_energy(ws.start_at_end_drive) - total_energy(before));
        }
        const Real growth = total_energy(after) - total_energy(before) - drive_work -
                            allowance.work - state.liquid_work;
        const Real surplus = std::max(0.0, state.energy_surplus + growth);
        // The scale counts the frame's end too: a ball dropped from rest has its kinetic energy
        // only there. An explosion is still caught: its surplus grows as fast as its energy,
        // and the limit is only a quarter of that.
        const Real scale = std::max(state.energy_scale, e1);
        const Real limit = model.solver.energy_tolerance * (scale + floor);
        if (!(surplus <= limit)) {
          failure = part_that_gained(model, before, after) + ": the energy grew by " +
                    std::to_string(surplus) +
                    " J beyond the work of the inputs, more than solver.energy_tolerance " +
                    std::to_string(model.solver.energy_tolerance) + " x " +
                    std::to_string(scale + floor) + " J";
        } else {
          state.energy_surplus = surplus;
          after.energy_surplus = surplus;
          after.energy_limit = limit;
        }
      }
    }
    if (failure.empty()) {
      ws.last_measured.valid = true;
      ws.last_measured.time = state.time;
      ws.last_measured.q = state.q;
      ws.last_measured.v = state.v;
      ws.last_measured.stats = after;
      stats = after;
      stats.substeps = done;
      stats.rejected = rejected;
      stats.retries = attempt;
      stats.evaluations = evaluations;
      stats.contacts = state.contact_nodes;
      stats.body_collisions = ws.body_collision_stats;
      stats.segment_bodies = ws.segment_body_stats;
      stats.levels = levels;
      stats.notes = model.notes;
      ws.clock.switch_to(StepStage::count, SubsystemId::count);
      stats.stage_seconds = ws.clock.stage_seconds;
      stats.subsystem_seconds = ws.clock.subsystem_seconds;
      stats.wall_seconds = seconds_since(wall0);
      return result;
    }
    state = ws.frame_start;
    state.rk45_step = 0;  // the retry starts with the whole substep
    result.message = failure;
  }
  result.ok = false;
  result.message += " (after " + std::to_string(model.solver.max_retries) +
                    " retries with halved substeps, at t = " + std::to_string(state.time) + " s)";
  stats = before;
  stats.wall_seconds = seconds_since(wall0);
  return result;
}

}  // namespace pbm
