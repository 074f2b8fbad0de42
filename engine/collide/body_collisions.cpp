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
using Scratch = BodyContactScratch;

bool sized_for(std::span<const BodyModel> bodies, const BodyCollisionWorkspace& cws) {
  if (cws.bodies.size() != bodies.size() || cws.broadphase.boxes.size() != bodies.size()) {
    return false;
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!scratch_sized_for(bodies[b], cws.bodies[b]) ||
        cws.broadphase.boxes[b].size() != bodies[b].tessellation.triangles.size()) {
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
    size_body_scratch(bodies[b], cws.bodies[b]);
    counts.push_back(static_cast<int>(bodies[b].tessellation.triangles.size()));
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

using Side = ContactSide;
using Bodies = ContactBodies;

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
void solve_impulses(const Bodies& all, std::vector<BodyContact>& contacts,
                    const BodyCollisionOptions& options, Real dt, BodyCollisionStats& stats) {
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
      apply_side_impulse(all, a, J);
      apply_side_impulse(all, b, -J);
      change = std::max(change, dj.cwiseAbs().maxCoeff());
      largest = std::max(largest, j.cwiseAbs().maxCoeff());
    }
    if (change <= 1e-12 * largest) break;
  }
  for (const BodyContact& c : contacts) stats.normal_impulse += c.impulse[0];
}

// Step 3: penetrating pairs to the mass-weighted mid-plane, Gauss-Seidel passes for pairs that
// share nodes.
void project_to_mid_plane(const Bodies& all, std::vector<BodyContact>& contacts,
                          const BodyCollisionOptions& options, BodyCollisionStats& stats) {
  for (int pass = 0; pass < options.iterations; ++pass) {
    Real worst = 0;
    for (BodyContact& c : contacts) {
      const Side a = side_a(c), b = side_b(c);
      const Vec3 n = c.basis.col(0);
      const Real gap = n.dot(side_position(all, a) - side_position(all, b));
      if (gap >= 0) continue;
      worst = std::min(worst, gap);
      const Real lambda = (kProjectionMargin - gap) / c.position_inverse_mass;
      apply_side_displacement(all, a, lambda, n);
      apply_side_displacement(all, b, -lambda, n);
    }
    if (worst >= 0) break;
  }
  for (const BodyContact& c : contacts) {
    const Side a = side_a(c), b = side_b(c);
    const Real gap = c.basis.col(0).dot(side_position(all, a) - side_position(all, b));
    stats.max_penetration_after = std::max(stats.max_penetration_after, -gap);
  }
}

void write_back(const BodySet& set, BodyCollisionWorkspace& cws) {
  for (int b = 0; b < set.size(); ++b) {
    if (cws.bodies[b].touched) write_back_body(set, b, cws.bodies[b]);
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
    Scratch& s = cws.bodies[b];
    load_body_scratch(set, b, s);
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
  const Bodies all{set, cws.bodies, model.constrained};
  for (BodyContact& c : cws.contacts) {
    const Side a = side_a(c), b = side_b(c);
    ensure_side_mass(all, a);
    ensure_side_mass(all, b);
    for (int d = 0; d < 3; ++d) {
      c.inverse_mass[d] =
          side_inverse_mass(all, a, c.basis.col(d)) + side_inverse_mass(all, b, c.basis.col(d));
    }
    c.position_inverse_mass =
        side_position_inverse_mass(all, a) + side_position_inverse_mass(all, b);
  }
  solve_impulses(all, cws.contacts, options, dt, stats);
  project_to_mid_plane(all, cws.contacts, options, stats);
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
    Scratch& s = cws.bodies[b];
    load_body_scratch(set, b, s);
    std::vector<Vec3>& x_start = sws.x_start[b];
    if (!recorded) {
      // First order in dt, exact only for straight node paths: a fallback for callers that step
      // without record_step_start.
      for (int i = 0; i < body.n_nodes(); ++i) x_start[i] = s.x[i] - dt * s.x_dot[i];
      ++stats.self.estimated_starts;
    }
    if (resolve_self_collisions(body, b, x_start, s.x, s.x_dot, dt, options, sws, stats.self)) {
      s.touched = true;
      write_back_body(set, b, s);
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
