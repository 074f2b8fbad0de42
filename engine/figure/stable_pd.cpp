#include "figure/stable_pd.h"

#include <stdexcept>

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
  // The servo's torque at the end of the step, its qddot part moved to the left.
  tau_pd.setZero(n_v);
  for (const SegmentModel& s : figure.segments) {
    const int dof = joint_v_size(s.joint.kind);
    const bool scalar = s.joint.kind == JointKind::revolute ||
                        s.joint.kind == JointKind::prismatic ||
                        s.joint.kind == JointKind::universal;
    for (int k = 0; k < dof; ++k) {
      const int i = s.v_offset + k;
      if (Kp[i] == 0 && Kd[i] == 0) continue;
      if (!scalar) throw std::invalid_argument("stable PD gains on a quaternion joint");
      const Real position = q[s.q_offset + k];
      tau_pd[i] = -Kp[i] * (position + dt * v[i] - q_target[i]) - Kd[i] * (v[i] - v_target[i]);
      pd.H(i, i) += dt * Kd[i] + dt * dt * Kp[i];
    }
  }
  pd.rhs = tau_ext - pd.C + tau_pd;
  pd.llt.compute(pd.H);
  qdd = pd.llt.solve(pd.rhs);
  tau_pd -= (dt * Kd + dt * dt * Kp).cwiseProduct(qdd);
}

}  // namespace pbm
