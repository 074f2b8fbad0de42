// Impulse events and site actuators on a figure (figure/figure_impulse.h, figure/site_actuator.h):
// the velocity jump H dv = J^T P against the composite-rigid-body H and the contact Jacobian (an
// independent route), the momentum a free-floating tree gains (exactly the impulse), the work
// returned (exactly the kinetic energy gained), a site-frame impulse turning with its site, and
// the site actuator's joint forces J^T F against inverse dynamics and the point Jacobian.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>
#include <vector>

#include "core/quaternion.h"
#include "figure/figure_impact.h"
#include "figure/figure_impulse.h"
#include "figure/figure_kinematics.h"
#include "figure/inverse_dynamics.h"
#include "figure/joint_space_inertia.h"
#include "figure_momentum.h"
#include "figure_points.h"
#include "random_figures.h"

namespace pbm {
namespace {

using test::point_jacobian;
using test::random_q;
using test::random_tree;
using test::random_vector;
using test::world_point;

Real kinetic_energy(const FigureModel& figure, const VecX& q, const VecX& v) {
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  MatX H;
  joint_space_inertia(figure, q.data(), ws, H);
  return 0.5 * v.dot(H * v);
}

struct Struck {
  FigureModel figure;
  VecX q, v;
  CompiledImpulse impulse;
};

Struck random_strike(int n, std::mt19937& rng) {
  Struck s{random_tree(n, rng), {}, {}, {}};
  s.q = random_q(s.figure, rng);
  s.v = random_vector(s.figure.n_v, rng, 1.0);
  s.impulse.site.segment = std::uniform_int_distribution<int>(0, n - 1)(rng);
  s.impulse.site.position = random_vector(3, rng, 0.4);
  s.impulse.linear = random_vector(3, rng, 5.0);
  return s;
}

Real apply(Struck& s) {
  FigureWorkspace ws;
  size_figure_workspace(s.figure, ws);
  ImpulseScratch scratch;
  size_impulse_scratch(s.figure.n_v, s.figure.size(), scratch);
  return apply_impulse(s.figure, s.q.data(), s.v.data(), s.impulse, scratch, ws);
}

TEST(FigureImpulse, VelocityJumpIsTheMassMatrixSolveOfTheJacobianTranspose) {
  std::mt19937 rng(41);
  for (int n : {1, 2, 3, 6, 12, 30}) {
    for (int trial = 0; trial < 4; ++trial) {
      Struck s = random_strike(n, rng);
      const VecX v0 = s.v;
      apply(s);
      // The independent route: CRBA's H and the point's Jacobian, H dv = J^T P.
      FigureWorkspace ws;
      size_figure_workspace(s.figure, ws);
      MatX H;
      joint_space_inertia(s.figure, s.q.data(), ws, H);
      const Vec3 x = world_point(s.figure, s.q, s.impulse.site.segment, s.impulse.site.position);
      const MatX J = point_jacobian(s.figure, s.q, s.impulse.site.segment, x);
      const VecX expected = H.llt().solve(J.transpose() * s.impulse.linear);
      const VecX dv = s.v - v0;
      EXPECT_LT((dv - expected).norm(), 1e-10 * (1 + expected.norm())) << "n = " << n;
    }
  }
}

TEST(FigureImpulse, FreeFloatingTreeGainsExactlyTheImpulsesMomentum) {
  std::mt19937 rng(7);
  for (int n : {2, 5, 9, 20}) {  // random_tree's root is free from n = 2
    Struck s = random_strike(n, rng);
    s.impulse.angular = random_vector(3, rng, 2.0);
    const Vec6 before = test::momentum(s.figure, s.q, s.v);
    apply(s);
    const Vec6 after = test::momentum(s.figure, s.q, s.v);
    const Vec3 x = world_point(s.figure, s.q, s.impulse.site.segment, s.impulse.site.position);
    Vec6 expected;  // [angular about the origin; linear]
    expected << x.cross(s.impulse.linear) + s.impulse.angular, s.impulse.linear;
    EXPECT_LT((after - before - expected).norm(), 1e-10) << "n = " << n;
  }
}

TEST(FigureImpulse, WorkIsTheKineticEnergyGained) {
  std::mt19937 rng(3);
  for (int n : {1, 4, 10, 25}) {
    Struck s = random_strike(n, rng);
    s.impulse.angular = random_vector(3, rng, 1.0);
    const Real before = kinetic_energy(s.figure, s.q, s.v);
    const Real work = apply(s);
    const Real after = kinetic_energy(s.figure, s.q, s.v);
    EXPECT_NEAR(work, after - before, 1e-11 * (1 + std::abs(after) + std::abs(before)))
        << "n = " << n;
  }
  // An impulse at a free body's centre of mass that halves its centre's velocity takes out
  // 3/8 m |v_c|^2 and leaves its spin alone: the work is negative.
  FigureModel body;
  SegmentModel free_body;
  free_body.name = "body";
  free_body.joint.kind = JointKind::free;
  free_body.inertia = test::random_inertia(rng);
  body.segments.push_back(free_body);
  finalize_figure_model(body);
  Struck s{body, random_q(body, rng), random_vector(body.n_v, rng, 2.0), {}};
  const test::FigurePose pose = test::pose_of(body, s.q.data(), s.v.data());
  const SpatialInertia& I = body.segments[0].inertia;
  const Vec6& V = pose.ws.v[0];
  const Vec3 v_c = pose.world[0].E.transpose() * (V.tail<3>() + V.head<3>().cross(I.c));
  s.impulse.site.position = I.c;
  s.impulse.linear = -0.5 * I.m * v_c;
  const Real before = kinetic_energy(body, s.q, s.v);
  const Real work = apply(s);
  EXPECT_NEAR(work, -0.375 * I.m * v_c.squaredNorm(), 1e-12 * before);
  EXPECT_NEAR(kinetic_energy(body, s.q, s.v), before + work, 1e-12 * before);
}

TEST(FigureImpulse, SiteFrameImpulseTurnsWithTheSite) {
  std::mt19937 rng(11);
  Struck a = random_strike(8, rng);
  const Mat3 R = rotation_from_quaternion(Vec4(0.3, -0.5, 0.8, 0.1).normalized());
  a.impulse.site.rotation = R;
  a.impulse.angular = Vec3(0.2, -0.4, 0.9);
  a.impulse.frame = ImpulseFrame::site;
  Struck b = a;
  // The same impulse in the world's axes: world <- segment <- site.
  const Mat3 to_world =
      test::pose_of(b.figure, b.q.data()).world[b.impulse.site.segment].E.transpose() * R;
  b.impulse.frame = ImpulseFrame::world;
  b.impulse.linear = to_world * a.impulse.linear;
  b.impulse.angular = to_world * a.impulse.angular;
  const Real wa = apply(a);
  const Real wb = apply(b);
  EXPECT_LT((a.v - b.v).norm(), 1e-12 * (1 + a.v.norm()));
  EXPECT_NEAR(wa, wb, 1e-12 * (1 + std::abs(wa)));
}

TEST(SiteActuatorForces, JointForcesAreTheJacobianTransposeOfThePointForce) {
  std::mt19937 rng(5);
  for (int n : {1, 3, 7, 16, 40}) {
    const FigureModel figure = random_tree(n, rng);
    const VecX q = random_q(figure, rng);
    test::FigurePose pose = test::pose_of(figure, q.data());
    FigureWorkspace& ws = pose.ws;
    const std::vector<SpatialTransform>& world = pose.world;
    // Forces at two points of two segments, as a site actuator's would be.
    std::vector<ForceVector> f(static_cast<std::size_t>(n));
    VecX expected = VecX::Zero(figure.n_v);
    for (int k = 0; k < 2; ++k) {
      const int i = std::uniform_int_distribution<int>(0, n - 1)(rng);
      const Vec3 local = random_vector(3, rng, 0.5), F = random_vector(3, rng, 10);
      const Vec3 fi = world[i].E * F;
      f[i] += ForceVector{local.cross(fi), fi};
      const Vec3 x = world[i].r + world[i].E.transpose() * local;
      expected += point_jacobian(figure, q, i, x).transpose() * F;
    }
    VecX tau = VecX::Constant(figure.n_v, 0.25);
    add_external_joint_forces(figure, f, ws, tau.data());
    EXPECT_LT((tau - VecX::Constant(figure.n_v, 0.25) - expected).norm(),
              1e-11 * (1 + expected.norm()))
        << "n = " << n;
    // And the negative of what inverse dynamics needs to hold them, at rest without gravity.
    VecX id(figure.n_v);
    const VecX zero = VecX::Zero(figure.n_v);
    inverse_dynamics(figure, q.data(), nullptr, zero.data(), f, Vec3::Zero(), ws, id.data());
    EXPECT_LT((id + expected).norm(), 1e-11 * (1 + expected.norm())) << "n = " << n;
  }
}

}  // namespace
}  // namespace pbm
