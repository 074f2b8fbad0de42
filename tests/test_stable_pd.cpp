// Stable PD servos on a figure (beyond the book, issue list of sec. 15.4): at gains where an
// explicit PD at the same step diverges, the stable PD holds its target; and at small gains both
// agree, since the stable form differs only by terms of order dt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "figure/articulated_body.h"
#include "figure/stable_pd.h"

namespace pbm {
namespace {

const Vec3 kGravity(0, 0, -9.81);

// Three links hanging on revolute joints about y, each a 1 kg bob 0.3 m below its joint.
FigureModel arm() {
  FigureModel figure;
  for (int i = 0; i < 3; ++i) {
    SegmentModel s;
    s.parent = i - 1;
    s.joint.kind = JointKind::revolute;
    s.joint.axis = Vec3::UnitY();
    s.X_tree = translation(Vec3(0, 0, i == 0 ? 0.0 : -0.3));
    s.inertia = SpatialInertia{1.0, Vec3(0, 0, -0.3), Mat3::Identity() * 1e-3};
    figure.segments.push_back(s);
  }
  finalize_figure_model(figure);
  return figure;
}

struct ServoRun {
  Real final_error = 0;  // |q - q_d| at the end
  VecX q;                // the final position
  bool diverged = false;
};

// 2 s of semi-implicit Euler at dt, servos at gains (kp, kd) toward q_d = (0.5, -0.4, 0.3).
ServoRun run(Real kp, Real kd, Real dt, bool stable) {
  const FigureModel figure = arm();
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  StablePdWorkspace pd;
  VecX q = VecX::Zero(3), v = VecX::Zero(3), qdd(3), tau(3);
  const VecX Kp = VecX::Constant(3, kp), Kd = VecX::Constant(3, kd), zero = VecX::Zero(3);
  const VecX target = Vec3(0.5, -0.4, 0.3);
  ServoRun r;
  for (int step = 0; step * dt < 2.0; ++step) {
    if (stable) {
      stable_pd_accelerations(figure, q, v, zero, {}, kGravity, Kp, Kd, target, zero, dt, ws, pd,
                              qdd, tau);
    } else {
      tau = -Kp.cwiseProduct(q - target) - Kd.cwiseProduct(v);
      forward_dynamics(figure, q.data(), v.data(), tau.data(), {}, kGravity, ws, qdd.data());
    }
    v += dt * qdd;
    q += dt * v;
    if (!q.allFinite() || q.cwiseAbs().maxCoeff() > 1e6) {
      r.diverged = true;
      return r;
    }
  }
  r.final_error = (q - target).cwiseAbs().maxCoeff();
  r.q = q;
  return r;
}

TEST(StablePd, HoldsAtGainsWhereTheExplicitPdDiverges) {
  const Real dt = 0.01, kp = 1e5, kd = 1e3;
  const ServoRun explicit_pd = run(kp, kd, dt, false), stable_pd = run(kp, kd, dt, true);
  std::printf("Kp %.0e, Kd %.0e, dt %.2f s: explicit PD %s; stable PD error %.2e rad\n", kp, kd, dt,
              explicit_pd.diverged ? "diverged" : "held", stable_pd.final_error);
  EXPECT_TRUE(explicit_pd.diverged);
  EXPECT_FALSE(stable_pd.diverged);
  // The remaining error is gravity's pull over the servo's stiffness, m g l / Kp ~ 1e-4 rad.
  EXPECT_LT(stable_pd.final_error, 1e-3);
  // A thousand times stiffer still holds, a thousand times closer.
  const ServoRun stiffer = run(1e3 * kp, 1e3 * kd, dt, true);
  EXPECT_FALSE(stiffer.diverged);
  EXPECT_LT(stiffer.final_error, 1e-6);
}

// At modest gains both settle where the servo balances gravity, Kp (q_d - q) = m g l sin q
// summed down the arm: the stable form changes the path by O(dt), not the equilibrium.
TEST(StablePd, SettlesWhereTheExplicitPdSettlesAtModestGains) {
  const Real kp = 200, kd = 20, dt = 1e-3;
  const ServoRun a = run(kp, kd, dt, true), b = run(kp, kd, dt, false);
  ASSERT_FALSE(a.diverged);
  ASSERT_FALSE(b.diverged);
  std::printf("Kp %.0f, Kd %.0f: final error stable %.4e, explicit %.4e rad, apart %.2e rad\n", kp,
              kd, a.final_error, b.final_error, (a.q - b.q).cwiseAbs().maxCoeff());
  EXPECT_GT(b.final_error, 1e-3);  // gravity holds both visibly off the target
  EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace
}  // namespace pbm
