// Model reference adaptive control (sec. 15.4): the reference model's settling time, a step
// command followed by an arm with 1x and 5x its payload without retuning (against a PD tuned at
// 1x), and the torque limit that freezes the adaptation (end of 15.4.2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "control/joint_trajectory.h"
#include "control/mrac.h"
#include "figure/articulated_body.h"

namespace pbm {
namespace {

const Vec3 kGravity(0, 0, -9.81);

// Time from which |q - target| stays within 10% of the step (the book's settling time), and the
// largest overshoot past the target, over a sampled response.
struct StepResponse {
  Real settle = 0, overshoot = 0;
};

StepResponse measure_step(const std::vector<Real>& t, const std::vector<Real>& q, Real target) {
  StepResponse r;
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (std::abs(q[k] - target) > 0.1 * std::abs(target)) r.settle = t[k];
    r.overshoot = std::max(r.overshoot, (q[k] - target) / target);
  }
  return r;
}

// The reference model alone, driven by (15.14) toward a unit step, settles at t_s: its response
// 1 - (1 + lambda t) e^(-lambda t) comes within 10% at lambda t = 3.89, t = 0.97 t_s.
TEST(Mrac, ReferenceModelSettlesAtTheSettlingTime) {
  for (Real t_s : {0.1, 0.3, 0.6}) {
    MracSettings settings;
    settings.settling_time = t_s;
    MracState state = mrac_start(0, 0), rate;
    const DesiredMotion step{1, 0, 0};
    std::vector<Real> t, q;
    const Real h = t_s / 4000;
    for (int k = 0; k < 12000; ++k) {
      // The model's rate does not depend on the plant: its exact flow is what RK4 integrates.
      const auto f = [&](const MracState& s) {
        mrac_control(settings, s, 0, 0, step, rate);
        return rate.x_m;
      };
      MracState s2 = state, s3 = state, s4 = state;
      const Vec2 k1 = f(state);
      s2.x_m += 0.5 * h * k1;
      const Vec2 k2 = f(s2);
      s3.x_m += 0.5 * h * k2;
      const Vec2 k3 = f(s3);
      s4.x_m += h * k3;
      const Vec2 k4 = f(s4);
      state.x_m += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      t.push_back((k + 1) * h);
      q.push_back(state.x_m[0]);
    }
    const StepResponse r = measure_step(t, q, 1.0);
    EXPECT_NEAR(r.settle / t_s, 3.8897 / 4, 1e-3) << "t_s = " << t_s;
    EXPECT_LE(r.overshoot, 1e-9);  // critically damped
  }
}

// An arm turning about a horizontal axis: its bob of `payload` kg at 0.5 m, under gravity.
FigureModel arm(Real payload) {
  FigureModel figure;
  SegmentModel s;
  s.joint.kind = JointKind::revolute;
  s.joint.axis = Vec3::UnitY();
  s.inertia = SpatialInertia{payload, Vec3(0.5, 0, 0), Mat3::Identity() * 0.01 * payload};
  figure.segments.push_back(s);
  finalize_figure_model(figure);
  return figure;
}

// Simulates the arm from rest at q = 0 toward a step to `target` for `duration` s under a
// controller u(t, q, q_dot, controller state) -> (u, rates), RK4 at 0.5 ms; returns q(t)'s step
// response, and in last_q the final q.
template <class Controller>
StepResponse run_arm(Real payload, Real target, Real duration, Controller&& controller,
                     Real* max_u = nullptr, Real* last_q = nullptr) {
  const FigureModel figure = arm(payload);
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  struct X {
    Real q = 0, v = 0;
    MracState c;
  };
  const auto rates = [&](const X& x, X& dx) {
    const Real u = controller(x.q, x.v, x.c, dx.c);
    if (max_u) *max_u = std::max(*max_u, std::abs(u));
    dx.q = x.v;
    forward_dynamics(figure, &x.q, &x.v, &u, {}, kGravity, ws, &dx.v);
  };
  const auto axpy = [](const X& x, Real a, const X& d) {
    X y = x;
    y.q += a * d.q;
    y.v += a * d.v;
    y.c.x_m += a * d.c.x_m;
    y.c.K_integral += a * d.c.K_integral;
    y.c.Kr_integral += a * d.c.Kr_integral;
    y.c.bias_integral += a * d.c.bias_integral;
    return y;
  };
  X x;
  x.c = mrac_start(0, 0);
  std::vector<Real> t, q;
  const Real h = 5e-4;
  for (int k = 0; k * h < duration; ++k) {
    X k1, k2, k3, k4;
    rates(x, k1);
    rates(axpy(x, 0.5 * h, k1), k2);
    rates(axpy(x, 0.5 * h, k2), k3);
    rates(axpy(x, h, k3), k4);
    x = axpy(x, h / 6, k1);
    x = axpy(x, h / 3, k2);
    x = axpy(x, h / 3, k3);
    x = axpy(x, h / 6, k4);
    t.push_back((k + 1) * h);
    q.push_back(x.q);
  }
  if (last_q) *last_q = x.q;
  return measure_step(t, q, target);
}

TEST(Mrac, StepSettlesAtItsTimeWithOneAndFiveTimesThePayload) {
  const Real t_s = 0.3, target = 1.0;
  MracSettings settings;
  settings.settling_time = t_s;
  const DesiredMotion step{target, 0, 0};
  const auto mrac = [&](Real q, Real v, const MracState& c, MracState& rate) {
    return mrac_control(settings, c, q, v, step, rate).u;
  };
  // A PD tuned at 1x for the same t_s: critically damped on the arm's inertia at 1x.
  const Real J1 = 0.01 + 0.25, lambda = 4 / t_s;
  const auto pd = [&](Real q, Real v, const MracState&, MracState& rate) {
    rate = MracState{};
    return J1 * lambda * lambda * (target - q) - 2 * J1 * lambda * v;
  };
  for (Real payload : {1.0, 5.0}) {
    const StepResponse a = run_arm(payload, target, 3 * t_s, mrac);
    const StepResponse b = run_arm(payload, target, 3 * t_s, pd);
    std::printf("payload %.0fx: MRAC settles at %.3f t_s, overshoot %.1f%%; PD %.3f t_s, %.1f%%\n",
                payload, a.settle / t_s, 100 * a.overshoot, b.settle / t_s, 100 * b.overshoot);
    // MRAC within t_s +- 20% at both payloads with the same settings, without overshoot.
    EXPECT_GT(a.settle, 0.8 * t_s) << payload;
    EXPECT_LT(a.settle, 1.2 * t_s) << payload;
    EXPECT_LT(a.overshoot, 0.01) << payload;
    // The PD tuned at 1x rings at 5x: its overshoot and late settling are what MRAC removes.
    if (payload == 5.0) {
      EXPECT_GT(b.overshoot, 0.3);
      EXPECT_GT(b.settle, 1.5 * t_s);
    }
  }
}

// Held level (q_d = 0) against gravity, which pulls with m g 0.5 m (4.9 N m at 1x): the book's
// u = K x + K_r r is 0 at x = r = 0, so the arm sags until its gains have grown to hold it; with
// the adaptive bias (beyond the book) the holding torque is learnt as a gain and the sag is gone
// within a few t_s. And a step with the bias still settles within t_s +- 20% at 1x and 5x.
TEST(Mrac, AdaptiveBiasHoldsTheArmLevelAgainstGravity) {
  const Real t_s = 0.3;
  MracSettings book, bias;
  book.settling_time = bias.settling_time = t_s;
  bias.adaptive_bias = true;
  for (Real payload : {1.0, 5.0}) {
    Real sag[2][2];  // [book, bias][at 1 s, at 4 s]
    for (int law = 0; law < 2; ++law) {
      const MracSettings& settings = law == 0 ? book : bias;
      const auto hold = [&](Real q, Real v, const MracState& c, MracState& rate) {
        return mrac_control(settings, c, q, v, DesiredMotion{}, rate).u;
      };
      for (int at = 0; at < 2; ++at) {
        run_arm(payload, 1.0, at == 0 ? 1.0 : 4.0, hold, nullptr, &sag[law][at]);
      }
    }
    std::printf(
        "payload %.0fx held level: book's law %.4f rad at 1 s, %.4f at 4 s; with the "
        "adaptive bias %.2e, %.2e\n",
        payload, sag[0][0], sag[0][1], sag[1][0], sag[1][1]);
    EXPECT_GT(std::abs(sag[0][1]), 0.01) << payload;  // the book's law still sags at 4 s
    EXPECT_LT(std::abs(sag[1][0]), 0.1 * std::abs(sag[0][0])) << payload;
    EXPECT_LT(std::abs(sag[1][1]), 1e-3) << payload;
    const DesiredMotion step{1.0, 0, 0};
    const auto mrac = [&](Real q, Real v, const MracState& c, MracState& rate) {
      return mrac_control(bias, c, q, v, step, rate).u;
    };
    const StepResponse r = run_arm(payload, 1.0, 3 * t_s, mrac);
    std::printf("  a step with the bias settles at %.3f t_s, overshoot %.1f%%\n", r.settle / t_s,
                100 * r.overshoot);
    EXPECT_GT(r.settle, 0.8 * t_s) << payload;
    EXPECT_LT(r.settle, 1.2 * t_s) << payload;
  }
}

// A smooth joint trajectory's desired rate and acceleration are the derivatives of its position:
// central differences agree to O(h^2) inside each interval.
TEST(Mrac, TrajectoryGivesTheDerivativesOfItsPosition) {
  const std::vector<Keyframe> keys = {{0, 0}, {0.4, 0.8}, {0.9, -0.3}, {1.5, 0.5}};
  const Real h = 1e-5;
  for (Real t : {0.1, 0.33, 0.5, 0.77, 1.2, 1.45}) {
    const DesiredMotion d = desired_motion(Interpolation::smooth, keys, t);
    const auto q = [&](Real s) { return evaluate_keys(Interpolation::smooth, keys, s); };
    EXPECT_NEAR(d.q_dot, (q(t + h) - q(t - h)) / (2 * h), 1e-8) << t;
    EXPECT_NEAR(d.q_ddot, (q(t + h) - 2 * q(t) + q(t - h)) / (h * h), 1e-4) << t;
  }
}

// MRAC follows a smooth trajectory (0 -> 0.8 -> -0.3 -> 0.5 rad over 1.5 s) with the arm at 1x
// and 5x its payload: RMS error under 1% of the trajectory's range, settings unchanged.
TEST(Mrac, FollowsASmoothTrajectoryWithinOnePercentOfItsRange) {
  const std::vector<Keyframe> keys = {{0, 0}, {0.4, 0.8}, {0.9, -0.3}, {1.5, 0.5}};
  MracSettings settings;
  settings.settling_time = 0.1;
  for (Real payload : {1.0, 5.0}) {
    Real t = 0, sum = 0;
    int samples = 0;
    const auto mrac = [&](Real q, Real v, const MracState& c, MracState& rate) {
      return mrac_control(settings, c, q, v, desired_motion(Interpolation::smooth, keys, t), rate)
          .u;
    };
    // Its own loop (run_arm knows no clock): the desired motion is read at each step's start.
    const FigureModel figure = arm(payload);
    FigureWorkspace ws;
    size_figure_workspace(figure, ws);
    Real q = 0, v = 0;
    MracState c = mrac_start(0, 0);
    const Real h = 2.5e-4;
    for (int k = 0; k * h < 1.5; ++k) {
      // Semi-implicit Euler on the arm and the controller, the controller's rates at the step's
      // start.
      t = k * h;
      MracState rate;
      const Real u = mrac(q, v, c, rate);
      Real qdd = 0;
      forward_dynamics(figure, &q, &v, &u, {}, kGravity, ws, &qdd);
      v += h * qdd;
      q += h * v;
      c.x_m += h * rate.x_m;
      c.K_integral += h * rate.K_integral;
      c.Kr_integral += h * rate.Kr_integral;
      const Real error = q - evaluate_keys(Interpolation::smooth, keys, t + h);
      sum += error * error;
      ++samples;
    }
    const Real rms = std::sqrt(sum / samples), range = 1.1;
    std::printf("payload %.0fx: RMS tracking error %.4f rad, %.2f%% of the range\n", payload, rms,
                100 * rms / range);
    EXPECT_LT(rms, 0.01 * range) << payload;
  }
}

// A limit below the torque that holds the arm at the target (m g l sin 1 = 4.1 N m): every output
// stays within it, the integrals stop while it is reached, and the arm stays short of the target.
TEST(Mrac, TorqueLimitIsNeverExceededAndFreezesTheAdaptation) {
  const Real t_s = 0.3, limit = 3.0;
  MracSettings settings;
  settings.settling_time = t_s;
  settings.max_output = limit;
  const DesiredMotion step{1.0, 0, 0};
  int saturated = 0, frozen = 0;
  const auto mrac = [&](Real q, Real v, const MracState& c, MracState& rate) {
    const MracOutput out = mrac_control(settings, c, q, v, step, rate);
    if (out.saturated) {
      ++saturated;
      frozen += rate.K_integral.isZero(0) && rate.Kr_integral == 0;
    }
    return out.u;
  };
  Real max_u = 0;
  const StepResponse r = run_arm(1.0, 1.0, 3 * t_s, mrac, &max_u);
  std::printf("limit %.1f N m: largest |u| %.6f, %d of the evaluations saturated\n", limit, max_u,
              saturated);
  EXPECT_LE(max_u, limit);
  EXPECT_GT(saturated, 100);
  EXPECT_EQ(frozen, saturated);
  EXPECT_GT(r.settle, 2.9 * t_s);  // never within 10% of the target: the limit holds it back
}

}  // namespace
}  // namespace pbm
