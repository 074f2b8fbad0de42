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

// tau += J^T f: the joint forces that do on the joints what the external forces f_ext (one per
// segment, in its own coordinates, as in forward_dynamics) do on the segments, by the inverse
// pass alone. Needs figure_kinematics' X_up and S at the figure's q; overwrites ws.f.
void add_external_joint_forces(const FigureModel& figure, std::span<const ForceVector> f_ext,
                               FigureWorkspace& ws, Real* tau);

}  // namespace pbm
