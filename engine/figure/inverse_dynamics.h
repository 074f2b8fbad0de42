// Inverse dynamics of a figure by the recursive Newton-Euler algorithm (RBDA Table 5.1): the
// joint forces tau that give accelerations qddot at (q, qdot) under gravity and external forces.
// With qddot = 0 it is the bias C(q, qdot) of H qddot + C = tau, which the tests and the
// controllers (15.14) use.
#pragma once

#include <span>

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// q (n_q), v (n_v), qdd (n_v); f_ext as in forward_dynamics. Writes tau (n_v).
void inverse_dynamics(const FigureModel& figure, const Real* q, const Real* v, const Real* qdd,
                      std::span<const ForceVector> f_ext, const Vec3& gravity, FigureWorkspace& ws,
                      Real* tau);

}  // namespace pbm
