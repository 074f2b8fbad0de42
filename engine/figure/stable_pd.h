// Stable proportional-derivative servos on a figure's single-axis and ball joints (beyond the book;
// the issue list of sec. 15.4): the PD torque taken at the end of the step the integrator is about
// to take (v' = v + dt qddot, q' = q + dt v', the semi-implicit Euler of the figure),
// tau = -Kp (q + dt qdot + dt^2 qddot - q_d) - Kd (qdot + dt qddot - qdot_d). The unknown qddot
// moves into the mass matrix, (H + dt Kd + dt^2 Kp) qddot = tau_ext - C - Kp (q + dt qdot - q_d)
// - Kd (qdot - qdot_d): backward Euler on the servo, stable at any gain, where an explicit PD
// needs dt below about 2 / sqrt(Kp / m). (Tan, Liu and Turk 2011 take the spring at q + dt qdot
// only, which is still unstable once Kd dt is far above the link's inertia.) H and C come from
// the composite-rigid-body and Newton-Euler recursions.
#pragma once

#include <Eigen/Cholesky>
#include <span>

#include "figure/figure_model.h"
#include "figure/figure_workspace.h"

namespace pbm {

// Sized on first use for a figure; later calls on it allocate nothing.
struct StablePdWorkspace {
  MatX H;
  VecX C, rhs, zero;
  Eigen::LLT<MatX> llt;
};

// Gains per velocity coordinate (n_v; on revolute, prismatic and universal joints, whose q and v
// entries correspond, and on spherical joints, whose three are the components of the rotation
// vector r, control/ball_coordinates.h); targets q_d and qdot_d per velocity coordinate (a ball:
// r_d and r_d-dot). tau_ext (n_v) are the other joint forces; f_ext the external forces on the
// segments as in forward_dynamics (empty: none). Writes the accelerations and the servo outputs
// (tau_pd, n_v: the force on each coordinate; a ball's f on r enters as the torque J_r^-T f).
// armature (n_v or empty) joins H's diagonal, as in forward_dynamics (implicit joint damping).
// Throws std::invalid_argument for a gain on a free joint.
void stable_pd_accelerations(const FigureModel& figure, const VecX& q, const VecX& v,
                             const VecX& tau_ext, std::span<const ForceVector> f_ext,
                             const Vec3& gravity, const VecX& Kp, const VecX& Kd,
                             const VecX& q_target, const VecX& v_target, Real dt,
                             FigureWorkspace& ws, StablePdWorkspace& pd, VecX& qdd, VecX& tau_pd,
                             const Real* armature = nullptr);

}  // namespace pbm
