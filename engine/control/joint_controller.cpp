#include "control/joint_controller.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "control/ball_coordinates.h"
#include "control/joint_trajectory.h"

namespace pbm {

namespace {

MracState unpack(const Real* s) {
  MracState m;
  m.x_m = Vec2(s[0], s[1]);
  m.K_integral = Vec2(s[2], s[3]);
  m.Kr_integral = s[4];
  m.bias_integral = s[5];
  return m;
}

void pack(const MracState& m, Real* s) {
  s[0] = m.x_m[0];
  s[1] = m.x_m[1];
  s[2] = m.K_integral[0];
  s[3] = m.K_integral[1];
  s[4] = m.Kr_integral;
  s[5] = m.bias_integral;
}

}  // namespace

ControlledCoordinate controlled_coordinate(const JointController& c, const Real* q, const Real* v) {
  if (!c.ball) return {.x = q[c.q_index], .x_dot = v[c.v_index]};
  const int k = c.def.dof;
  const Vec3 r = ball_rotation_vector(q + c.q_index);
  const Mat3 J = ball_rate_map(r);
  const Vec3 omega(v[c.v_index - k], v[c.v_index - k + 1], v[c.v_index - k + 2]);
  return {.x = r[k], .x_dot = J.row(k).dot(omega), .torque = J.row(k).transpose()};
}

void add_controller_output(const JointController& c, const ControlledCoordinate& x, Real u,
                           Real* tau) {
  if (!c.ball) {
    tau[c.v_index] += u;
    return;
  }
  Real* omega = tau + c.v_index - c.def.dof;
  for (int i = 0; i < 3; ++i) omega[i] += u * x.torque[i];
}

DesiredMotion controller_desired(const JointController& c, Real t,
                                 const std::optional<LiveKey>& held) {
  if (held && held->time <= t) return live_desired(*held, t);
  const std::vector<LiveKey>& live = c.def.live;
  // The last live key at or before t (times strictly increase).
  const auto after = std::upper_bound(
      live.begin(), live.end(), t, [](Real time, const LiveKey& key) { return time < key.time; });
  if (after != live.begin()) return live_desired(*std::prev(after), t);
  return desired_motion(c.def.interpolation, c.def.keys, t);
}

ControlSample explicit_control(const JointController& c, Real t, Real q, Real q_dot,
                               const Real* state, Real* rate, const std::optional<LiveKey>& held) {
  const DesiredMotion d = controller_desired(c, t, held);
  ControlSample out{.desired = d.q, .reference = d.q, .actual = q};
  if (c.def.kind == ControllerKind::mrac) {
    MracState r;
    const MracOutput u = mrac_control(c.mrac, unpack(state), q, q_dot, d, r);
    pack(r, rate);
    out.reference = state[0];
    out.output = u.u;
    out.saturated = u.saturated;
    return out;
  }
  const Real u = c.def.kp * (d.q - q) + c.def.kd * (d.q_dot - q_dot);
  const Real limit = c.def.max_output.value_or(std::numeric_limits<Real>::infinity());
  out.saturated = std::abs(u) > limit;
  out.output = std::clamp(u, -limit, limit);
  return out;
}

void controller_start(const JointController& c, Real q, Real q_dot, Real* state) {
  if (c.def.kind == ControllerKind::mrac) pack(mrac_start(q, q_dot), state);
}

}  // namespace pbm
