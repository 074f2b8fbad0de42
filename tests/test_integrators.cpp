// The time integrators (integrate/integrators.h, sec. 6.1) on the harmonic oscillator
// x'' = -w^2 x, whose exact solution is x = cos(w t): the measured order of convergence under dt
// halving (1 for the book's Euler, 4 for RK4), RK45 holding its tolerance over many periods, and
// the explicit Euler's stability limit w dt < 2 (the bound a body's substep must respect). Also
// the superquadric (2.7) against its implicit equation at random parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "deform/superquadric.h"
#include "integrate/integrators.h"

namespace pbm {
namespace {

constexpr Real kOmega = 3.0;  // [rad/s]

struct Oscillator {
  VecX q = VecX::Constant(1, 1.0), v = VecX::Zero(1);
  IntegratorWorkspace ws;
  IntegrationStats stats;
  Oscillator() { ws.resize(1, 1); }
};

void rates(Real, const VecX& q, const VecX& v, VecX& q_dot, VecX& v_dot) {
  q_dot = v;
  v_dot = -kOmega * kOmega * q;
}
void kinematic(const VecX&, const VecX& v, VecX& q_dot) {
  q_dot = v;
}

// |x(T) - cos(w T)| after T = 2 s in steps of dt.
Real error_after(IntegratorKind kind, Real dt) {
  Oscillator o;
  const int steps = static_cast<int>(std::lround(2.0 / dt));
  auto f = rates;
  auto k = kinematic;
  for (int n = 0; n < steps; ++n) {
    const Real t = n * dt;
    if (kind == IntegratorKind::euler) {
      euler_step(f, k, t, dt, o.q, o.v, o.ws, o.stats);
    } else {
      rk4_step(f, t, dt, o.q, o.v, o.ws, o.stats);
    }
  }
  return std::abs(o.q[0] - std::cos(kOmega * steps * dt));
}

TEST(Integrators, OrderOfConvergenceUnderDtHalving) {
  for (const auto& [kind, name, expected] :
       {std::tuple{IntegratorKind::euler, "euler", 1.0}, {IntegratorKind::rk4, "rk4", 4.0}}) {
    Real previous = 0;
    for (Real dt : {0.02, 0.01, 0.005, 0.0025}) {
      const Real error = error_after(kind, dt);
      if (previous > 0) {
        const Real order = std::log2(previous / error);
        std::printf("%s: dt %.4f s, error %.3e, order %.3f\n", name, dt, error, order);
        EXPECT_NEAR(order, expected, 0.15) << name << " at dt " << dt;
      }
      previous = error;
    }
  }
}

// RK45 over ten periods, advanced one second at a time (several periods' worth of its own
// steps, so the step size is set by the error control alone): the error stays within a small
// multiple of the tolerance (its control is per step: the global error is their sum), and a
// tolerance 1000 times tighter buys an error at least 100 times smaller with more steps.
TEST(Integrators, Rk45HoldsItsToleranceOnTheOscillator) {
  Real errors[2] = {0, 0};
  int accepted[2] = {0, 0};
  const Real tolerances[2] = {1e-6, 1e-9};
  for (int i = 0; i < 2; ++i) {
    Oscillator o;
    Real step = 0;
    const Real frame = 1.0;
    const int frames = static_cast<int>(std::ceil(10 * 2 * std::numbers::pi / kOmega / frame));
    auto f = rates;
    for (int n = 0; n < frames; ++n) {
      ASSERT_TRUE(rk45_advance(f, n * frame, frame, tolerances[i], o.q, o.v, step, o.ws, o.stats));
      errors[i] = std::max(errors[i], std::abs(o.q[0] - std::cos(kOmega * (n + 1) * frame)));
    }
    accepted[i] = o.stats.accepted;
    std::printf(
        "rk45, tolerance %.0e: worst |x - cos(w t)| %.3e over 10 periods, %d steps "
        "accepted, %d rejected\n",
        tolerances[i], errors[i], o.stats.accepted, o.stats.rejected);
    EXPECT_LT(errors[i], 100 * tolerances[i]);
  }
  EXPECT_LT(errors[1], errors[0] / 100);
  EXPECT_GT(accepted[1], accepted[0]);  // it paid for the accuracy in steps
}

// The book's Euler (6.1) updates v, then q from the new v: on the oscillator it is stable for
// w dt < 2 and grows without bound past it. This is the limit the explicit substep of a body
// must stay under for its stiffest mode.
TEST(Integrators, EulerIsStableBelowOmegaDtTwoAndExplodesAbove) {
  for (const auto& [omega_dt, stable] : {std::pair{1.9, true}, {2.1, false}}) {
    Oscillator o;
    const Real dt = omega_dt / kOmega;
    auto f = rates;
    auto k = kinematic;
    Real largest = 0;
    for (int n = 0; n < 2000; ++n) {
      euler_step(f, k, n * dt, dt, o.q, o.v, o.ws, o.stats);
      largest = std::max(largest, std::abs(o.q[0]));
    }
    std::printf("euler at w dt = %.1f: largest |x| %.3g over 2000 steps\n", omega_dt, largest);
    if (stable) {
      EXPECT_LT(largest, 10.0);
    } else {
      EXPECT_GT(largest, 1e6);
    }
  }
}

// (2.7) e = a0 (a1 C_u^eps1 C_v^eps2, a2 C_u^eps1 S_v^eps2, a3 S_u^eps1) lies on
// (|x / a0 a1|^(2/eps2) + |y / a0 a2|^(2/eps2))^(eps2/eps1) + |z / a0 a3|^(2/eps1) = 1,
// for every shape from pinched (eps 0.1) to beyond the octahedron (eps 4).
TEST(Superquadric, PointsSatisfyTheImplicitEquationAtRandomParameters) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> size(0.3, 2.0), eps(0.1, 4.0);
  std::uniform_real_distribution<Real> lat(-1.5, 1.5), lon(-3.1, 3.1);
  Real worst = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    VecX q_s(6);
    q_s << size(rng), size(rng), size(rng), size(rng), eps(rng), eps(rng);
    Vec3 e;
    evaluate_superquadric(q_s, lat(rng), lon(rng), 1.0, e, nullptr);
    const Real a0 = q_s[0], e1 = q_s[4], e2 = q_s[5];
    const Real xy = std::pow(std::abs(e.x() / (a0 * q_s[1])), 2 / e2) +
                    std::pow(std::abs(e.y() / (a0 * q_s[2])), 2 / e2);
    const Real f = std::pow(xy, e2 / e1) + std::pow(std::abs(e.z() / (a0 * q_s[3])), 2 / e1);
    worst = std::max(worst, std::abs(f - 1));
  }
  std::printf("superquadric: worst |F(e) - 1| %.3g over 2000 random shapes and points\n", worst);
  EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace pbm
