#include "figure/joint_springs.h"

#include <cmath>

#include "core/quaternion.h"

namespace pbm {

namespace {

// The rotation vector of R_rest^T R, the shorter way round.
Vec3 spherical_deflection(const SegmentModel& s, const Real* q) {
  Vec4 e = quaternion_product(quaternion_conjugate(s.rest), Vec4(q[0], q[1], q[2], q[3]));
  if (e[0] < 0) e = -e;
  const Vec3 axis = e.tail<3>();
  const Real sine = axis.norm();
  if (!(sine > 0)) return Vec3::Zero();
  return 2 * std::atan2(sine, e[0]) / sine * axis;
}

}  // namespace

void add_joint_spring_forces(const FigureModel& figure, const Real* q, Real* tau) {
  for (const SegmentModel& s : figure.segments) {
    if (s.stiffness == 0) continue;
    const Real* qi = q + s.q_offset;
    Real* ti = tau + s.v_offset;
    if (s.joint.kind == JointKind::spherical) {
      const Vec3 theta = spherical_deflection(s, qi);
      for (int k = 0; k < 3; ++k) ti[k] -= s.stiffness * theta[k];
      continue;
    }
    const int n = joint_v_size(s.joint.kind);
    for (int k = 0; k < n; ++k) ti[k] -= s.stiffness * (qi[k] - s.rest[k]);
  }
}

Real joint_spring_energy(const FigureModel& figure, const Real* q) {
  Real energy = 0;
  for (const SegmentModel& s : figure.segments) {
    if (s.stiffness == 0) continue;
    const Real* qi = q + s.q_offset;
    if (s.joint.kind == JointKind::spherical) {
      energy += 0.5 * s.stiffness * spherical_deflection(s, qi).squaredNorm();
      continue;
    }
    const int n = joint_v_size(s.joint.kind);
    for (int k = 0; k < n; ++k)
      energy += 0.5 * s.stiffness * (qi[k] - s.rest[k]) * (qi[k] - s.rest[k]);
  }
  return energy;
}

}  // namespace pbm
