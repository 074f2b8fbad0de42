// A figure's joint controllers (sec. 15.4) checked against its tree: each drives one DOF of a
// revolute, prismatic or universal joint (whose q and v entries correspond) or one component of a
// spherical joint's rotation vector (control/ball_coordinates.h), no DOF has two, and
// every gain and time is in range. Refusals name the file and the JSON path of the field.
#pragma once

#include <string>
#include <vector>

#include "control/joint_controller.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"

namespace pbm {

// The controllers of `def` on its compiled `figure`, their MRAC states laid out after the one
// entry of the actuators' work (see CompiledFigure::n_control). `path`: the figure's JSON path.
std::vector<JointController> compile_figure_controllers(const FigureDef& def,
                                                        const FigureModel& figure,
                                                        const std::string& file,
                                                        const std::string& path);

struct CompiledFigure;

// The step limits of the figure's explicit joint forces (CompiledFigure's step_limit_*): joint
// damping D, joint springs and explicit PD servos K make the figure of joint-space inertia H a
// damped oscillator, H qddot = -D qdot - K q, whose explicit step must stay below
// 2 / (lambda_max(H^-1 D) + sqrt(lambda_max(H^-1 K))) (the damped mode's bound 2 I / d and the
// spring's 2 / omega, for one DOF exactly). H is taken at the initial pose, a guide the
// stability guard backs up as the pose changes. With the joint damping implicit (euler) only the
// servos' kd remain in D. MRAC's gains adapt and have no such bound; a stable PD's are implicit.
void explicit_joint_force_limit(CompiledFigure& figure);

// Entries the controllers keep in State::q: 0 without controllers, else the actuators' work and
// kMracStateSize per MRAC.
int controller_state_size(const std::vector<JointController>& controllers);

}  // namespace pbm
