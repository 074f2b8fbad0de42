// The stages of a step in the book's order (docs/architecture.md, "The step"), the subsystems
// that run in them, and the clock that charges each stage its own wall time.
//
// Order of one substep: the tracks set what they drive, the rates of every subsystem are
// evaluated (external forces, obstacles' push, controllers, the bodies' dynamics, constraint
// forces, the kinematic rates) as often as the integrator asks, the integrator advances, then
// the corrections after the step: unit quaternions, impacts, collisions between bodies, with
// obstacles, within a body, the liquid and its coupling. Slots without a subsystem (coupling)
// cost nothing and report 0.
#pragma once

#include <array>
#include <chrono>

namespace pbm {

enum class StepStage {
  drive,                  // tracks -> gravity, rest shapes, spring targets, obstacle placement
  step_start,             // what later stages need of the substep's start (self-collision)
  forces,                 // kinematics, elastic forces (3.43), nodal loads, the mass block (3.16)
  contact_forces,         // the obstacles' push (5.11) and friction (5.12)
  controllers,            // joint controllers (ch. 15.4)
  dynamics,               // the solve of (3.13) / (3.51)
  constraints,            // constraint forces (7.33) and hinge springs
  kinematics,             // q-dot from v: quaternion rates (sec. 3.1.1), first-order velocities
  integrate,              // the integrator's own arithmetic, between rate evaluations
  renormalize,            // unit quaternions after the step (sec. 6.1)
  impacts,                // impacts of figures (ch. 15.3)
  body_collisions,        // between bodies (5.2.2)
  obstacle_collisions,    // with obstacles (5.2.1)
  velocity_split,         // the mean-axis split restored where no obstacle stage did it
  self_collisions,        // a local body with itself
  constraint_projection,  // C, C-dot restored to their values before the collisions
  liquid,                 // the liquid's grid (ch. 16)
  coupling,               // liquid and solids (ch. 16)
  measure,                // energies and distances for the stability guard
  count
};
inline constexpr int kStageCount = static_cast<int>(StepStage::count);
const char* stage_name(StepStage stage);

// The subsystems a scene may have (sim/subsystems.cpp holds their table).
enum class SubsystemId {
  bodies,
  obstacles,
  body_collisions,
  self_collision,
  constraints,
  figures,
  segment_bodies,  // figures' segments with deformable bodies
  liquids,         // liquid grids (ch. 16)
  liquid_bodies,   // bodies in a liquid: its buoyancy and drag on them (16.4)
  count
};
inline constexpr int kSubsystemCount = static_cast<int>(SubsystemId::count);
const char* subsystem_name(SubsystemId id);

// Charges elapsed wall time to one (stage, subsystem) at a time: each switch charges the time
// since the previous switch to the previous pair. Every interval is measured once, so no stage's
// time is found by subtracting others. Time outside any stage is charged to none.
struct StageClock {
  using Clock = std::chrono::steady_clock;
  std::array<double, kStageCount> stage_seconds{};
  std::array<double, kSubsystemCount> subsystem_seconds{};
  StepStage stage = StepStage::count;          // charged now (count: none)
  SubsystemId subsystem = SubsystemId::count;  // charged now (count: none)
  Clock::time_point since{};

  void reset() {
    stage_seconds.fill(0);
    subsystem_seconds.fill(0);
    stage = StepStage::count;
    subsystem = SubsystemId::count;
  }
  void switch_to(StepStage next_stage, SubsystemId next_subsystem) {
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - since).count();
    if (stage != StepStage::count) stage_seconds[static_cast<int>(stage)] += elapsed;
    if (subsystem != SubsystemId::count) {
      subsystem_seconds[static_cast<int>(subsystem)] += elapsed;
    }
    stage = next_stage;
    subsystem = next_subsystem;
    since = now;
  }
};

// Charges the enclosed code to (stage, subsystem), then goes back to what was charged before.
class StageScope {
 public:
  StageScope(StageClock& clock, StepStage stage, SubsystemId subsystem = SubsystemId::count)
      : clock_(clock), outer_stage_(clock.stage), outer_subsystem_(clock.subsystem) {
    clock_.switch_to(stage, subsystem);
  }
  ~StageScope() { clock_.switch_to(outer_stage_, outer_subsystem_); }
  StageScope(const StageScope&) = delete;
  StageScope& operator=(const StageScope&) = delete;

 private:
  StageClock& clock_;
  StepStage outer_stage_;
  SubsystemId outer_subsystem_;
};

}  // namespace pbm
