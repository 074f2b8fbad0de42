#include "sim/state.h"

#include <cstring>

namespace pbm {

Mat3 rotation_from_quaternion(const Vec4& q) {
  const Vec4 n = q.normalized();
  const Real s = n[0], v1 = n[1], v2 = n[2], v3 = n[3];
  Mat3 R;  // (3.7)
  R << 1 - 2 * (v2 * v2 + v3 * v3), 2 * (v1 * v2 - s * v3), 2 * (v1 * v3 + s * v2),
      2 * (v1 * v2 + s * v3), 1 - 2 * (v1 * v1 + v3 * v3), 2 * (v2 * v3 - s * v1),
      2 * (v1 * v3 - s * v2), 2 * (v2 * v3 + s * v1), 1 - 2 * (v1 * v1 + v2 * v2);
  return R;
}

Vec4 quaternion_rate(const Vec4& q, const Vec3& w) {
  // 1/2 q (x) (0, omega): the inverse of omega = G q-dot (A.2, A.3) for a body-frame omega.
  const Real s = q[0], x = q[1], y = q[2], z = q[3];
  return 0.5 * Vec4(-x * w.x() - y * w.y() - z * w.z(), s * w.x() + y * w.z() - z * w.y(),
                    s * w.y() + z * w.x() - x * w.z(), s * w.z() + x * w.y() - y * w.x());
}

State initial_state(const Model& model) {
  State st;
  st.time = 0;
  st.q.setZero(model.n_q);
  st.v.setZero(model.n_v);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    const BodyDef& def = model.scene.bodies[b];
    auto q = st.q.segment(body.q_offset, body.q_size);
    auto v = st.v.segment(body.v_offset, body.v_size);
    q.segment<3>(0) = def.position;
    const Vec4 quat = def.orientation.normalized();
    q.segment<4>(3) = quat;
    if (body.n_s > 0) q.segment(7, body.n_s) = body.q_s_fixed;
    v.segment<3>(0) = def.velocity;
    v.segment<3>(3) = rotation_from_quaternion(quat).transpose() * def.angular_velocity;
  }
  return st;
}

std::uint64_t hash_state(const State& state) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= bytes[i];
      h *= 1099511628211ull;
    }
  };
  mix(&state.time, sizeof state.time);
  mix(state.q.data(), sizeof(Real) * state.q.size());
  mix(state.v.data(), sizeof(Real) * state.v.size());
  return h;
}

}  // namespace pbm
