// Decoupled model reference adaptive control of one degree of freedom (sec. 15.4, (15.10)-
// (15.17)): a critically damped reference model the DOF should behave like, driven by the input
// that inverts it onto the desired trajectory (15.14), and a control law u = K x + K_r r whose
// gains adapt by integrals of the model-following error (15.16), (15.17). The integrals freeze
// while the output is at its limit (end of sec. 15.4.2).
//
// The controller's own state (reference model and integrals) changes later frames, so it lives in
// State and is integrated with the plant: mrac_control returns its rates.
#pragma once

#include <limits>

#include "core/types.h"

namespace pbm {

struct MracSettings {
  Real settling_time = 0.3;  // t_s [s]: time to come within 10% of a step, no overshoot
  // Adaptation of (15.16), (15.17): integral (alpha) and proportional (beta). The book finds a
  // wide range works; on a 0.5 m arm (tests/test_mrac.cpp) these settle a step within
  // 0.93-0.96 t_s and follow a smooth trajectory within 0.4-0.7% of its range at 1x and 5x
  // payload; beta 10 is too stiff for a 0.5 ms explicit step.
  Real alpha = 10.0;
  Real beta = 2.0;
  // Beyond the book: an adaptive bias u_b added to u, adapted from the same error with a
  // regressor of 1 (u_b = alpha int y + beta y). The book's u = K x + K_r r is 0 at x = r = 0, so a
  // DOF held at 0 against gravity sags until K grows (a 1 kg arm held level is still 0.066 rad
  // low after 4 s, tests/test_mrac.cpp); the bias learns the holding torque as the gains learn
  // the rest (6.7e-11 rad after 4 s).
  bool adaptive_bias = false;
  Real max_output = std::numeric_limits<Real>::infinity();  // |u| limit [N m or N]
};

// The reference model (15.11) of a settling time: a_m1 = b_m = lambda^2, a_m2 = 2 lambda,
// lambda = 4 / t_s.
struct MracReference {
  Real a1 = 0, a2 = 0, b = 0;
};
MracReference mrac_reference(Real settling_time);

// The controller's state: the reference model's (q_m, q_m-dot), the integrals of (15.16)
// (a 1 x 2 gain) and (15.17), and the adaptive bias's (0 without it).
struct MracState {
  Vec2 x_m = Vec2::Zero();
  Vec2 K_integral = Vec2::Zero();
  Real Kr_integral = 0;
  Real bias_integral = 0;
};

// The desired trajectory of the DOF at one time: q_d, q_d-dot and q_d-ddot.
struct DesiredMotion {
  Real q = 0, q_dot = 0, q_ddot = 0;
};

struct MracOutput {
  Real u = 0;              // the control force or torque, within the limit
  bool saturated = false;  // the limit cut it (the integrals are frozen)
  Real r = 0;              // the model input (15.14)
};

// u for the DOF at (q, q_dot) following `desired`, and the rates of the controller's state
// (reference model (15.11) and integrals, zero while saturated) in `rate`.
MracOutput mrac_control(const MracSettings& settings, const MracState& state, Real q, Real q_dot,
                        const DesiredMotion& desired, MracState& rate);

// The reference model started at the DOF's state, integrals zero: no jump at switch-on.
MracState mrac_start(Real q, Real q_dot);

}  // namespace pbm
