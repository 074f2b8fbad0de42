// The World: the subsystems a scene has, composed into one step (docs/architecture.md, "The
// step"). Built from the Model; holds only the subsystems present (a scene without constraints
// has no constraint solver, without obstacles no obstacle stage) and their hooks in the order of
// the stages (sim/step_stage.h), which is the book's order of a step:
//   drive (tracks) -> rates: forces, contact forces, controllers, dynamics, constraints,
//   kinematics -> integrate -> renormalize -> impacts -> collisions (between bodies, with
//   obstacles, within a body) -> liquid -> coupling
// wrapped, per frame, in the stability guard (docs/architecture.md, "Stability guard").
#pragma once

#include <string>
#include <vector>

#include "core/function_ref.h"
#include "sim/frame_stats.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/step_stage.h"
#include "sim/subsystem.h"
#include "sim/workspace.h"

namespace pbm {

struct World {
  const Model* model = nullptr;              // outlives the World
  std::vector<const Subsystem*> subsystems;  // present, in table order
  struct BoundRate {
    StepStage stage;
    SubsystemId subsystem;
    void (*run)(const RateContext&);
  };
  struct BoundSubstep {
    StepStage stage;
    SubsystemId subsystem;
    void (*run)(const SubstepContext&);
  };
  std::vector<BoundRate> rates;        // present rate hooks, by stage then table order
  std::vector<BoundSubstep> substeps;  // present substep hooks, likewise
  bool has(SubsystemId id) const;
};

World make_world(const Model& model);

// Sizes every present subsystem's part of ws for the world's model. Any workspace so sized gives
// the same results (docs/architecture.md, "Determinism").
void init_workspace(const World& world, Workspace& ws);

struct FrameResult {
  bool ok = true;
  std::string message;  // on failure: names the body and the quantity
};

// Advances state by one frame (1 / solver.fps) in substeps of at most solver.dt, with the inputs
// of the moment, and writes what it measured into stats. On NaN, a state out of range or energy
// growth past solver.energy_growth_bound the frame is retried from its start with half the
// substep, up to solver.max_retries times; then it fails, state is left at the frame start and
// stats holds the start's measurement. Allocates nothing once ws and stats have been used for
// this model.
FrameResult advance_frame(const World& world, const Inputs& inputs, State& state, Workspace& ws,
                          FrameStats& stats);

// Called before and after every hook of a substep (after = true once it ran), with the state
// it corrects: a test measures what one stage of the engine's own step does (the collision
// stage's momentum, say) without running a copy of it. A FunctionRef refers to its callable:
// name the lambda first (`auto watch = [&](...) {...}; const StageObserver observer = watch;`),
// since one made from a temporary lambda outlives it.
using StageObserver = FunctionRef<void(StepStage stage, SubsystemId subsystem, bool after,
                                       const State& state, Workspace& ws)>;

// One substep of size dt with the configured integrator, then the corrections after it
// (renormalization, collisions). Returns false if the integrator failed (rk45 step underflow) or
// the state is not finite. `observer`, when given, sees every substep hook (not the rates).
bool advance_substep(const World& world, const Inputs& inputs, State& state, Real dt, Workspace& ws,
                     int& evaluations, const StageObserver* observer = nullptr);

// Energies, distances and per-body and per-constraint numbers of a state (time, energies, bodies,
// min_distance, constraint violations of stats); leaves ws.drive at state.time and the bodies'
// kinematics of state in ws.bodies.
void measure_state(const World& world, const Inputs& inputs, const State& state, Workspace& ws,
                   FrameStats& stats);

}  // namespace pbm
