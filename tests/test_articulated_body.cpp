// Articulated figures (ch. 15): the articulated-body method (sec. 15.2) against the composite-
// rigid-body mass matrix and recursive Newton-Euler (two independent recursions over the same
// model), closed forms (a pendulum, Euler's equations of a free body), and energy conservation of
// undamped trees of every joint type under gravity.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "figure/articulated_body.h"
#include "figure/figure_kinematics.h"
#include "figure/inverse_dynamics.h"
#include "figure/joint_space_inertia.h"
#include "figure_rk4.h"
#include "random_figures.h"

namespace pbm {
namespace {

using test::random_q;
using test::random_tree;
using test::random_vector;

const Vec3 kGravity(0, 0, -9.81);

std::vector<ForceVector> random_forces(int n, std::mt19937& rng) {
  std::vector<ForceVector> f(n);
  for (ForceVector& fi : f) {
    const Vec6 x = random_vector(6, rng, 3.0);
    fi = force_from_vec6(x);
  }
  return f;
}

Real relative_error(const VecX& a, const VecX& b) {
  return (a - b).norm() / std::max<Real>(1.0, b.norm());
}

TEST(ArticulatedBody, AgreesWithMassMatrixAndNewtonEulerOnRandomTrees) {
  std::mt19937 rng(7);
  Real worst_forward = 0, worst_inverse = 0;
  for (int n : {1, 2, 3, 6, 7, 12, 20, 30}) {
    for (int trial = 0; trial < 4; ++trial) {
      const FigureModel figure = random_tree(n, rng);
      FigureWorkspace ws;
      size_figure_workspace(figure, ws);
      const VecX q = random_q(figure, rng);
      const VecX v = random_vector(figure.n_v, rng, 2.0);
      const VecX tau = random_vector(figure.n_v, rng, 5.0);
      const std::vector<ForceVector> f_ext = random_forces(n, rng);
      VecX qdd(figure.n_v);
      forward_dynamics(figure, q.data(), v.data(), tau.data(), f_ext, kGravity, ws, qdd.data());
      // H qdd + C = tau, C the bias: RNEA at qdd = 0.
      MatX H;
      joint_space_inertia(figure, q.data(), ws, H);
      VecX C(figure.n_v), zero = VecX::Zero(figure.n_v);
      inverse_dynamics(figure, q.data(), v.data(), zero.data(), f_ext, kGravity, ws, C.data());
      const VecX expected = H.llt().solve(tau - C);
      worst_forward = std::max(worst_forward, relative_error(qdd, expected));
      // And back: the joint forces that give ABA's accelerations are the ones it was given.
      VecX tau_back(figure.n_v);
      inverse_dynamics(figure, q.data(), v.data(), qdd.data(), f_ext, kGravity, ws,
                       tau_back.data());
      worst_inverse = std::max(worst_inverse, relative_error(tau_back, tau));
      EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
      EXPECT_EQ(H.llt().info(), Eigen::Success);
    }
  }
  std::printf("worst relative error: ABA vs H^-1 (tau - C) %.2e, RNEA(ABA) vs tau %.2e\n",
              worst_forward, worst_inverse);
  EXPECT_LT(worst_forward, 1e-10);
  EXPECT_LT(worst_inverse, 1e-10);
}

// Armature a (the step's implicit joint damping, RBDA sec. 7.3): ABA with D = S^T I^A S + a
// gives (H + diag(a))^-1 (tau - C), on random trees and on trees whose joints turn about
// coordinate axes, where ABA takes a shortcut for a revolute joint about e_k (row and column k of
// I^a vanish, but only without armature: with it I^a s = U a / D). This test found the shortcut
// taken with armature: a 7-link chain's accelerations 3% off at a = 1e-3 kg m^2.
TEST(ArticulatedBody, WithArmatureAgreesWithTheMassMatrixPlusItsDiagonal) {
  std::mt19937 rng(11);
  Real worst = 0;
  for (const bool coordinate_axes : {false, true}) {
    for (int n : {1, 2, 3, 6, 7, 12, 20}) {
      for (int trial = 0; trial < 3; ++trial) {
        const FigureModel figure = random_tree(n, rng, coordinate_axes);
        FigureWorkspace ws;
        size_figure_workspace(figure, ws);
        const VecX q = random_q(figure, rng);
        const VecX v = random_vector(figure.n_v, rng, 2.0);
        const VecX tau = random_vector(figure.n_v, rng, 5.0);
        MatX H;
        joint_space_inertia(figure, q.data(), ws, H);
        VecX C(figure.n_v), zero = VecX::Zero(figure.n_v);
        inverse_dynamics(figure, q.data(), v.data(), zero.data(), {}, kGravity, ws, C.data());
        for (const Real scale : {1e-3, 0.1, 10.0}) {
          const VecX armature = scale * (random_vector(figure.n_v, rng, 1.0).array() + 1.5);
          VecX qdd(figure.n_v);
          forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, kGravity, ws, qdd.data(),
                           armature.data());
          MatX H_a = H;
          H_a.diagonal() += armature;
          worst = std::max(worst, relative_error(qdd, H_a.llt().solve(tau - C)));
        }
      }
    }
  }
  std::printf("worst relative error with armature: ABA vs (H + diag a)^-1 (tau - C) %.2e\n", worst);
  EXPECT_LT(worst, 1e-10);
}

// 1/2 v^T H v equals the sum of the segments' 1/2 v_i^T I_i v_i.
TEST(ArticulatedBody, MassMatrixGivesTheSegmentsKineticEnergy) {
  std::mt19937 rng(11);
  const FigureModel figure = random_tree(14, rng);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  const VecX q = random_q(figure, rng);
  const VecX v = random_vector(figure.n_v, rng, 2.0);
  MatX H;
  joint_space_inertia(figure, q.data(), ws, H);
  figure_kinematics(figure, q.data(), v.data(), ws);
  Real segments = 0;
  for (int i = 0; i < figure.size(); ++i) segments += 0.5 * ws.v[i].dot(ws.inertia[i] * ws.v[i]);
  EXPECT_NEAR(0.5 * v.dot(H * v), segments, 1e-12 * segments);
}

// A rigid pendulum about a horizontal axis: (I_c + m l^2) qdd = -m g l sin q.
TEST(ArticulatedBody, PendulumFollowsItsClosedForm) {
  FigureModel figure;
  SegmentModel s;
  s.joint.kind = JointKind::revolute;
  s.joint.axis = Vec3::UnitY();
  const Real m = 2.0, l = 0.7, I_yy = 0.01;
  s.inertia = SpatialInertia{m, Vec3(0, 0, -l), Mat3::Identity() * I_yy};
  figure.segments.push_back(s);
  finalize_figure_model(figure);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  for (Real angle : {0.0, 0.3, 1.2, -2.5}) {
    const Real q = angle, v = 0.8, tau = 0.4;
    Real qdd = 0;
    forward_dynamics(figure, &q, &v, &tau, {}, kGravity, ws, &qdd);
    // Rotating by q about +y moves the bob at (0, 0, -l) to (-l sin q, 0, -l cos q): gravity's
    // torque about +y is -m g l sin q.
    const Real expected = (tau - m * 9.81 * l * std::sin(q)) / (I_yy + m * l * l);
    EXPECT_NEAR(qdd, expected, 1e-12 * std::max(1.0, std::abs(expected))) << "q = " << q;
  }
}

// A free body without forces: Euler's equations I w-dot = -w x I w, and its origin (the centre
// of mass) unaccelerated, a spatial linear acceleration of -w x v in body coordinates.
TEST(ArticulatedBody, FreeBodyFollowsEulersEquations) {
  FigureModel figure;
  SegmentModel s;
  s.joint.kind = JointKind::free;
  const Mat3 I_c = Vec3(0.3, 0.5, 0.9).asDiagonal();
  s.inertia = SpatialInertia{3.0, Vec3::Zero(), I_c};
  figure.segments.push_back(s);
  finalize_figure_model(figure);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  VecX q(7);
  q << 0.1, -0.2, 0.3, std::cos(0.4), std::sin(0.4) * Vec3(1, 2, 3).normalized();
  VecX v(6);
  v << 1.0, -2.0, 0.5, 0.3, 0.7, -0.4;
  const VecX tau = VecX::Zero(6);
  VecX qdd(6);
  forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, Vec3::Zero(), ws, qdd.data());
  const Vec3 w = v.head<3>(), lin = v.tail<3>();
  const Vec3 w_dot = I_c.inverse() * (-w.cross(I_c * w));
  EXPECT_LT((qdd.head<3>() - w_dot).norm(), 1e-12);
  EXPECT_LT((qdd.tail<3>() + w.cross(lin)).norm(), 1e-12);
}

// World transform of every segment, inertial -> segment, from the workspace's X_up.
std::vector<SpatialTransform> world_transforms(const FigureModel& figure,
                                               const FigureWorkspace& ws) {
  std::vector<SpatialTransform> X(figure.size());
  for (int i = 0; i < figure.size(); ++i) {
    const int p = figure.segments[i].parent;
    X[i] = p >= 0 ? ws.X_up[i] * X[p] : ws.X_up[i];
  }
  return X;
}

Real total_energy(const FigureModel& figure, const VecX& q, const VecX& v, FigureWorkspace& ws) {
  figure_kinematics(figure, q.data(), v.data(), ws);
  const std::vector<SpatialTransform> X = world_transforms(figure, ws);
  Real energy = 0;
  for (int i = 0; i < figure.size(); ++i) {
    const SpatialInertia& I = figure.segments[i].inertia;
    const Vec3 centre = X[i].r + X[i].E.transpose() * I.c;  // world position of the centre
    energy += 0.5 * ws.v[i].dot(ws.inertia[i] * ws.v[i]) - I.m * kGravity.dot(centre);
  }
  return energy;
}

// An undamped tree of every joint kind swinging under gravity for 1 s (RK4, 1 ms): the total
// energy stays within 1e-6 of itself. A wrong joint bias c_J, quaternion rate or free-joint
// position rate breaks it at the first percent.
TEST(ArticulatedBody, UndampedTreeConservesEnergyUnderGravity) {
  std::mt19937 rng(3);
  const FigureModel figure = random_tree(12, rng);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  VecX q = random_q(figure, rng);
  VecX v = random_vector(figure.n_v, rng, 1.0);
  const VecX tau = VecX::Zero(figure.n_v);
  const auto rates = [&](const VecX& qs, const VecX& vs, VecX& q_dot, VecX& v_dot) {
    q_dot.resize(figure.n_q);
    v_dot.resize(figure.n_v);
    figure_q_dot(figure, qs.data(), vs.data(), q_dot.data());
    forward_dynamics(figure, qs.data(), vs.data(), tau.data(), {}, kGravity, ws, v_dot.data());
  };
  const Real e0 = total_energy(figure, q, v, ws);
  const Real h = 1e-3;
  Real worst = 0;
  for (int step = 0; step < 1000; ++step) {
    test::figure_rk4_step(figure, q, v, h, rates);
    worst = std::max(worst, std::abs(total_energy(figure, q, v, ws) - e0));
  }
  std::printf("energy %.6f J, worst drift over 1 s %.2e relative\n", e0, worst / std::abs(e0));
  EXPECT_LT(worst, 1e-6 * std::abs(e0));
}

TEST(ArticulatedBody, BadModelsAreRefusedNamingTheField) {
  const auto expect_error = [](FigureModel figure, const std::string& path) {
    try {
      finalize_figure_model(figure, "robot.json", "figures[0].segments");
      ADD_FAILURE() << "accepted; expected an error at " << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.path(), path) << e.what();
      EXPECT_EQ(e.file(), "robot.json");
    }
  };
  FigureModel good;
  SegmentModel s;
  s.inertia = solid_box_inertia(1.0, Vec3(0.1, 0.2, 0.3));
  good.segments = {s, s};
  good.segments[1].parent = 0;
  EXPECT_NO_THROW(finalize_figure_model(good));
  EXPECT_EQ(good.n_v, 2);

  FigureModel cycle = good;
  cycle.segments[0].parent = 1;  // a cycle in the tree: a parent that is not earlier
  expect_error(cycle, "figures[0].segments[0].parent");
  FigureModel missing = good;
  missing.segments[1].parent = 5;
  expect_error(missing, "figures[0].segments[1].parent");
  FigureModel massless = good;
  massless.segments[1].inertia.m = 0;
  expect_error(massless, "figures[0].segments[1].mass");
  FigureModel flat = good;
  flat.segments[1].inertia.I_c(2, 2) = 0;
  expect_error(flat, "figures[0].segments[1].inertia");
  FigureModel no_axis = good;
  no_axis.segments[1].joint.axis = Vec3::Zero();
  expect_error(no_axis, "figures[0].segments[1].joint.axis");
  FigureModel nan_mass = good;
  nan_mass.segments[0].inertia.m = std::nan("");
  expect_error(nan_mass, "figures[0].segments[0].mass");
}

}  // namespace
}  // namespace pbm
