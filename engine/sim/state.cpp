#include "sim/state.h"

#include <cstring>

#include "core/bits.h"

namespace pbm {

State initial_state(const Model& model) {
  State st;
  st.time = 0;
  st.q.setZero(model.n_q);
  st.v.setZero(model.n_v);
  st.dormant.assign(model.bodies.size(), 0);
  st.impulses_applied.assign(model.figures.size(), 0);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    const BodyDef& def = model.scene.bodies[b];
    auto q = st.q.segment(body.q_offset, body.q_size);
    auto v = st.v.segment(body.v_offset, body.v_size);
    position_of(q) = def.position;
    const Vec4 quat = def.orientation.normalized();
    quaternion_of(q) = quat;
    if (body.n_s > 0) shape_of(body.layout, q) = body.q_s_fixed;
    velocity_of(v) = def.velocity;
    omega_of(v) = rotation_from_quaternion(quat).transpose() * def.angular_velocity;
    // An "auto" body starts dormant; the first frame wakes it where it must be awake.
    st.dormant[b] = body.auto_level ? 1 : 0;
  }
  for (const CompiledFigure& figure : model.figures) {
    st.q.segment(figure.model.state_q_offset, figure.model.n_q) = figure.q0;
    st.v.segment(figure.model.state_v_offset, figure.model.n_v) = figure.v0;
    // No work done yet; each MRAC's reference model at its DOF, its integrals zero.
    Real* control = st.q.data() + figure.state_control_offset;
    for (const JointController& c : figure.controllers) {
      if (c.state_offset < 0) continue;
      const ControlledCoordinate x = controlled_coordinate(c, figure.q0.data(), figure.v0.data());
      controller_start(c, x.x, x.x_dot, control + c.state_offset);
    }
  }
  for (const LiquidModel& liquid : model.liquids) {
    st.liquids.push_back(initial_liquid_state(liquid, model.gravity));
  }
  return st;
}

std::uint64_t hash_state(const State& state) {
  std::uint64_t h = kFnvOffset;
  auto mix = [&h](const void* data, std::size_t n) { fnv1a_mix(h, data, n); };
  mix(&state.time, sizeof state.time);
  mix(state.q.data(), sizeof(Real) * state.q.size());
  mix(state.v.data(), sizeof(Real) * state.v.size());
  mix(&state.rk45_step, sizeof state.rk45_step);
  mix(&state.adaptive_level, sizeof state.adaptive_level);
  mix(&state.adaptive_calm, sizeof state.adaptive_calm);
  mix(&state.contact_nodes, sizeof state.contact_nodes);
  mix(&state.energy_surplus, sizeof state.energy_surplus);
  mix(&state.energy_scale, sizeof state.energy_scale);
  mix(&state.liquid_work, sizeof state.liquid_work);
  mix(state.dormant.data(), state.dormant.size());
  mix(state.impulses_applied.data(), sizeof(int) * state.impulses_applied.size());
  for (const LiquidState& liquid : state.liquids) hash_liquid_state(liquid, h);
  return h;
}

}  // namespace pbm
