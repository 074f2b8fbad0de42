// step(): one frame of the whole system as named, ordered, timed stages (STYLE §3, DESIGN §3):
//   drive (tracks) -> external forces (gravity, fields, springs, mouse, damping, contact)
//   -> dynamics solve -> constraint forces (ch. 7) -> integrate -> collisions
// wrapped in the stability guard of DESIGN §6.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "collide/body_collisions.h"
#include "constrain/constraint_forces.h"
#include "deform/body_dynamics.h"
#include "integrate/integrators.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/tracks.h"

namespace pbm {

// Where a step's time goes: nodal forces (with kinematics, elastic forces and the mass block),
// obstacle forces (5.11, 5.12), the solve of (3.13), the constraint forces (7.33) with the hinge
// springs, the integrator, penetration resolution.
enum class StepStage {
  forces,
  contact_forces,
  dynamics,
  constraints,
  integrate,
  collisions,
  count
};
const char* stage_name(StepStage stage);

struct BodyFrameStats {
  VecX q_s;  // current global parameters (n_shape)
  Real kinetic = 0, elastic = 0;
  Vec3 position = Vec3::Zero();
};

struct FrameStats {
  Real time = 0;
  double wall_seconds = 0;
  int substeps = 0;
  int retries = 0;
  int evaluations = 0;
  Real kinetic = 0, elastic = 0, potential = 0;
  Real min_distance = 1e300;  // min signed distance of any node to any obstacle after the frame
  int contacts = 0;
  Real constraint_violation = 0;  // max_l |C_l| after the frame [m] (ch. 7; 0 without any)
  // |C_l| of each point constraint l of ConstraintSystemModel::points [m] (its `source` names the
  // scene constraint; a hinge has two).
  VecX constraint_violations;
  std::array<double, static_cast<int>(StepStage::count)> stage_seconds{};
  std::vector<BodyFrameStats> bodies;
  // Warnings about the model's solvers, '; '-separated (a constraint loop's dense fallback,
  // Baumgarte gains too stiff for dt): empty when all is well.
  std::string notes;
};

struct Workspace {
  std::vector<BodyWorkspace> bodies;
  IntegratorWorkspace integrator;
  ConstraintWorkspace constraints;
  Drive drive;
  VecX first_order_velocity;  // velocities of first-order bodies from the last evaluation
  const Inputs* inputs = nullptr;
  std::array<double, static_cast<int>(StepStage::count)> stage_seconds{};
  int contacts = 0;                         // touching nodes in the last derivative evaluation
  BodyCollisionWorkspace body_collisions;   // 5.2.2, sized on first use
  BodyCollisionStats body_collision_stats;  // of the last substep
  // The measurement that ended the last frame, and the state it measured: the next frame starts
  // from it unless the state was changed in between (a seek, an edit).
  struct Measured {
    bool valid = false;
    Real time = 0;
    VecX q, v;
    FrameStats stats;
  } last_measured;
};

// Sized for the model; binds the derivative callbacks to model, inputs and workspace, so the
// model and inputs must outlive the workspace's use.
void init_workspace(const Model& model, const Inputs& inputs, Workspace& ws);

struct FrameResult {
  bool ok = true;
  std::string message;  // on failure: names the body and the quantity
  FrameStats stats;
};

// Advances state by one frame (1 / solver.fps) in substeps of at most solver.dt. On NaN or energy
// growth past solver.energy_growth_bound the frame is retried from its start with half the
// substep, up to solver.max_retries times; then it fails and state is left at the frame start.
FrameResult advance_frame(const Model& model, State& state, Workspace& ws);

// Kinetic/elastic/potential energy and per-body stats of a state (fills FrameStats fields).
void measure_state(const Model& model, const State& state, Workspace& ws, FrameStats& stats);

// One substep of size dt with the configured integrator, then collision resolution.
// Returns false if the integrator failed (rk45 step underflow).
bool advance_substep(const Model& model, State& state, Real dt, Workspace& ws, int& evaluations);

}  // namespace pbm
