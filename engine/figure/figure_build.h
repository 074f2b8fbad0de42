// Compiles a FigureDef into its FigureModel: parents by name (earlier segments, no cycle), joint
// frames from their sites, masses and inertias from the segments' geometry (sec. 15.1.1), and
// the initial q and v. Every refusal names the file and the JSON path of the field.
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "control/joint_controller.h"
#include "figure/figure_def.h"
#include "figure/figure_impulse.h"
#include "figure/figure_model.h"
#include "figure/joint_limits.h"
#include "figure/site_actuator.h"

namespace pbm {

// Volume [m^3] of a shape, and its inertia (mass m, about its centre, in its own axes).
Real shape_volume(const SegmentShapeDef& shape);
Mat3 shape_inertia(const SegmentShapeDef& shape, Real m);

struct CompiledFigure {
  FigureModel model;
  VecX q0, v0;                                       // initial state, n_q and n_v
  std::vector<JointController> controllers;          // sec. 15.4 (figure/figure_controllers.h)
  std::vector<CompiledSiteActuator> site_actuators;  // sec. 15.4 (figure/site_actuator.h)
  std::vector<CompiledImpulse> impulses;             // in time order (figure/figure_impulse.h)
  // The controllers' slice of State::q, first-order state integrated with the figure: the work
  // the actuators and the impulses have done [J] (the stability guard's account of the energy
  // they put in), then kMracStateSize per MRAC (its reference model and integrals, sec. 15.4.2).
  // Empty without controllers, site actuators and impulses; placed by sim/model.cpp.
  int n_control = 0;
  int state_control_offset = 0;
  // The longest step the explicit PD servos stay stable at (infinite without any), the one that
  // sets it and its DOF's inertia (figure/figure_controllers.h).
  Real servo_step_limit = std::numeric_limits<Real>::infinity();
  int servo_limiting = -1;
  Real servo_inertia = 0;
  // Which of its segments' pairs may collide (sec. 15.3), n x n and symmetric, row-major: not a
  // segment with itself, its parent or its children, nor a non_colliding pair; all zero without
  // self_collisions. sim/model.cpp also clears the pairs that overlap at the initial pose.
  std::vector<std::uint8_t> self_pairs;
  // Its joints' limits (figure/joint_limits.h); their springs are sized by sim/model.cpp, which
  // knows the step.
  std::vector<JointLimit> limits;
  // Whether it has actuators (controllers or site actuators) whose forces join its joints'.
  bool actuated() const { return !controllers.empty() || !site_actuators.empty(); }
  bool collides(int a, int b) const { return self_pairs[a * model.size() + b] != 0; }
};

// `path` is the figure's JSON path ("figures[0]").
CompiledFigure build_figure_model(const FigureDef& def, const std::string& file,
                                  const std::string& path);

}  // namespace pbm
