// Random figures for the tests of the recursions and the figure's events: trees of every joint
// kind with random axes, frames and inertias, and random states (tests/test_articulated_body.cpp,
// tests/test_figure_impulse.cpp).
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <string>

#include "figure/figure_model.h"

namespace pbm::test {

inline Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<Real> normal;
  Vec3 a(normal(rng), normal(rng), normal(rng));
  return a.normalized();
}

inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<Real> normal;
  return Eigen::Quaternion<Real>(normal(rng), normal(rng), normal(rng), normal(rng))
      .normalized()
      .toRotationMatrix();
}

inline SpatialInertia random_inertia(std::mt19937& rng) {
  std::uniform_real_distribution<Real> uniform(-0.3, 0.3), positive(0.2, 2.0);
  const Mat3 R = random_rotation(rng);
  SpatialInertia I;
  I.m = positive(rng);
  I.c = Vec3(uniform(rng), uniform(rng), uniform(rng));
  // Principal moments of a real body obey the triangle inequality; keep them well inside it.
  const Vec3 moments =
      0.05 * Vec3(positive(rng), positive(rng), positive(rng)) + Vec3::Constant(0.05);
  I.I_c = R * moments.asDiagonal() * R.transpose();
  return I;
}

// A tree of n segments, each joint kind in turn (so every kind appears from n = 6), parents drawn
// among the earlier segments. coordinate_axes: every other segment's axis is +-e_k instead, the
// axes along which the articulated-body method takes its shortcuts (figure_kinematics.h).
inline FigureModel random_tree(int n, std::mt19937& rng, bool coordinate_axes = false) {
  static constexpr JointKind kKinds[] = {JointKind::revolute,  JointKind::spherical,
                                         JointKind::prismatic, JointKind::universal,
                                         JointKind::fixed,     JointKind::free};
  std::uniform_real_distribution<Real> offset(-0.5, 0.5);
  FigureModel figure;
  for (int i = 0; i < n; ++i) {
    SegmentModel s;
    s.name = "s" + std::to_string(i);
    s.parent = i == 0 ? -1 : std::uniform_int_distribution<int>(-1, i - 1)(rng);
    if (i > 0 && s.parent < 0) s.parent = i - 1;  // one root only, as in a figure
    s.joint.kind = kKinds[(i + (n > 1 ? 1 : 0)) % 6];
    if (i == 0 && n > 1) s.joint.kind = JointKind::free;
    s.joint.axis = random_unit(rng);
    if (coordinate_axes && i % 2 == 1) {
      s.joint.axis = Vec3::Unit((i / 2 + i / 6) % 3) * (i % 4 == 1 ? 1 : -1);
    }
    s.joint.axis2 = s.joint.axis.unitOrthogonal();
    s.X_tree = SpatialTransform{random_rotation(rng), Vec3(offset(rng), offset(rng), offset(rng))};
    s.inertia = random_inertia(rng);
    figure.segments.push_back(s);
  }
  finalize_figure_model(figure);
  return figure;
}

inline VecX random_q(const FigureModel& figure, std::mt19937& rng) {
  std::uniform_real_distribution<Real> angle(-1.5, 1.5);
  VecX q(figure.n_q);
  for (int k = 0; k < figure.n_q; ++k) q[k] = angle(rng);
  figure_normalize(figure, q.data());
  return q;
}

inline VecX random_vector(int n, std::mt19937& rng, Real scale) {
  std::uniform_real_distribution<Real> u(-scale, scale);
  VecX x(n);
  for (int k = 0; k < n; ++k) x[k] = u(rng);
  return x;
}

}  // namespace pbm::test
