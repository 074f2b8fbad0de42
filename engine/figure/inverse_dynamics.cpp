#include "figure/inverse_dynamics.h"

#include "figure/figure_kinematics.h"

namespace pbm {

void inverse_dynamics(const FigureModel& figure, const Real* q, const Real* v, const Real* qdd,
                      std::span<const ForceVector> f_ext, const Vec3& gravity, FigureWorkspace& ws,
                      Real* tau) {
  const int n = figure.size();
  figure_kinematics(figure, q, v, ws);
  // Outward: a_i = X_up a_parent + S qddot + c_i; f_i = I a_i + v_i x* I v_i - f_ext.
  const Vec6 a0 = gravity_acceleration(gravity);
  for (int i = 0; i < n; ++i) {
    const SegmentModel& segment = figure.segments[i];
    const int dof = static_cast<int>(ws.S[i].cols());
    const Vec6& a_parent = segment.parent >= 0 ? ws.a[segment.parent] : a0;
    ws.a[i] = transform_to_child(ws.X_up[i], a_parent) + ws.c[i];
    if (dof > 0) ws.a[i] += ws.S[i] * Eigen::Map<const VecX>(qdd + segment.v_offset, dof);
    ws.f[i] = ws.inertia[i] * ws.a[i] + force_cross(ws.v[i], ws.inertia[i] * ws.v[i]);
    if (!f_ext.empty()) ws.f[i] -= to_vec6(f_ext[i]);
  }
  // Inward: tau_i = S^T f_i, and the parent carries what its child's joint transmits.
  for (int i = n - 1; i >= 0; --i) {
    const SegmentModel& segment = figure.segments[i];
    const int dof = static_cast<int>(ws.S[i].cols());
    if (dof > 0) Eigen::Map<VecX>(tau + segment.v_offset, dof) = ws.S[i].transpose() * ws.f[i];
    if (segment.parent >= 0) ws.f[segment.parent] += transform_to_parent(ws.X_up[i], ws.f[i]);
  }
}

void add_external_joint_forces(const FigureModel& figure, std::span<const ForceVector> f_ext,
                               FigureWorkspace& ws, Real* tau) {
  const int n = figure.size();
  for (int i = 0; i < n; ++i) ws.f[i] = to_vec6(f_ext[i]);
  for (int i = n - 1; i >= 0; --i) {
    const SegmentModel& segment = figure.segments[i];
    const int dof = static_cast<int>(ws.S[i].cols());
    if (dof > 0) Eigen::Map<VecX>(tau + segment.v_offset, dof) += ws.S[i].transpose() * ws.f[i];
    if (segment.parent >= 0) ws.f[segment.parent] += transform_to_parent(ws.X_up[i], ws.f[i]);
  }
}

}  // namespace pbm
