// Joint springs (sec. 15.1.1's "joint springs"): each sprung joint pulls toward its rest
// coordinates, tau = -k (q - rest) per DOF of a revolute, prismatic or universal joint; a
// spherical joint's spring acts on the rotation from its rest orientation, tau = -k theta with
// theta the rotation vector of R_rest^T R in the child's frame (whose angular velocity is the
// joint's v, so that d/dt (k |theta|^2 / 2) = -tau . v exactly: the spring conserves energy).
#pragma once

#include "figure/figure_model.h"

namespace pbm {

// Adds the springs' joint forces to tau (n_v) at q (n_q).
void add_joint_spring_forces(const FigureModel& figure, const Real* q, Real* tau);

// Their potential energy at q [J].
Real joint_spring_energy(const FigureModel& figure, const Real* q);

}  // namespace pbm
