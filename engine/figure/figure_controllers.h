// A figure's joint controllers (sec. 15.4) checked against its tree: each drives one DOF of a
// revolute, prismatic or universal joint (whose q and v entries correspond), no DOF has two, and
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

// The step limit of the figure's explicit PD servos (CompiledFigure::servo_step_limit): a servo
// of gains kp, kd on a DOF of inertia I is a damped oscillator whose explicit step must stay
// below 2 / (kd / I + sqrt(kp / I)) (the bound of the damped mode and of the spring's). I is the
// DOF's articulated inertia at the initial pose (1 / (S^T I^A S)^-1 of the articulated-body
// method: what the servo moves with its parent held), a guide the stability guard backs up as
// the pose changes. MRAC's gains adapt and have no such bound.
void explicit_servo_limit(CompiledFigure& figure);

// Entries the controllers keep in State::q: 0 without controllers, else the actuators' work and
// kMracStateSize per MRAC.
int controller_state_size(const std::vector<JointController>& controllers);

}  // namespace pbm
