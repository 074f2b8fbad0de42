#include "sim/level_of_detail.h"

#include <algorithm>
#include <cmath>

#include "collide/rigid_contact.h"

namespace pbm {
namespace {

// How far ahead a body's reach is taken, in frames: the decision holds for one frame, and a
// second covers a body that wakes with a contact just past the frame's end.
constexpr Real kLookaheadFrames = 2;
// Slack on every reach, relative to the body's radius (the sphere bounds the nodes, the nodes
// bound the surface between them only to within the mesh's sag).
constexpr Real kReachSlack = 0.1;

using Reach = BodyReach;

Reach reach_of(const BodyModel& body, const VecX& q, const VecX& v, const BodyWorkspace& bw,
               const Vec3& gravity, Real lookahead) {
  Reach r;
  r.centre = position_of(body_q(body, q));
  for (const Vec3& x : bw.x) r.radius = std::max(r.radius, (x - r.centre).norm());
  const auto vb = body_v(body, v);
  const Real speed = velocity_of(vb).norm() + omega_of(vb).norm() * r.radius;
  r.travel =
      speed * lookahead + 0.5 * gravity.norm() * lookahead * lookahead + kReachSlack * r.radius;
  return r;
}

bool pulled(const Model& model, int b, Real t0, Real t1) {
  for (const SpringModel& s : model.springs) {
    if (s.body == b && s.t_begin <= t1 && s.t_end >= t0 && s.stiffness > 0) return true;
  }
  return false;
}

// Energy the displacements hold: 1/2 sum m_i |d-dot_i|^2 + 1/2 q_d^T K_dd q_d [J] (uses K_q).
Real local_energy(const BodyModel& body, const VecX& q, const VecX& v, BodyWorkspace& bw) {
  const auto d = displacement_of(body.layout, body_q(body, q));
  const auto d_dot = displacement_rate_of(body.layout, body_v(body, v));
  bw.K_q.setZero();
  add_membrane_forces(body.tessellation, body.stiffness, d, bw.K_q);
  Real kinetic = 0;
  for (int i = 0; i < body.n_nodes(); ++i) {
    kinetic += body.node_mass[i] * d_dot.segment<3>(3 * i).squaredNorm();
  }
  return 0.5 * kinetic + 0.5 * d.dot(bw.K_q);
}

Real largest_node_norm(const Eigen::Ref<const VecX>& x) {
  Real worst = 0;
  for (Eigen::Index i = 0; i + 2 < x.size(); i += 3)
    worst = std::max(worst, x.segment<3>(i).norm());
  return worst;
}

}  // namespace

bool auto_levels_present(const Model& model) {
  for (const BodyModel& body : model.bodies) {
    if (body.auto_level) return true;
  }
  return false;
}

bool choose_levels(const Model& model, State& state, Workspace& ws, LevelStats& stats) {
  const int n = static_cast<int>(model.bodies.size());
  if (state.dormant.size() != model.bodies.size()) state.dormant.assign(model.bodies.size(), 0);
  bool slept = false;
  if (auto_levels_present(model)) {
    const Real frame = 1.0 / model.solver.fps;
    const Real lookahead = kLookaheadFrames * frame;
    const Vec3& gravity = ws.drive.gravity;
    // Every body's reach: the auto bodies look at all of them.
    std::vector<BodyReach>& reach = ws.level_reach;
    reach.resize(static_cast<std::size_t>(n));
    for (int b = 0; b < n; ++b) {
      reach[b] = reach_of(model.bodies[b], state.q, state.v, ws.bodies[b], gravity, lookahead);
    }
    Real obstacle_speed = 0;
    for (const ObstacleModel& o : ws.drive.obstacles) {
      obstacle_speed = std::max(obstacle_speed, o.velocity.norm() + o.angular_velocity.norm());
    }
    const bool bodies_collide = model.body_collisions.options.enabled;
    // Segments that collide with bodies (sim/segment_body_collisions.h) keep every auto body
    // awake: their reach would need the figures' kinematics at each frame's start, and a dormant
    // body has no q_d for a segment to dent.
    bool segments_collide = false;
    for (const FigureDef& def : model.scene.figures) segments_collide |= def.body_collisions;
    for (int b = 0; b < n; ++b) {
      const BodyModel& body = model.bodies[b];
      if (!body.auto_level) continue;
      const auto q_d = displacement_of(body.layout, body_q(body, state.q));
      const auto d_dot = displacement_rate_of(body.layout, body_v(body, state.v));
      const Real dent = largest_node_norm(q_d), dent_rate = largest_node_norm(d_dot);
      const Reach& r = reach[b];
      bool wake = state.dormant[b] && (dent > 0 || dent_rate > 0);  // dented while dormant
      wake = wake || pulled(model, b, state.time, state.time + lookahead) || segments_collide;
      if (!wake && !ws.drive.obstacles.empty()) {
        const Real clearance = min_obstacle_distance(ws.drive.obstacles, ws.bodies[b]);
        wake = clearance < r.travel + obstacle_speed * (1 + r.radius) * lookahead;
      }
      for (int o = 0; o < n && !wake && bodies_collide; ++o) {
        if (o == b || model.body_collisions.joined_pair(std::min(o, b), std::max(o, b))) continue;
        const Real gap = (reach[o].centre - r.centre).norm() - reach[o].radius - r.radius;
        wake = gap < r.travel + reach[o].travel + model.body_collisions.options.margin;
      }
      if (wake) {
        if (state.dormant[b]) ++stats.switches;
        state.dormant[b] = 0;
        continue;
      }
      if (state.dormant[b]) continue;
      // Awake, far from everything: off once the dents have died down.
      const Real small = kSleepDisplacement * r.radius;
      if (dent > small || dent_rate * frame > small) continue;
      stats.energy_jump =
          std::max(stats.energy_jump, local_energy(body, state.q, state.v, ws.bodies[b]));
      stats.position_jump = std::max(stats.position_jump, dent);
      displacement_of(body.layout, body_q(body, state.q)).setZero();
      displacement_rate_of(body.layout, body_v(body, state.v)).setZero();
      state.dormant[b] = 1;
      ++stats.switches;
      slept = true;
    }
  }
  stats.dormant_bodies = 0;
  for (int b = 0; b < n; ++b) {
    ws.bodies[b].dormant = state.dormant[b] != 0;
    stats.dormant_bodies += state.dormant[b] != 0;
  }
  return slept;
}

Real frame_substep(const Model& model, const State& state) {
  if (!auto_levels_present(model)) return model.substep;
  return stable_substep(model, state.dormant, nullptr);
}

}  // namespace pbm
