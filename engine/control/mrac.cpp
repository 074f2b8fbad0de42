#include "control/mrac.h"

#include <algorithm>
#include <cmath>

namespace pbm {

MracReference mrac_reference(Real settling_time) {
  const Real lambda = 4 / settling_time;
  return {lambda * lambda, 2 * lambda, lambda * lambda};
}

MracState mrac_start(Real q, Real q_dot) {
  MracState s;
  s.x_m = Vec2(q, q_dot);
  return s;
}

MracOutput mrac_control(const MracSettings& settings, const MracState& state, Real q, Real q_dot,
                        const DesiredMotion& desired, MracState& rate) {
  const MracReference m = mrac_reference(settings.settling_time);
  const Real t_s = settings.settling_time;
  const Vec2 x(q, q_dot);
  MracOutput out;
  // (15.14): r = B_m^+ (x_d-dot - A_m x_d), the input that drives the model onto x_d.
  out.r = (desired.q_ddot + m.a1 * desired.q + m.a2 * desired.q_dot) / m.b;
  // (15.12), (15.15): the model-following error, weighted as the model's own dynamics.
  const Vec2 x_e = state.x_m - x;
  const Real y = 16 / (t_s * t_s) * x_e[0] + 4 / t_s * x_e[1];
  // (15.16), (15.17): gains = integral part + proportional part; (15.13): u = K x + K_r r, plus
  // the adaptive bias when asked (beyond the book, MracSettings).
  const Vec2 K = state.K_integral + settings.beta * y * x;
  const Real Kr = state.Kr_integral + settings.beta * y * out.r;
  const Real bias = settings.adaptive_bias ? state.bias_integral + settings.beta * y : 0;
  const Real u = K.dot(x) + Kr * out.r + bias;
  out.saturated = std::abs(u) > settings.max_output;
  out.u = std::clamp(u, -settings.max_output, settings.max_output);
  // The model runs beside the plant (15.11); the integrals stop while the output is cut.
  rate.x_m = Vec2(state.x_m[1], -m.a1 * state.x_m[0] - m.a2 * state.x_m[1] + m.b * out.r);
  rate.K_integral = out.saturated ? Vec2::Zero() : Vec2(settings.alpha * y * x);
  rate.Kr_integral = out.saturated ? 0 : settings.alpha * y * out.r;
  rate.bias_integral = out.saturated || !settings.adaptive_bias ? 0 : settings.alpha * y;
  return out;
}

}  // namespace pbm
