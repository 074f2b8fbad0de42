#include "collide/body_collisions.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "collide/body_push.h"
#include "collide/contact_impulse.h"
#include "collide/rigid_contact.h"
#include "collide/triangle_geometry.h"
#include "core/wall_clock.h"
#include "deform/body_dynamics.h"

namespace pbm {
namespace {

using Clock = WallClock;
using Scratch = BodyCollisionWorkspace::BodyScratch;

bool sized_for(std::span<const BodyModel> bodies, const BodyCollisionWorkspace& cws) {
  if (cws.bodies.size() != bodies.size() || cws.broadphase.boxes.size() != bodies.size()) {
    return false;
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyModel& body = bodies[b];
    if (static_cast<int>(cws.bodies[b].x0.size()) != body.n_nodes() ||
        cws.bodies[b].nu.size() != body.n_generalized() ||
        cws.broadphase.boxes[b].size() != body.tessellation.triangles.size()) {
      return false;
    }
  }
  return true;
}

void size_workspace(std::span<const BodyModel> bodies, BodyCollisionWorkspace& cws) {
  if (sized_for(bodies, cws)) return;
  std::vector<int> counts;
  cws.bodies.assign(bodies.size(), Scratch{});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyModel& body = bodies[b];
    Scratch& s = cws.bodies[b];
    s.stiffness = node_contact_stiffness(body);
    const auto n = static_cast<std::size_t>(body.n_nodes());
    s.x0.assign(n, Vec3::Zero());
    s.x.assign(n, Vec3::Zero());
    s.x_dot0.assign(n, Vec3::Zero());
    s.x_dot.assign(n, Vec3::Zero());
    s.normal.assign(n, Vec3::Zero());
    s.nu.setZero(body.n_generalized());
    s.g.setZero(body.n_generalized());
    s.delta.setZero(body.n_generalized());
    const auto& tris = body.tessellation.triangles;
    s.triangle_start.assign(n + 1, 0);
    for (const std::array<int, 3>& t : tris) {
      for (int v : t) ++s.triangle_start[static_cast<std::size_t>(v) + 1];
    }
    for (std::size_t k = 1; k <= n; ++k) s.triangle_start[k] += s.triangle_start[k - 1];
    s.node_triangles.assign(3 * tris.size(), 0);
    std::vector<int> fill(s.triangle_start.begin(), s.triangle_start.end() - 1);
    for (std::size_t t = 0; t < tris.size(); ++t) {
      for (int v : tris[t]) s.node_triangles[fill[v]++] = static_cast<int>(t);
    }
    s.seen.assign(tris.size(), 0);
    s.stamp = 0;
    counts.push_back(static_cast<int>(body.tessellation.triangles.size()));
  }
  resize_broadphase(counts, cws.broadphase);
  // Room for a contact as large as the bodies' surfaces, so that one forming or spreading inside
  // a step does not allocate.
  std::size_t triangles = 0, nodes = 0;
  for (const BodyModel& body : bodies) {
    triangles += body.tessellation.triangles.size();
    nodes += static_cast<std::size_t>(body.n_nodes());
  }
  cws.pairs.reserve(2 * triangles);
  cws.contacts.reserve(nodes);
}

void compute_vertex_normals(const BodyModel& body, Scratch& s) {
  std::fill(s.normal.begin(), s.normal.end(), Vec3::Zero());
  for (const std::array<int, 3>& t : body.tessellation.triangles) {
    // Twice the area times the outward normal (triangles are counter-clockwise from outside).
    const Vec3 area = (s.x[t[1]] - s.x[t[0]]).cross(s.x[t[2]] - s.x[t[0]]);
    for (int v : t) s.normal[v] += area;
  }
  for (Vec3& n : s.normal) {
    const Real length = n.norm();
    if (length > 0) n /= length;
  }
}

// World velocity of node k of a rigid or global body from the scratch nu: R P_k nu (3.4).
Vec3 generalized_node_velocity(const BodyModel& body, const BodyWorkspace& bw, const Scratch& s,
                               int k) {
  Vec3 r = linear_part(s.nu) + angular_part(s.nu).cross(bw.p[k]);
  if (body.n_s > 0) r += J_times(bw, k, s.nu.data() + BodyLayout::kShapeInV);
  return bw.R * r;
}

// One side of a contact: a node (count 1, weight 1) or a triangle's point sum w_k x_k.
struct Side {
  int body = 0;
  const int* nodes = nullptr;
  const Real* weights = nullptr;
  int count = 1;
};

struct Bodies {
  const BodySet& set;
  BodyCollisionWorkspace& cws;
  // BodyCollisionModel::constrained: a rigid or global part held by a constraint (ch. 7) is not
  // translated by the projection; the other side is moved the whole way.
  const std::vector<char>& constrained;
  const BodyModel& body(const Side& side) const { return set.models[side.body]; }
  bool pinned(const Side& side) const {
    return constrained[side.body] != 0 && !set.models[side.body].has_local;
  }
  BodyWorkspace& bw(const Side& side) const { return set.ws[side.body]; }
  Scratch& scratch(const Side& side) const { return cws.bodies[side.body]; }
};

Vec3 side_velocity(const Bodies& all, const Side& side) {
  const BodyModel& body = all.body(side);
  const Scratch& s = all.scratch(side);
  Vec3 v = Vec3::Zero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    v += side.weights[k] *
         (body.has_local ? s.x_dot[i] : generalized_node_velocity(body, all.bw(side), s, i));
  }
  return v;
}

Vec3 side_position(const Bodies& all, const Side& side) {
  const BodyModel& body = all.body(side);
  const Scratch& s = all.scratch(side);
  Vec3 x = Vec3::Zero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    x += side.weights[k] * (body.has_local ? s.x[i] : Vec3(s.x0[i] + s.shift));
  }
  return x;
}

// L^T J = sum w_k P_k^T R^T J into s.g (rigid and global sides).
void generalized_impulse(const BodyModel& body, const BodyWorkspace& bw, const Side& side,
                         const Vec3& J, Scratch& s) {
  const Vec3 y = bw.R.transpose() * J;
  s.g.setZero();
  for (int k = 0; k < side.count; ++k) {
    const int i = side.nodes[k];
    const Real w = side.weights[k];
    linear_part(s.g) += w * y;
    angular_part(s.g) += w * bw.p[i].cross(y);
    if (body.n_s > 0) add_Jt_y(bw, i, y, w, s.g.data() + BodyLayout::kShapeInV);
  }
}

// Inverse of the mass the side moves with along the unit direction d.
Real side_inverse_mass(const Bodies& all, const Side& side, const Vec3& d) {
  const BodyModel& body = all.body(side);
  if (body.has_local) {
    Real sum = 0;
    for (int k = 0; k < side.count; ++k) {
      sum += side.weights[k] * side.weights[k] / body.node_mass[side.nodes[k]];
    }
    return sum;
  }
  Scratch& s = all.scratch(side);
  BodyWorkspace& bw = all.bw(side);
  generalized_impulse(body, bw, side, d, s);
  solve_generalized_mass(bw, s.g, s.delta);
  return s.g.dot(s.delta);
}

void apply_impulse(const Bodies& all, const Side& side, const Vec3& J) {
  const BodyModel& body = all.body(side);
  Scratch& s = all.scratch(side);
  s.touched = true;
  if (body.has_local) {
    for (int k = 0; k < side.count; ++k) {
      const int i = side.nodes[k];
      s.x_dot[i] += (side.weights[k] / body.node_mass[i]) * J;
    }
    return;
  }
  BodyWorkspace& bw = all.bw(side);
  generalized_impulse(body, bw, side, J, s);
  solve_generalized_mass(bw, s.g, s.delta);
  s.nu += s.delta;
}

// Moves the side by lambda times its positional inverse mass along n (local: the nodes, each
// by its weight over its mass; rigid and global: c, by 1 / M).
void apply_displacement(const Bodies& all, const Side& side, Real lambda, const Vec3& n) {
  const BodyModel& body = all.body(side);
  Scratch& s = all.scratch(side);
  s.touched = true;
  if (body.has_local) {
    for (int k = 0; k < side.count; ++k) {
      const int i = side.nodes[k];
      s.x[i] += (lambda * side.weights[k] / body.node_mass[i]) * n;
    }
  } else if (!all.pinned(side)) {
    s.shift += (lambda / body.mass) * n;
  }
}

Real position_inverse_mass(const Bodies& all, const Side& side) {
  const BodyModel& body = all.body(side);
  if (!body.has_local) return all.pinned(side) ? 0.0 : 1.0 / body.mass;
  return side_inverse_mass(all, side, Vec3::UnitX());
}

constexpr Real kUnitWeight = 1.0;

Side side_a(const BodyContact& c) {
  return Side{c.body_a, &c.node_a, &kUnitWeight, 1};
}

Side side_b(const BodyContact& c) {
  return Side{c.body_b, c.nodes_b.data(), c.w_b.data(), 3};
}

void make_basis(const Vec3& n, Mat3& basis) {
  const Vec3 t1 = n.unitOrthogonal();
  basis.col(0) = n;
  basis.col(1) = t1;
  basis.col(2) = n.cross(t1);
}

// Triangle `key` of each pair, with its partner `1 - key`, bucketed by a counting sort (the order
// within a bucket is the traversal's; pair_nodes does not depend on it).
void bucket_pairs(const std::vector<std::array<int, 2>>& pairs, int key, int n_triangles,
                  BodyCollisionWorkspace::Side& side) {
  std::vector<int>& start = side.start;
  start.assign(static_cast<std::size_t>(n_triangles) + 2, 0);
  for (const std::array<int, 2>& p : pairs) ++start[p[key] + 2];
  for (std::size_t t = 2; t < start.size(); ++t) start[t] += start[t - 1];
  side.partners.resize(pairs.size());
  // start[t + 1] runs from the start of t's bucket to its end, which leaves start[t] its start.
  for (const std::array<int, 2>& p : pairs) side.partners[start[p[key] + 1]++] = p[1 - key];
}

BodyCollisionWorkspace::Side& next_side(BodyCollisionWorkspace& cws, int body, int other) {
  if (static_cast<int>(cws.sides.size()) == cws.n_sides) cws.sides.emplace_back();
  BodyCollisionWorkspace::Side& side = cws.sides[cws.n_sides++];
  side.body = body;
  side.other = other;
  return side;
}

// Step 1: the triangle pairs of each pair of bodies whose boxes overlap, bucketed by triangle
// on both sides.
void gather_candidates(const BodyCollisionModel& model, std::span<const BodyModel> bodies,
                       BodyCollisionWorkspace& cws, BodyCollisionStats& stats) {
  cws.n_sides = 0;
  const int n_bodies = static_cast<int>(bodies.size());
  for (int a = 0; a < n_bodies; ++a) {
    for (int b = a + 1; b < n_bodies; ++b) {
      if (!cws.broadphase.body_boxes[a].overlaps(cws.broadphase.body_boxes[b])) continue;
      if (model.joined_pair(a, b)) continue;
      cws.pairs.clear();
      // Unsorted: a comparison sort of the pairs (for an order independent of the trees'
      // history) was 7% of the see-saw's run; the buckets and pair_nodes' tie-break make the
      // result independent of it instead.
      collect_overlapping_triangles(a, b, cws.broadphase, cws.pairs);
      if (cws.pairs.empty()) continue;
      stats.triangle_pairs += static_cast<int>(cws.pairs.size());
      const int n_a = static_cast<int>(bodies[a].tessellation.triangles.size());
      const int n_b = static_cast<int>(bodies[b].tessellation.triangles.size());
      bucket_pairs(cws.pairs, 0, n_a, next_side(cws, a, b));
      bucket_pairs(cws.pairs, 1, n_b, next_side(cws, b, a));
    }
  }
  cws.side_order.resize(static_cast<std::size_t>(cws.n_sides));
  for (int k = 0; k < cws.n_sides; ++k) cws.side_order[k] = k;
  std::sort(cws.side_order.begin(), cws.side_order.end(), [&](int l, int r) {
    const auto& sl = cws.sides[l];
    const auto& sr = cws.sides[r];
    return std::pair(sl.body, sl.other) < std::pair(sr.body, sr.other);
  });
}

// Step 2: each node with its closest triangle point of each other body among its candidates (the
// partners of the triangles around it); the pairs within the margin become contacts, ordered by
// (body, node, other body). Every node in a pair of overlapping boxes is a candidate, whether
// the triangles intersect or not: a node near a face is within the margin before they do.
void pair_nodes(std::span<const BodyModel> bodies, BodyCollisionWorkspace& cws,
                const BodyCollisionOptions& options, BodyCollisionStats& stats) {
  cws.contacts.clear();
  for (std::size_t first = 0; first < cws.side_order.size();) {
    const int a = cws.sides[cws.side_order[first]].body;
    std::size_t last = first;
    while (last < cws.side_order.size() && cws.sides[cws.side_order[last]].body == a) ++last;
    const Scratch& sa = cws.bodies[a];
    for (int node = 0; node < bodies[a].n_nodes(); ++node) {
      const Vec3& x = sa.x[node];
      for (std::size_t k = first; k < last; ++k) {
        const BodyCollisionWorkspace::Side& side = cws.sides[cws.side_order[k]];
        const int b = side.other;
        Scratch& sb = cws.bodies[b];
        if (++sb.stamp == 0) {  // wrapped: no entry may look current
          std::fill(sb.seen.begin(), sb.seen.end(), 0u);
          sb.stamp = 1;
        }
        const auto& triangles = bodies[b].tessellation.triangles;
        Real best = 1e300;
        int best_t = -1;
        TrianglePoint best_point;
        for (int j = sa.triangle_start[node]; j < sa.triangle_start[node + 1]; ++j) {
          const int own = sa.node_triangles[j];
          for (int e = side.start[own]; e < side.start[own + 1]; ++e) {
            const int tb = side.partners[e];
            if (sb.seen[tb] == sb.stamp) continue;
            sb.seen[tb] = sb.stamp;
            const std::array<int, 3>& t = triangles[tb];
            const TrianglePoint cp =
                closest_point_on_triangle(x, sb.x[t[0]], sb.x[t[1]], sb.x[t[2]]);
            ++stats.node_tests;
            const Real d2 = (x - cp.point).squaredNorm();
            // Ties keep the lowest triangle index, whatever the order of the buckets.
            if (d2 < best || (d2 == best && tb < best_t)) {
              best = d2;
              best_t = tb;
              best_point = cp;
            }
          }
        }
        if (best_t < 0) continue;  // no candidate, or no finite distance (left to the guard)
        const std::array<int, 3>& t = triangles[best_t];
        const Vec3& w = best_point.weights;
        Vec3 n = w[0] * sb.normal[t[0]] + w[1] * sb.normal[t[1]] + w[2] * sb.normal[t[2]];
        if (!(n.norm() > 0)) n = (sb.x[t[1]] - sb.x[t[0]]).cross(sb.x[t[2]] - sb.x[t[0]]);
        n.normalize();
        const Vec3 to_node = x - best_point.point;
        const Real gap = n.dot(to_node);
        if (gap < -options.max_depth) continue;
        if (gap >= 0 && std::sqrt(best) >= options.margin) continue;
        BodyContact c;
        c.body_a = a;
        c.node_a = node;
        c.body_b = b;
        c.triangle_b = best_t;
        c.nodes_b = t;
        c.w_b = w;
        c.gap = gap;
        make_basis(n, c.basis);
        cws.contacts.push_back(c);
        ++stats.contacts;
        if (gap < 0) {
          ++stats.penetrating;
          stats.max_penetration = std::max(stats.max_penetration, -gap);
        }
      }
    }
    first = last;
  }
}

// Step 4: equal and opposite inelastic impulses with Coulomb's cone (5.13), projected
// Gauss-Seidel in alternating sweeps.
void solve_impulses(const Bodies& all, const BodyCollisionOptions& options, Real dt,
                    BodyCollisionStats& stats) {
  std::vector<BodyContact>& contacts = all.cws.contacts;
  const int m = static_cast<int>(contacts.size());
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    Real change = 0, largest = 0;
    for (int step = 0; step < m; ++step) {
      BodyContact& c = contacts[iteration % 2 == 0 ? step : m - 1 - step];
      // Apart by gap: the pair may approach by gap in this step, and no more.
      Real allowed = 0;
      if (c.gap > 0) {
        if (!(dt > 0)) continue;
        allowed = c.gap / dt;
      }
      const Side a = side_a(c), b = side_b(c);
      const Vec3 u = c.basis.transpose() * (side_velocity(all, a) - side_velocity(all, b));
      const Vec3 j =
          updated_contact_impulse(c.impulse, u, allowed, c.inverse_mass, options.friction);
      const Vec3 dj = j - c.impulse;
      if (dj.isZero(0)) continue;
      c.impulse = j;
      const Vec3 J = c.basis * dj;
      apply_impulse(all, a, J);
      apply_impulse(all, b, -J);
      change = std::max(change, dj.cwiseAbs().maxCoeff());
      largest = std::max(largest, j.cwiseAbs().maxCoeff());
    }
    if (change <= 1e-12 * largest) break;
  }
  for (const BodyContact& c : contacts) stats.normal_impulse += c.impulse[0];
}

// Step 3: penetrating pairs to the mass-weighted mid-plane, Gauss-Seidel passes for pairs that
// share nodes.
void project_to_mid_plane(const Bodies& all, const BodyCollisionOptions& options,
                          BodyCollisionStats& stats) {
  std::vector<BodyContact>& contacts = all.cws.contacts;
  for (int pass = 0; pass < options.iterations; ++pass) {
    Real worst = 0;
    for (BodyContact& c : contacts) {
      const Side a = side_a(c), b = side_b(c);
      const Vec3 n = c.basis.col(0);
      const Real gap = n.dot(side_position(all, a) - side_position(all, b));
      if (gap >= 0) continue;
      worst = std::min(worst, gap);
      const Real lambda = (kProjectionMargin - gap) / c.position_inverse_mass;
      apply_displacement(all, a, lambda, n);
      apply_displacement(all, b, -lambda, n);
    }
    if (worst >= 0) break;
  }
  for (const BodyContact& c : contacts) {
    const Side a = side_a(c), b = side_b(c);
    const Real gap = c.basis.col(0).dot(side_position(all, a) - side_position(all, b));
    stats.max_penetration_after = std::max(stats.max_penetration_after, -gap);
  }
}

// Back to q and v: local nodes through q_d and d-dot, then the mean-axis split; rigid and global
// bodies through c and nu.
void write_back_body(const BodySet& set, int b, BodyCollisionWorkspace& cws) {
  Scratch& s = cws.bodies[b];
  const BodyModel& body = set.models[b];
  BodyWorkspace& bw = set.ws[b];
  auto q = body_q(body, set.q);
  auto v = body_v(body, set.v);
  const Mat3 Rt = bw.R.transpose();
  if (body.has_local) {
    const int d_q = body.layout.displacement_in_q(), d_v = body.layout.displacement_in_v();
    const Vec3 omega = omega_of(v);
    for (int i = 0; i < body.n_nodes(); ++i) {
      // x-dot = R (V + omega x p + p-dot) (3.4): a node moved by dp would gain omega x dp, so
      // its d-dot loses it and the velocity is the one the impulses left.
      const Vec3 dp = Rt * (s.x[i] - s.x0[i]);
      q.segment<3>(d_q + 3 * i) += dp;
      v.segment<3>(d_v + 3 * i) += Rt * (s.x_dot[i] - s.x_dot0[i]) - omega.cross(dp);
    }
    recenter_displacements(body, q, v);
    compute_body_kinematics(body, q, v, bw, false);
    factor_generalized_mass(body, q, bw);
    resplit_velocities(body, q, v, bw);
  } else {
    position_of(q) += s.shift;
    velocity_of(v) = bw.R * linear_part(s.nu);
    after_translation(v, body.n_generalized()) = after_translation(s.nu, body.n_generalized());
  }
  compute_body_kinematics(body, q, v, bw, false);
}

void write_back(const BodySet& set, BodyCollisionWorkspace& cws) {
  for (int b = 0; b < set.size(); ++b) {
    if (cws.bodies[b].touched) write_back_body(set, b, cws);
  }
}

// Pairs of distinct bodies (steps 1-4 above).
void resolve_between_bodies(const BodyCollisionModel& model, const BodySet& set,
                            BodyCollisionWorkspace& cws, Real dt, BodyCollisionStats& stats) {
  const BodyCollisionOptions& options = model.options;
  const int n_bodies = set.size();
  auto t0 = Clock::now();
  cws.broadphase.reinserted = 0;
  for (int b = 0; b < n_bodies; ++b) {
    const BodyModel& body = set.models[b];
    BodyWorkspace& bw = set.ws[b];
    Scratch& s = cws.bodies[b];
    const auto q = body_q(body, set.q);
    const auto v = body_v(body, set.v);
    compute_body_kinematics(body, q, v, bw, false);
    s.x0 = bw.x;
    s.x = bw.x;
    s.x_dot0 = bw.x_dot;
    s.x_dot = bw.x_dot;
    s.shift.setZero();
    s.touched = false;
    s.mass_factored = false;
    if (!body.has_local) {
      linear_part(s.nu) = bw.R.transpose() * velocity_of(v);
      after_translation(s.nu, body.n_generalized()) = after_translation(v, body.n_generalized());
    }
    compute_vertex_normals(body, s);
    update_surface_tree(b, s.x, body.tessellation.triangles, options.margin, cws.broadphase);
  }
  stats.reinserted_leaves = cws.broadphase.reinserted;
  gather_candidates(model, set.models, cws, stats);
  stats.seconds_broadphase = seconds_since(t0);

  t0 = Clock::now();
  pair_nodes(set.models, cws, options, stats);
  stats.seconds_narrowphase = seconds_since(t0);
  if (cws.contacts.empty()) return;

  t0 = Clock::now();
  const Bodies all{set, cws, model.constrained};
  for (BodyContact& c : cws.contacts) {
    for (const int b : {c.body_a, c.body_b}) {
      Scratch& s = cws.bodies[b];
      if (set.models[b].has_local || s.mass_factored) continue;
      factor_generalized_mass(set.models[b], body_q(set.models[b], set.q), set.ws[b]);
      s.mass_factored = true;
    }
    const Side a = side_a(c), b = side_b(c);
    for (int d = 0; d < 3; ++d) {
      c.inverse_mass[d] =
          side_inverse_mass(all, a, c.basis.col(d)) + side_inverse_mass(all, b, c.basis.col(d));
    }
    c.position_inverse_mass = position_inverse_mass(all, a) + position_inverse_mass(all, b);
  }
  solve_impulses(all, options, dt, stats);
  project_to_mid_plane(all, options, stats);
  write_back(set, cws);
  const BodyPushStats push = apply_body_push(set, cws, options.elasticity, dt);
  stats.pressing = push.pressing;
  stats.push_impulse = push.impulse;
  stats.seconds_response = seconds_since(t0);
}

// Each local body with itself (collide/self_collision.h), on the state the pairs of bodies left.
void resolve_within_bodies(const BodyCollisionOptions& options, const BodySet& set,
                           BodyCollisionWorkspace& cws, Real dt, BodyCollisionStats& stats) {
  const auto t0 = Clock::now();
  SelfCollisionWorkspace& sws = cws.self;
  size_self_collision_workspace(set.models, sws);
  const bool recorded = sws.recorded && sws.recorded_time == set.time;
  for (int b = 0; b < set.size(); ++b) {
    const BodyModel& body = set.models[b];
    if (!body.has_local) continue;
    BodyWorkspace& bw = set.ws[b];
    Scratch& s = cws.bodies[b];
    compute_body_kinematics(body, body_q(body, set.q), body_v(body, set.v), bw, false);
    s.x0 = bw.x;
    s.x = bw.x;
    s.x_dot0 = bw.x_dot;
    s.x_dot = bw.x_dot;
    s.touched = false;
    std::vector<Vec3>& x_start = sws.x_start[b];
    if (!recorded) {
      // First order in dt, exact only for straight node paths: a fallback for callers that step
      // without record_step_start.
      for (int i = 0; i < body.n_nodes(); ++i) x_start[i] = s.x[i] - dt * s.x_dot[i];
      ++stats.self.estimated_starts;
    }
    if (resolve_self_collisions(body, b, x_start, s.x, s.x_dot, dt, options, sws, stats.self)) {
      s.touched = true;
      write_back_body(set, b, cws);
    }
  }
  stats.seconds_self = seconds_since(t0);
}

}  // namespace

BodyCollisionStats resolve_body_collisions(const BodyCollisionModel& model, const BodySet& set,
                                           Real dt, BodyCollisionWorkspace& cws) {
  BodyCollisionStats stats;
  const auto start = Clock::now();
  if (!model.options.enabled || set.size() < 2) return stats;
  size_workspace(set.models, cws);
  resolve_between_bodies(model, set, cws, dt, stats);
  stats.seconds = seconds_since(start);
  return stats;
}

void resolve_body_self_collisions(const BodyCollisionOptions& options, const BodySet& set, Real dt,
                                  BodyCollisionWorkspace& cws, BodyCollisionStats& stats) {
  bool any_self = false;
  for (const BodyModel& body : set.models) any_self |= options.self_collision && body.has_local;
  if (!options.enabled || !any_self) return;
  size_workspace(set.models, cws);
  resolve_within_bodies(options, set, cws, dt, stats);
}

}  // namespace pbm
