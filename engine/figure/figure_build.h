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

// The longest step a figure's explicit joint forces stay stable at, and the DOF that sets it
// with what sets it (figure/figure_controllers.h, explicit_joint_force_limit).
struct JointStepLimit {
  Real step = std::numeric_limits<Real>::infinity();  // none without such forces
  int segment = -1;                                   // whose parent joint
  int dof = 0;                                        // which of its DOFs
  int controller = -1;  // the explicit PD servo on it, if one is part of the limit
  Real inertia = 0;     // the mode's inertia on that DOF [kg m^2 or kg]
  Real stiffness = 0;   // joint spring plus servo kp on it
  Real damping = 0;     // joint damping (when explicit) plus servo kd on it
};

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
  // The step limits of its explicit joint forces: with the joint damping explicit (the
  // Runge-Kutta integrators) and implicit (euler and implicit, sim/stages_figures.cpp).
  JointStepLimit step_limit_explicit_damping, step_limit_implicit_damping;
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
