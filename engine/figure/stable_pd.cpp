#include "figure/stable_pd.h"

#include <stdexcept>

#include "control/ball_coordinates.h"
#include "figure/inverse_dynamics.h"
#include "figure/joint_space_inertia.h"

namespace pbm {

void stable_pd_accelerations(const FigureModel& figure, const VecX& q, const VecX& v,
                             const VecX& tau_ext, std::span<const ForceVector> f_ext,
                             const Vec3& gravity, const VecX& Kp, const VecX& Kd,
                             const VecX& q_target, const VecX& v_target, Real dt,
                             FigureWorkspace& ws, StablePdWorkspace& pd, VecX& qdd, VecX& tau_pd,
                             const Real* armature) {
  const int n_v = figure.n_v;
  joint_space_inertia(figure, q.data(), ws, pd.H);
  if (armature) {
    for (int i = 0; i < n_v; ++i) pd.H(i, i) += armature[i];
  }
  pd.zero.setZero(n_v);
  pd.C.resize(n_v);
  // The bias with the external forces: RNEA's tau at zero acceleration is C - J^T f_ext.
  inverse_dynamics(figure, q.data(), v.data(), pd.zero.data(), f_ext, gravity, ws, pd.C.data());
  // The servo's torque at the end of the step, its qddot part moved to the left. A ball's servo
  // acts on its rotation vector r, r-dot = J omega (J = J_r^-1, control/ball_coordinates.h):
  // its force f on r is the torque J^T f, and its qddot part, with r-ddot ~ J omega-dot (the
  // J-dot omega term, O(dt) in the implicit part, left explicit), is J^T D J omega-dot.
  tau_pd.setZero(n_v);
  pd.rhs = tau_ext - pd.C;
  const auto gains = [&](int i) { return dt * Kd[i] + dt * dt * Kp[i]; };
  for (const SegmentModel& s : figure.segments) {
    const int dof = joint_v_size(s.joint.kind);
    const int i0 = s.v_offset;
    bool any = false;
    for (int k = 0; k < dof; ++k) any = any || Kp[i0 + k] != 0 || Kd[i0 + k] != 0;
    if (!any) continue;
    const bool scalar = s.joint.kind == JointKind::revolute ||
                        s.joint.kind == JointKind::prismatic ||
                        s.joint.kind == JointKind::universal;
    if (scalar) {
      for (int k = 0; k < dof; ++k) {
        const int i = i0 + k;
        const Real position = q[s.q_offset + k];
        tau_pd[i] = -Kp[i] * (position + dt * v[i] - q_target[i]) - Kd[i] * (v[i] - v_target[i]);
        pd.H(i, i) += gains(i);
        pd.rhs[i] += tau_pd[i];
      }
      continue;
    }
    if (s.joint.kind != JointKind::spherical) {
      throw std::invalid_argument("stable PD gains on a free joint");
    }
    const Vec3 r = ball_rotation_vector(q.data() + s.q_offset);
    const Mat3 J = ball_rate_map(r);
    const Vec3 r_dot = J * v.segment<3>(i0);
    Vec3 f, D;
    for (int k = 0; k < 3; ++k) {
      const int i = i0 + k;
      f[k] = -Kp[i] * (r[k] + dt * r_dot[k] - q_target[i]) - Kd[i] * (r_dot[k] - v_target[i]);
      D[k] = gains(i);
    }
    tau_pd.segment<3>(i0) = f;
    pd.H.block<3, 3>(i0, i0) += J.transpose() * D.asDiagonal() * J;
    pd.rhs.segment<3>(i0) += J.transpose() * f;
  }
  pd.llt.compute(pd.H);
  qdd = pd.llt.solve(pd.rhs);
  for (const SegmentModel& s : figure.segments) {
    const int dof = joint_v_size(s.joint.kind);
    const int i0 = s.v_offset;
    if (s.joint.kind != JointKind::spherical) {
      for (int i = i0; i < i0 + dof; ++i) tau_pd[i] -= gains(i) * qdd[i];
      continue;
    }
    if (Kp.segment<3>(i0).isZero() && Kd.segment<3>(i0).isZero()) continue;
    const Mat3 J = ball_rate_map(ball_rotation_vector(q.data() + s.q_offset));
    const Vec3 r_ddot = J * qdd.segment<3>(i0);
    for (int k = 0; k < 3; ++k) tau_pd[i0 + k] -= gains(i0 + k) * r_ddot[k];
  }
}

}  // namespace pbm
