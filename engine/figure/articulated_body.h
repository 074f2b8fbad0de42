// Forward dynamics of a figure by Featherstone's articulated-body method (sec. 15.2, the book's
// "ABM" [83]; RBDA Table 7.1): qddot from q, qdot, the joint forces tau and the external forces,
// in time linear in the DOF, without forming the joint-space mass matrix.
#pragma once

#include <span>

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// q (n_q), v (n_v), tau (n_v); f_ext: one force per segment in its own coordinates, acting on
// it (empty: none); gravity in the inertial frame. Writes qdd (n_v). ws sized for the figure.
// armature (n_v, or null): a joint-space inertia added to each DOF's own, D = S^T I^A S +
// diag(armature) (RBDA sec. 7.3's rotor inertia). The step uses it for implicit joint damping:
// a damper -d (v + dt qddot) taken at the step's end moves dt d onto the left side.
void forward_dynamics(const FigureModel& figure, const Real* q, const Real* v, const Real* tau,
                      std::span<const ForceVector> f_ext, const Vec3& gravity, FigureWorkspace& ws,
                      Real* qdd, const Real* armature = nullptr);

// The same with ws already holding figure_kinematics(figure, q, v, ws) of the q and v meant: a
// stage before it in the same rate evaluation computed them (the figures' contact forces), so
// ABA's first pass does not repeat them.
void forward_dynamics_after_kinematics(const FigureModel& figure, const Real* tau,
                                       std::span<const ForceVector> f_ext, const Vec3& gravity,
                                       FigureWorkspace& ws, Real* qdd,
                                       const Real* armature = nullptr);

}  // namespace pbm
