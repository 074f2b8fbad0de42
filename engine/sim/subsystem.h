// What a subsystem supplies to the step (docs/architecture.md, "Adding a subsystem"): the same
// small set of free functions, any of which may be absent. sim/subsystems.cpp holds the table of
// every subsystem; a World (sim/world.h) keeps the rows a scene has and runs their hooks in the
// order of the stages (sim/step_stage.h).
#pragma once

#include <array>
#include <span>
#include <string>

#include "draw/snapshot.h"
#include "sim/frame_stats.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/step_stage.h"
#include "sim/workspace.h"

namespace pbm {

// One evaluation of the system's rates at (t, q, v), as the integrator asks for it: ws.drive is
// already at t. Hooks add to v_dot (accelerations of second-order parts, velocities of
// first-order ones) and fill their q_dot.
struct RateContext {
  const Model& model;
  const Inputs& inputs;
  Workspace& ws;
  Real t;
  const VecX& q;
  const VecX& v;
  VecX& q_dot;
  VecX& v_dot;
};

// A substep of length dt around the integrator: before it, state is its start; after it, its
// end, which the hooks correct in place (collisions, renormalization).
struct SubstepContext {
  const Model& model;
  const Inputs& inputs;
  Workspace& ws;
  State& state;
  Real dt;
};

struct RateHook {
  StepStage stage = StepStage::count;
  void (*run)(const RateContext&) = nullptr;
};
struct SubstepHook {
  StepStage stage = StepStage::count;
  void (*run)(const SubstepContext&) = nullptr;
  bool (*present)(const Model&) = nullptr;  // null: whenever the subsystem is
};

struct Subsystem {
  SubsystemId id = SubsystemId::count;
  bool (*present)(const Model&) = nullptr;  // does the scene have it
  // Sizes its part of the workspace (called once per workspace).
  void (*size_workspace)(const Model&, Workspace&) = nullptr;
  std::array<RateHook, 4> rates{};  // its forces and rates, by stage
  // q-dot from v for its second-order parts (Euler's update of q from the new v, (6.1)).
  void (*kinematic_rates)(const Model&, const VecX& q, const VecX& v, VecX& q_dot) = nullptr;
  std::array<SubstepHook, 3> substep{};  // before and after the integrator, by stage
  // Adds its measurements of `state` to stats (ws.drive is at state.time; the bodies' hook runs
  // first and leaves their kinematics in ws.bodies).
  void (*measure)(const Model&, const Inputs&, const State&, Workspace&, FrameStats&) = nullptr;
  // Energy [J] the frame from state.time to t_end may legitimately gain from this subsystem (the
  // stability guard's allowance), after measure of the frame's start.
  Real (*energy_allowance)(const Model&, const Inputs&, const State&, Real t_end,
                           Workspace&) = nullptr;
  // What of its part of a state that failed is NaN or out of range (names the part and the
  // quantity); empty when its part is fine.
  std::string (*describe_failure)(const Model&, const State&) = nullptr;
  // Its drawables at `state` (ws.drive at state.time, the bodies' kinematics current).
  void (*add_drawables)(const Model&, const Inputs&, const State&, Workspace&,
                        draw::Snapshot&) = nullptr;
};

// Every subsystem, in table order (the order their measurements and drawables are taken).
std::span<const Subsystem> subsystem_table();

}  // namespace pbm
