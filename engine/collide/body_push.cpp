#include "collide/body_push.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "deform/body_dynamics.h"

namespace pbm {
namespace {

// Critical damping of each pair's spring (at most one step's worth, c dt <= m): the global
// surfaces meet without a bounce, as the book's balloons collide "inelastically" (sec. 7.4).
constexpr Real kPushDampingRatio = 1.0;
// [1/s]: the fastest the push parts two overlapping global surfaces, per metre of overlap.
constexpr Real kOverlapRecovery = 5.0;
constexpr Real kInfinite = std::numeric_limits<Real>::infinity();
constexpr Real kUnitPushWeight = 1.0;

struct PushPair {
  int contact = 0;
  Real phi = 0, stiffness = 0, mobility = 0, approach = 0;
};

}  // namespace

GlobalPoint global_point(const BodyModel& body, const BodyWorkspace& bw,
                         const Eigen::Ref<const VecX>& q, const Eigen::Ref<const VecX>& v, int k) {
  if (!body.has_local) return {bw.x[k], bw.x_dot[k]};
  Vec3 r = omega_of(v).cross(bw.s[k]);
  if (body.n_s > 0) r += J_times(bw, k, v.data() + BodyLayout::kShapeInV);
  return {position_of(q) + bw.R * bw.s[k], velocity_of(v) + bw.R * r};
}

void push_direction(const BodyModel& body, const BodyWorkspace& bw, const int* nodes,
                    const Real* weights, int count, const Vec3& y_world, VecX& g) {
  const Vec3 y = bw.R.transpose() * y_world;
  g.setZero(body.n_generalized());
  for (int k = 0; k < count; ++k) {
    const int i = nodes[k];
    const Vec3& s = body.has_local ? bw.s[i] : bw.p[i];
    linear_part(g) += weights[k] * y;
    angular_part(g) += weights[k] * s.cross(y);
    if (body.n_s > 0) add_Jt_y(bw, i, y, weights[k], g.data() + BodyLayout::kShapeInV);
  }
}

Real push_impulse(Real stiffness, Real mass, Real phi, Real approach, Real dt) {
  const Real rate = 1.0 / dt;
  const Real k = std::min(stiffness, mass * rate * rate);
  // At most what stops the pair's approach in this step and then parts the global points at
  // kOverlapRecovery times their overlap (see the header).
  const Real target = approach + kOverlapRecovery * (-phi);
  if (!(target > 0)) return 0;
  const Real c_d = std::min(2 * kPushDampingRatio * std::sqrt(k * mass), mass * rate);
  const Real f = k * (-phi) + c_d * approach;
  return std::min(dt * std::max(0.0, f), mass * target);
}

std::vector<Real> node_contact_stiffness(const BodyModel& body) {
  std::vector<Real> k;
  if (!body.has_local) return k;
  k.assign(static_cast<std::size_t>(body.n_nodes()), 0.0);
  for (const ContactSample& sample : body.contact_samples) {
    for (int j = 0; j < 3; ++j) k[sample.nodes[j]] += sample.weights[j] * sample.stiffness;
  }
  return k;
}

BodyPushStats apply_body_push(const BodySet& set, BodyCollisionWorkspace& cws, Real elasticity,
                              Real dt) {
  BodyPushStats stats;
  if (!(elasticity > 0) || !(dt > 0) || cws.contacts.empty()) return stats;
  const int n_bodies = static_cast<int>(set.models.size());
  auto slice_q = [&](int b) { return set.q.segment(set.models[b].q_offset, set.models[b].q_size); };
  auto slice_v = [&](int b) { return set.v.segment(set.models[b].v_offset, set.models[b].v_size); };
  auto moves = [&](int b) { return set.models[b].order == DynamicsOrder::second; };
  std::vector<PushPair> pairs;
  std::vector<Real> pair_stiffness(static_cast<std::size_t>(n_bodies * n_bodies), 0.0);
  VecX g, a_inv_g;
  std::vector<char> factored(static_cast<std::size_t>(n_bodies), 0);
  auto ensure_mass = [&](int b) {
    if (factored[b]) return;
    factor_generalized_mass(set.models[b], slice_q(b), set.ws[b]);
    factored[b] = 1;
  };
  for (int index = 0; index < static_cast<int>(cws.contacts.size()); ++index) {
    const BodyContact& c = cws.contacts[index];
    const BodyModel& A = set.models[c.body_a];
    const BodyModel& B = set.models[c.body_b];
    if (c.body_a == c.body_b || (!A.has_local && !B.has_local)) continue;
    if (!moves(c.body_a) && !moves(c.body_b)) continue;
    const BodyWorkspace& bwa = set.ws[c.body_a];
    const BodyWorkspace& bwb = set.ws[c.body_b];
    const GlobalPoint pa = global_point(A, bwa, slice_q(c.body_a), slice_v(c.body_a), c.node_a);
    GlobalPoint pb;
    for (int k = 0; k < 3; ++k) {
      const GlobalPoint p =
          global_point(B, bwb, slice_q(c.body_b), slice_v(c.body_b), c.nodes_b[k]);
      pb.x += c.w_b[k] * p.x;
      pb.x_dot += c.w_b[k] * p.x_dot;
    }
    const Vec3 n = c.basis.col(0);
    const Real phi = n.dot(pa.x - pb.x);
    if (!(phi < 0)) continue;
    // (5.11) with f_i = K_ii (dent): two dents in series, a side without q_d is infinitely stiff.
    const auto& ka = cws.bodies[c.body_a].stiffness;
    const auto& kb = cws.bodies[c.body_b].stiffness;
    const Real k_a = A.has_local ? ka[c.node_a] : kInfinite;
    Real k_b = kInfinite;
    if (B.has_local)
      k_b = c.w_b[0] * kb[c.nodes_b[0]] + c.w_b[1] * kb[c.nodes_b[1]] + c.w_b[2] * kb[c.nodes_b[2]];
    const Real series = k_a == kInfinite ? k_b : k_b == kInfinite ? k_a : k_a * k_b / (k_a + k_b);
    if (!(series > 0)) continue;
    PushPair p;
    p.contact = index;
    p.phi = phi;
    p.stiffness = elasticity * series;
    p.approach = -n.dot(pa.x_dot - pb.x_dot);
    // The inverse of the mass the pair moves with along n, through both sides' A^+.
    if (moves(c.body_a)) {
      ensure_mass(c.body_a);
      push_direction(A, bwa, &c.node_a, &kUnitPushWeight, 1, n, g);
      solve_generalized_mass(set.ws[c.body_a], g, a_inv_g);
      p.mobility += g.dot(a_inv_g);
    }
    if (moves(c.body_b)) {
      ensure_mass(c.body_b);
      push_direction(B, bwb, c.nodes_b.data(), c.w_b.data(), 3, n, g);
      solve_generalized_mass(set.ws[c.body_b], g, a_inv_g);
      p.mobility += g.dot(a_inv_g);
    }
    if (!(p.mobility > 0)) continue;
    const int lo = std::min(c.body_a, c.body_b), hi = std::max(c.body_a, c.body_b);
    pair_stiffness[lo * n_bodies + hi] += p.stiffness;
    pairs.push_back(p);
    ++stats.pressing;
    stats.max_overlap = std::max(stats.max_overlap, -phi);
  }
  if (pairs.empty()) return stats;
  // Jacobi: every force from the state the contacts were resolved to, then all applied.
  std::vector<Real> impulse(pairs.size(), 0.0);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PushPair& pair = pairs[p];
    const BodyContact& c = cws.contacts[pair.contact];
    const int lo = std::min(c.body_a, c.body_b), hi = std::max(c.body_a, c.body_b);
    const Real share = pair.stiffness / pair_stiffness[lo * n_bodies + hi];
    impulse[p] = push_impulse(pair.stiffness, share / pair.mobility, pair.phi, pair.approach, dt);
  }
  std::vector<char> changed(static_cast<std::size_t>(n_bodies), 0);
  auto apply = [&](int b, const int* nodes, const Real* weights, int count, const Vec3& J) {
    if (!moves(b)) return;
    const BodyModel& body = set.models[b];
    BodyWorkspace& bw = set.ws[b];
    push_direction(body, bw, nodes, weights, count, J, g);
    solve_generalized_mass(bw, g, a_inv_g);
    auto v = slice_v(b);
    velocity_of(v) += bw.R * linear_part(a_inv_g);
    after_translation(v, body.n_generalized()) += after_translation(a_inv_g, body.n_generalized());
    changed[b] = 1;
  };
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (impulse[p] == 0) continue;
    const BodyContact& c = cws.contacts[pairs[p].contact];
    const Vec3 J = impulse[p] * c.basis.col(0);
    apply(c.body_a, &c.node_a, &kUnitPushWeight, 1, J);
    apply(c.body_b, c.nodes_b.data(), c.w_b.data(), 3, -J);
    stats.impulse += impulse[p];
  }
  for (int b = 0; b < n_bodies; ++b) {
    if (changed[b])
      compute_body_kinematics(set.models[b], slice_q(b), slice_v(b), set.ws[b], false);
  }
  return stats;
}

}  // namespace pbm
