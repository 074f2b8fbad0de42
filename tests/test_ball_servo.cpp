// Servos on spherical joints (control/ball_coordinates.h): a controller drives one component of
// the joint's rotation vector r = log(R), its rate r-dot = J_r^-1 omega and its force entering as
// the torque J_r^-T u. The rate map against a central difference; a spring on r is conservative
// (a tumbling capsule keeps kinetic + kp |r|^2 / 2 to the integrator's error, which the wrong
// torque map would not); a critically damped PD turns a sphere about a skew axis as the closed
// form; MRAC on a ball-jointed arm steps exactly as on a hinge about the same axis, and settles
// at t_s with 1x and 5x its payload.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "control/ball_coordinates.h"
#include "core/quaternion.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

Vec3 rotation_vector(const Eigen::Quaterniond& u) {
  const Real q[4] = {u.w(), u.x(), u.y(), u.z()};
  return ball_rotation_vector(q);
}

TEST(BallCoordinates, TheRotationVectorAndItsRateMap) {
  const Vec3 n = Vec3(1, -2, 2) / 3;
  for (const Real theta : {1e-9, 0.3, 2.0, 3.1}) {
    const Eigen::Quaterniond u(Eigen::AngleAxisd(theta, n));
    EXPECT_LT((rotation_vector(u) - theta * n).norm(), 1e-15 * (1 + theta)) << theta;
    // -q is the same rotation.
    const Eigen::Quaterniond minus(-u.w(), -u.x(), -u.y(), -u.z());
    EXPECT_LT((rotation_vector(minus) - theta * n).norm(), 1e-15 * (1 + theta)) << theta;
  }
  // Past pi the axis flips; continued from a key just short of pi, the vector keeps going.
  const Vec3 past = rotation_vector(Eigen::Quaterniond(Eigen::AngleAxisd(3.3, n)));
  EXPECT_NEAR(past.dot(n), 3.3 - 2 * std::numbers::pi, 1e-14);
  EXPECT_LT((ball_rotation_vector_near(past, 3.1 * n) - 3.3 * n).norm(), 1e-14);
  // r-dot = J_r^-1 omega against a central difference of r along u exp(omega t), omega in the
  // rotated frame, at random orientations below pi and rates; and at rest J_r^-1 = I.
  EXPECT_TRUE(ball_rate_map(Vec3::Zero()).isApprox(Mat3::Identity(), 1e-15));
  std::srand(11);
  Real worst = 0;
  int tried = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Quaterniond u = Eigen::Quaterniond(Vec4::Random().normalized());
    const Vec3 r = rotation_vector(u);
    if (r.norm() > 3.0) continue;
    ++tried;
    const Vec3 omega = Vec3::Random();
    const Real h = 1e-6;
    const auto turned = [&](Real t) {
      return rotation_vector(
          u * Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * t, omega.normalized())));
    };
    const Vec3 difference = (turned(h) - turned(-h)) / (2 * h);
    worst = std::max(worst, (difference - ball_rate_map(r) * omega).norm() / omega.norm());
  }
  std::printf("rate map against a central difference: worst %.2e over %d orientations\n", worst,
              tried);
  EXPECT_GT(tried, 25);
  EXPECT_LT(worst, 1e-8);
}

// A figure of one segment on a spherical joint at the origin, no gravity, with `controllers`.
std::string ball_scene(const std::string& shape, Real mass, const std::string& v0,
                       const std::string& controllers, const std::string& solver) {
  return R"({"gravity": [0, 0, 0], "solver": )" + solver +
         R"(, "figures": [{"name": "ball", "segments": [{"name": "link", "joint": {"kind":
          "spherical", "v0": )" +
         v0 + R"(}, "shape": )" + shape + R"(, "mass": )" + std::to_string(mass) +
         R"(}], "controllers": [)" + controllers + "]}]}";
}

std::string three(const std::string& kind, const Vec3& target, const std::string& gains) {
  std::string out;
  for (int k = 0; k < 3; ++k) {
    char text[256];
    std::snprintf(text, sizeof text,
                  R"(%s{"joint": "link", "dof": %d, "kind": "%s", "keys": [[0, %.17g]], %s})",
                  k ? ", " : "", k, kind.c_str(), target[k], gains.c_str());
    out += text;
  }
  return out;
}

Vec3 ball_r(const Simulation& sim) {
  return ball_rotation_vector(sim.state.q.data() + sim.model.figures[0].model.state_q_offset);
}

// kd = 0: the servo is the spring kp |r|^2 / 2, whose force on omega is -kp J_r^-T r; a capsule
// tumbling at 5 rad/s keeps its kinetic energy plus the spring's to RK4's error, which falls as
// dt^4. A torque of -kp r on omega (without J_r^-T) is not conservative and would drift.
Real spring_energy_drift(Real dt, Real& swing) {
  const Real kp = 2;
  char solver[128];
  std::snprintf(solver, sizeof solver, R"({"dt": %.17g, "fps": 50, "integrator": "rk4"})", dt);
  Simulation sim(parse_scene(
      ball_scene(R"({"kind": "capsule", "size": [0.1, 0.1, 0.3], "center": [0, 0.1, 0.2]})", 3,
                 "[3, -2, 4]", three("pd", Vec3::Zero(), R"("kp": 2)"), solver),
      "ball.json"));
  const auto total = [&] {
    const Vec3 r = ball_r(sim);
    return sim.stats.kinetic + 0.5 * kp * r.squaredNorm();
  };
  const Real e0 = total();
  Real drift = 0;
  swing = 0;
  for (int frame = 0; frame < 100; ++frame) {
    EXPECT_TRUE(advance_frame(sim).ok);
    drift = std::max(drift, std::abs(total() - e0) / e0);
    swing = std::max(swing, ball_r(sim).norm());
  }
  return drift;
}

TEST(BallServo, ASpringOnTheRotationVectorKeepsATumblingCapsulesEnergy) {
  Real swing = 0, swing_half = 0;
  const Real drift = spring_energy_drift(0.002, swing);
  const Real drift_half = spring_energy_drift(0.001, swing_half);
  std::printf(
      "tumbling capsule on a ball spring (|r| up to %.2f rad): energy drift %.2e at 2 ms, "
      "%.2e at 1 ms\n",
      swing, drift, drift_half);
  EXPECT_GT(swing, 1.0);  // well away from rest, where J_r^-1 differs from I
  EXPECT_LT(swing, 3.0);
  EXPECT_LT(drift_half, 1e-8);
  EXPECT_LT(drift_half, drift / 10);
}

TEST(BallServo, ACriticallyDampedPdTurnsASphereAboutASkewAxisAsTheClosedForm) {
  // A sphere centred on the joint (I = 2/5 m a^2 = 0.01 kg m^2 about every axis) turned from
  // rest toward r_d = 1.2 n: the motion stays about n, I theta-ddot = kp (theta_d - theta) -
  // kd theta-dot, critically damped at kd = 2 sqrt(kp I): theta = theta_d (1 - (1 + w t) e^-wt),
  // w = sqrt(kp / I) = 20 1/s.
  const Vec3 n = Vec3(2, -1, 2) / 3;
  const Real theta_d = 1.2, w = 20;
  Simulation sim(
      parse_scene(ball_scene(R"({"kind": "sphere", "size": [0.15811388300841897, 0.1, 0.1]})", 1,
                             "[0, 0, 0]", three("pd", theta_d * n, R"("kp": 4, "kd": 0.4)"),
                             R"({"dt": 0.0005, "fps": 100, "integrator": "rk4"})"),
                  "ball.json"));
  Real worst = 0;
  for (int frame = 0; frame < 50; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const Real t = sim.state.time;
    const Real theta = theta_d * (1 - (1 + w * t) * std::exp(-w * t));
    worst = std::max(worst, (ball_r(sim) - theta * n).norm());
  }
  std::printf("PD on a ball, critically damped about a skew axis: |r - r(t)| at most %.2e rad\n",
              worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(BallServo, MracOnABallStepsAsOnAHingeAndSettlesAtItsTime) {
  // The arm of test_figure_control_world (a ball 0.5 m along x from a joint 1 m up, gravity)
  // stepped to 1 rad about y: on a hinge about y, or on a spherical joint with MRAC on each
  // component of r (targets 0, 1, 0). Gravity's torque is about y and the arm is symmetric
  // about the xz plane, so the ball's x and z components stay at rest and its y steps as the
  // hinge does.
  const Real t_s = 0.3;
  for (const Real payload : {1.0, 5.0}) {
    const auto arm = [&](const std::string& joint, const std::string& controllers) {
      return R"({"solver": {"dt": 0.0005, "fps": 200, "integrator": "rk4"}, "figures": [{"name":
          "arm", "segments": [{"name": "link", "joint": )" +
             joint + R"(, "shape": {"kind": "sphere", "size": [0.15811388300841897, 0.1, 0.1],
          "center": [0.5, 0, 0]}, "mass": )" +
             std::to_string(payload) + R"(}], "controllers": [)" + controllers + "]}]}";
    };
    Simulation hinge(parse_scene(arm(R"({"axis": [0, 1, 0], "position": [0, 0, 1]})",
                                     R"({"joint": "link", "keys": [[0, 1]]})"),
                                 "hinge.json"));
    Simulation ball(parse_scene(arm(R"({"kind": "spherical", "position": [0, 0, 1]})",
                                    three("mrac", Vec3(0, 1, 0), R"("settling_time": 0.3)")),
                                "ball.json"));
    Real worst = 0, off_axis = 0, settle = 0;
    for (int frame = 0; frame < 180; ++frame) {  // 0.9 s = 3 t_s
      ASSERT_TRUE(advance_frame(hinge).ok);
      ASSERT_TRUE(advance_frame(ball).ok);
      const Vec3 r = ball_r(ball);
      worst = std::max(worst, std::abs(r.y() - hinge.state.q[0]));
      off_axis = std::max({off_axis, std::abs(r.x()), std::abs(r.z())});
      if (std::abs(r.y() - 1) > 0.1) settle = ball.state.time;
      EXPECT_EQ(ball.stats.figures[0].controllers[1].actual, r.y());
    }
    std::printf(
        "MRAC on a ball, payload %.0fx: settles at %.3f t_s; |r_y - q_hinge| %.1e rad, "
        "|r_x|, |r_z| %.1e rad\n",
        payload, settle / t_s, worst, off_axis);
    EXPECT_LT(worst, 1e-9);
    EXPECT_LT(off_axis, 1e-12);
    EXPECT_GT(settle, 0.8 * t_s);
    EXPECT_LT(settle, 1.2 * t_s);
  }
}

}  // namespace
}  // namespace pbm
