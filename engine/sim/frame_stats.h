// What a frame cost and what it measured: the stability guard's energies, every stage's and
// every subsystem's wall time, per-body and per-constraint numbers. Written by advance_frame
// (sim/world.h) into a FrameStats the caller keeps, so a step allocates nothing.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "collide/body_collisions.h"
#include "control/joint_controller.h"
#include "core/types.h"
#include "figure/site_actuator.h"
#include "liquid/liquid_step.h"
#include "sim/segment_body_collisions.h"
#include "sim/step_stage.h"

namespace pbm {

struct BodyFrameStats {
  VecX q_s;                       // current global parameters (n_shape)
  Real kinetic = 0, elastic = 0;  // [J]; elastic includes the obstacles' push (5.11)
  Real potential = 0;             // gravity, force fields and springs [J]
  Vec3 position = Vec3::Zero();   // q_c [m]
};

struct FigureFrameStats {
  Real kinetic = 0, potential = 0;  // [J]; potential: gravity's
  Real elastic = 0;                 // the joint springs' and the contact springs' [J]
  Real work = 0;                    // the work its actuators have done since the start [J]
  int contacts = 0;                 // contact points touching an obstacle or another segment
  Real depth = 0;                   // the deepest of them [m]: a penalty contact's error
  // Each controller of CompiledFigure::controllers at the measured state (figs. 15.7, 15.8).
  std::vector<ControlSample> controllers;
  // Each site actuator of CompiledFigure::site_actuators at the measured state.
  std::vector<SitePull> site_actuators;
};

// A liquid at the measured state, and what its substeps cost since the previous measurement
// (the frame's, with any attempt the guard rejected).
struct LiquidFrameStats {
  LiquidStepStats step;
  Real volume = 0;          // Full cells whole, Surface cells by their fill [m^3]
  int markers = 0;          // marker particles (16.3.1); 0 with a height field
  int spray = 0, foam = 0;  // spray and foam particles (liquid/spray.h)
  Real kinetic = 0;         // 1/2 rho |u|^2 over the liquid's cells, u at their centres [J]
  Real max_speed = 0;       // the fastest face of a liquid cell [m/s]
  // Its push on the bodies and the figures' segments at the measured state
  // (sim/liquid_body_loads.h, sim/liquid_segment_loads.h): buoyancy (16.15) and drag [N], and
  // the area of their surfaces under its surface [m^2].
  Vec3 body_force = Vec3::Zero();
  Real wetted_area = 0;
};

// Levels of detail chosen automatically (sim/level_of_detail.h) at the frame's start.
struct LevelStats {
  int dormant_bodies = 0;  // "auto" bodies running without their displacements this frame
  int switches = 0;        // displacements switched on or off at its start
  Real energy_jump = 0;    // largest energy a body's switch off removed [J]
  Real position_jump = 0;  // largest node displacement it zeroed [m]
};

struct FrameStats {
  Real time = 0;            // of the state measured [s]
  double wall_seconds = 0;  // the whole frame, guard and retries included
  int substeps = 0;         // of the accepted attempt
  int rejected = 0;     // adaptive implicit substeps rejected by the error estimate (all attempts)
  int retries = 0;      // halvings of the substep the guard needed
  int evaluations = 0;  // rate evaluations of the accepted attempt
  // Totals [J]. potential also counts, with a minus sign, the work the figures' actuators have
  // done: the energy they put in is spent from it, so an exact step keeps the total constant and
  // the guard judges only what the numerics add.
  Real kinetic = 0, elastic = 0, potential = 0;
  // The run-level guard after the frame: the energy gained beyond the inputs' work and the most
  // it may be (State::energy_surplus, solver.energy_tolerance x scale) [J].
  Real energy_surplus = 0, energy_limit = 0;
  Real hinge_energy = 0;          // the hinges' rotational springs, part of `elastic` [J]
  Real min_distance = 1e300;      // min signed distance of any node to any obstacle after the frame
  int contacts = 0;               // touching nodes after the last substep (State::contact_nodes)
  Real constraint_violation = 0;  // max_l |C_l| after the frame [m] (ch. 7; 0 without any)
  // |C_l| of each point constraint l of ConstraintSystemModel::points [m] (its `source` names the
  // scene constraint; a hinge has two).
  VecX constraint_violations;
  std::array<double, kStageCount> stage_seconds{};          // by StepStage
  std::array<double, kSubsystemCount> subsystem_seconds{};  // by SubsystemId
  std::vector<BodyFrameStats> bodies;
  std::vector<FigureFrameStats> figures;
  std::vector<LiquidFrameStats> liquids;
  BodyCollisionStats body_collisions;  // of the frame's last substep
  SegmentBodyStats segment_bodies;     // segments with bodies, of the frame's last substep
  LevelStats levels;
  // Warnings about the model's solvers, '; '-separated (a constraint loop's dense fallback,
  // Baumgarte gains too stiff for dt): empty when all is well.
  std::string notes;
};

}  // namespace pbm
