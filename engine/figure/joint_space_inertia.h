// The joint-space mass matrix H(q) of a figure by the composite-rigid-body algorithm (RBDA
// Table 6.2): with the bias C of inverse_dynamics, H qddot + C = tau. The tests check the
// articulated-body method against it; controllers may use it for their model inversion (15.14).
#pragma once

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// H: n_v x n_v, symmetric positive definite; resized if it is not.
void joint_space_inertia(const FigureModel& figure, const Real* q, FigureWorkspace& ws, MatX& H);
// The same into a view that already is n_v x n_v (storage the caller keeps).
void joint_space_inertia(const FigureModel& figure, const Real* q, FigureWorkspace& ws,
                         Eigen::Ref<MatX> H);

}  // namespace pbm
