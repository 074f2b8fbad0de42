#include "collide/self_collision.h"

#include <algorithm>
#include <cmath>

#include "collide/contact_impulse.h"
#include "collide/continuous_collision.h"
#include "collide/triangle_geometry.h"
#include "core/wall_clock.h"

namespace pbm {
namespace {

using Clock = WallClock;
using Pair = SelfCollisionWorkspace::Pair;
using Topology = SelfCollisionWorkspace::BodyTopology;

// Passes of stage 3 before the impact zones take over (Bridson uses a few).
constexpr int kContinuousPasses = 8;
// Distance under which the elements count as touching at a coplanar instant, per margin: far
// below anything the proximity stage lets happen, far above the rounding of the positions.
constexpr Real kTouchTolerance = 1e-6;
// Separation a colliding pair keeps along its normal at the step's end, per margin.
constexpr Real kKeptSeparation = 1e-3;
// Proximity: closest approach allowed within the margin, per margin.
constexpr Real kProximityFloor = 0.5;

Topology build_topology(const BodyModel& body) {
  Topology topo;
  const auto& triangles = body.tessellation.triangles;
  for (const std::array<int, 3>& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      topo.edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(topo.edges.begin(), topo.edges.end());
  topo.edges.erase(std::unique(topo.edges.begin(), topo.edges.end()), topo.edges.end());
  for (const std::array<int, 3>& t : triangles) {
    std::array<int, 3> e{};
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
      e[k] = static_cast<int>(std::lower_bound(topo.edges.begin(), topo.edges.end(), key) -
                              topo.edges.begin());
    }
    topo.triangle_edges.push_back(e);
  }
  return topo;
}

// Stage 1 on the current x: swept boxes, triangle pairs, node-face and edge-edge candidates.
void gather_candidates(const BodyModel& body, int b, const std::vector<Vec3>& x_start,
                       const std::vector<Vec3>& x, Real margin, SelfCollisionWorkspace& sws) {
  const auto& triangles = body.tessellation.triangles;
  const Topology& topo = sws.topology[b];
  update_swept_surface_tree(b, x_start, x, triangles, margin, sws.broadphase);
  sws.triangle_pairs.clear();
  collect_triangle_pairs(b, b, sws.broadphase, sws.triangle_pairs);
  sws.node_face.clear();
  sws.edge_edge.clear();
  for (const std::array<int, 2>& p : sws.triangle_pairs) {
    for (int side = 0; side < 2; ++side) {
      const std::array<int, 3>& face = triangles[p[1 - side]];
      for (int v : triangles[p[side]]) {
        if (v != face[0] && v != face[1] && v != face[2]) sws.node_face.push_back({v, p[1 - side]});
      }
    }
    for (int ea : topo.triangle_edges[p[0]]) {
      for (int eb : topo.triangle_edges[p[1]]) {
        const std::array<int, 2>& u = topo.edges[ea];
        const std::array<int, 2>& w = topo.edges[eb];
        if (u[0] == w[0] || u[0] == w[1] || u[1] == w[0] || u[1] == w[1]) continue;
        sws.edge_edge.push_back({std::min(ea, eb), std::max(ea, eb)});
      }
    }
  }
  for (auto* list : {&sws.node_face, &sws.edge_edge}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
}

std::array<int, 4> node_face_nodes(const BodyModel& body, const std::array<int, 2>& c) {
  const std::array<int, 3>& t = body.tessellation.triangles[c[1]];
  return {c[0], t[0], t[1], t[2]};
}

std::array<int, 4> edge_edge_nodes(const Topology& topo, const std::array<int, 2>& c) {
  const std::array<int, 2>& a = topo.edges[c[0]];
  const std::array<int, 2>& b = topo.edges[c[1]];
  return {a[0], a[1], b[0], b[1]};
}

FourPoints gather(const std::vector<Vec3>& x, const std::array<int, 4>& nodes) {
  return {x[nodes[0]], x[nodes[1]], x[nodes[2]], x[nodes[3]]};
}

// sum c_k v_k over the pair's nodes.
Vec3 combine(const std::vector<Vec3>& v, const std::array<int, 4>& nodes,
             const std::array<Real, 4>& c) {
  Vec3 r = Vec3::Zero();
  for (int k = 0; k < 4; ++k) r += c[k] * v[nodes[k]];
  return r;
}

// Relative average velocity of the pair over the step, (sum c_k (x_k - x_start_k)) / dt.
Vec3 relative_velocity(const std::vector<Vec3>& x_start, const std::vector<Vec3>& x,
                       const std::array<int, 4>& nodes, const std::array<Real, 4>& c, Real dt) {
  return (combine(x, nodes, c) - combine(x_start, nodes, c)) / dt;
}

Real inverse_mass(const BodyModel& body, const std::array<int, 4>& nodes,
                  const std::array<Real, 4>& c) {
  Real sum = 0;
  for (int k = 0; k < 4; ++k) sum += c[k] * c[k] / body.node_mass[nodes[k]];
  return sum;
}

// Impulse J on the pair: node k's velocities change by c_k J / m_k, its end position by dt times
// that (the average velocity over the step changes with the end velocity).
void apply_impulse(const BodyModel& body, const std::array<int, 4>& nodes,
                   const std::array<Real, 4>& c, const Vec3& J, Real dt, std::vector<Vec3>& x,
                   std::vector<Vec3>& x_dot) {
  for (int k = 0; k < 4; ++k) {
    const Vec3 dv = (c[k] / body.node_mass[nodes[k]]) * J;
    x_dot[nodes[k]] += dv;
    x[nodes[k]] += dt * dv;
  }
}

void make_basis(const Vec3& n, Mat3& basis) {
  const Vec3 t1 = n.unitOrthogonal();
  basis.col(0) = n;
  basis.col(1) = t1;
  basis.col(2) = n.cross(t1);
}

// Stage 2, detection: the pairs within the margin at the step's start.
void find_proximity(const BodyModel& body, int b, const std::vector<Vec3>& x_start,
                    const std::vector<Vec3>& x, Real margin, SelfCollisionWorkspace& sws) {
  const Topology& topo = sws.topology[b];
  sws.proximity.clear();
  auto add = [&](const std::array<int, 4>& nodes, const std::array<Real, 4>& c, Real distance,
                 const Vec3& fallback) {
    const Vec3 gap = combine(x_start, nodes, c);
    Vec3 n = distance > 0 ? Vec3(gap / distance) : fallback;
    if (distance == 0) {
      // Touching at the start: n against the approach over the step.
      if (n.dot(combine(x, nodes, c) - combine(x_start, nodes, c)) > 0) n = -n;
    }
    Pair p;
    p.nodes = nodes;
    p.weights = c;
    make_basis(n, p.basis);
    p.allowed = std::max(0.0, distance - kProximityFloor * margin);
    for (int d = 0; d < 3; ++d) p.inverse_mass[d] = inverse_mass(body, nodes, c);
    sws.proximity.push_back(p);
  };
  for (const std::array<int, 2>& cand : sws.node_face) {
    const std::array<int, 4> nodes = node_face_nodes(body, cand);
    const FourPoints p = gather(x_start, nodes);
    const TrianglePoint y = closest_point_on_triangle(p[0], p[1], p[2], p[3]);
    const Real distance = (p[0] - y.point).norm();
    if (!(distance < margin)) continue;
    Vec3 face = (p[2] - p[1]).cross(p[3] - p[1]);
    face = face.norm() > 0 ? Vec3(face.normalized()) : Vec3::UnitZ();
    add(nodes, {1.0, -y.weights[0], -y.weights[1], -y.weights[2]}, distance, face);
  }
  for (const std::array<int, 2>& cand : sws.edge_edge) {
    const std::array<int, 4> nodes = edge_edge_nodes(topo, cand);
    const FourPoints p = gather(x_start, nodes);
    const SegmentPoints s = closest_points_on_segments(p[0], p[1], p[2], p[3]);
    const Real distance = (s.on_p - s.on_q).norm();
    if (!(distance < margin)) continue;
    Vec3 cross = (p[1] - p[0]).cross(p[3] - p[2]);
    cross = cross.norm() > 0 ? Vec3(cross.normalized()) : Vec3::UnitZ();
    add(nodes, {1 - s.s, s.s, -(1 - s.u), -s.u}, distance, cross);
  }
}

// Stage 2, response: inelastic impulses with Coulomb's cone (5.13), projected Gauss-Seidel in
// alternating sweeps (as solve_impulses in body_collisions.cpp).
void solve_proximity(const BodyModel& body, const std::vector<Vec3>& x_start, std::vector<Vec3>& x,
                     std::vector<Vec3>& x_dot, Real dt, const BodyCollisionOptions& options,
                     SelfCollisionWorkspace& sws) {
  std::vector<Pair>& pairs = sws.proximity;
  const int m = static_cast<int>(pairs.size());
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    Real change = 0, largest = 0;
    for (int step = 0; step < m; ++step) {
      Pair& p = pairs[iteration % 2 == 0 ? step : m - 1 - step];
      const Vec3 u = p.basis.transpose() * relative_velocity(x_start, x, p.nodes, p.weights, dt);
      const Vec3 j =
          updated_contact_impulse(p.impulse, u, p.allowed / dt, p.inverse_mass, options.friction);
      const Vec3 dj = j - p.impulse;
      if (dj.isZero(0)) continue;
      p.impulse = j;
      apply_impulse(body, p.nodes, p.weights, p.basis * dj, dt, x, x_dot);
      change = std::max(change, dj.cwiseAbs().maxCoeff());
      largest = std::max(largest, j.cwiseAbs().maxCoeff());
    }
    if (change <= 1e-12 * largest) break;
  }
}

// Stage 3, one pair: detection over the step and, when it touches, the impulse that leaves it
// kKeptSeparation margin apart along the contact normal at the step's end. Returns whether it hit.
bool resolve_continuous(const BodyModel& body, const std::array<int, 4>& nodes, bool node_face,
                        const std::vector<Vec3>& x_start, std::vector<Vec3>& x,
                        std::vector<Vec3>& x_dot, Real dt, Real margin) {
  const FourPoints p0 = gather(x_start, nodes), p1 = gather(x, nodes);
  const Real tolerance = kTouchTolerance * margin;
  const ContinuousContact c = node_face ? detect_node_face_collision(p0, p1, tolerance)
                                        : detect_edge_edge_collision(p0, p1, tolerance);
  if (!c.hit) return false;
  const Vec3& n = c.normal;
  const Real end = n.dot(combine(x, nodes, c.weights));
  const Real wanted = kKeptSeparation * margin;
  if (end >= wanted) return true;  // already leaving: the hit stands for the zones to judge
  const Real j = (wanted - end) / (dt * inverse_mass(body, nodes, c.weights));
  apply_impulse(body, nodes, c.weights, j * n, dt, x, x_dot);
  return true;
}

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// The lower index becomes the root: the zones do not depend on the order of the merges.
bool merge(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a == b) return false;
  if (b < a) std::swap(a, b);
  parent[b] = a;
  return true;
}

bool one_zone(std::vector<int>& parent, const std::array<int, 4>& nodes) {
  const int r = find_root(parent, nodes[0]);
  for (int k = 1; k < 4; ++k) {
    if (find_root(parent, nodes[k]) != r) return false;
  }
  return true;
}

// Stage 4: merge the nodes of every pair still colliding, translate the zones, until none
// collides. Returns the rounds taken.
int resolve_impact_zones(const BodyModel& body, int b, const std::vector<Vec3>& x_start,
                         std::vector<Vec3>& x, std::vector<Vec3>& x_dot, Real margin,
                         SelfCollisionWorkspace& sws, SelfCollisionStats& stats) {
  const int n = body.n_nodes();
  std::vector<int>& zone = sws.zone;
  for (int i = 0; i < n; ++i) zone[i] = i;
  const Topology& topo = sws.topology[b];
  const Real tolerance = kTouchTolerance * margin;
  int rounds = 0;
  // Every round either finds nothing or merges two zones: at most n - 1 merging rounds.
  for (; rounds < n; ++rounds) {
    gather_candidates(body, b, x_start, x, margin, sws);
    bool merged = false;
    for (int kind = 0; kind < 2; ++kind) {
      const auto& list = kind == 0 ? sws.node_face : sws.edge_edge;
      for (const std::array<int, 2>& cand : list) {
        const std::array<int, 4> nodes =
            kind == 0 ? node_face_nodes(body, cand) : edge_edge_nodes(topo, cand);
        if (one_zone(zone, nodes)) continue;
        const FourPoints p0 = gather(x_start, nodes), p1 = gather(x, nodes);
        const ContinuousContact c = kind == 0 ? detect_node_face_collision(p0, p1, tolerance)
                                              : detect_edge_edge_collision(p0, p1, tolerance);
        if (!c.hit) continue;
        for (int k = 1; k < 4; ++k) merged |= merge(zone, nodes[0], nodes[k]);
      }
    }
    if (!merged) break;
    // Each zone: the mass-weighted mean motion and velocity (sum over the zone / its mass).
    std::fill(sws.zone_motion.begin(), sws.zone_motion.end(), Vec3::Zero());
    std::fill(sws.zone_momentum.begin(), sws.zone_momentum.end(), Vec3::Zero());
    std::fill(sws.zone_mass.begin(), sws.zone_mass.end(), 0.0);
    std::fill(sws.zone_count.begin(), sws.zone_count.end(), 0);
    for (int i = 0; i < n; ++i) {
      const int r = find_root(zone, i);
      const Real m = body.node_mass[i];
      sws.zone_motion[r] += m * (x[i] - x_start[i]);
      sws.zone_momentum[r] += m * x_dot[i];
      sws.zone_mass[r] += m;
      ++sws.zone_count[r];
    }
    for (int i = 0; i < n; ++i) {
      const int r = find_root(zone, i);
      if (sws.zone_count[r] < 2) continue;  // a lone node keeps its own motion, bit for bit
      x[i] = x_start[i] + sws.zone_motion[r] / sws.zone_mass[r];
      x_dot[i] = sws.zone_momentum[r] / sws.zone_mass[r];
    }
  }
  if (rounds > 0) {
    for (int i = 0; i < n; ++i) stats.zone_nodes += sws.zone_count[find_root(zone, i)] > 1;
  }
  return rounds;
}

}  // namespace

void size_self_collision_workspace(std::span<const BodyModel> bodies, SelfCollisionWorkspace& sws) {
  // A copied workspace has empty trees and boxes (SurfaceBroadphase): rebuild.
  bool fits = sws.topology.size() == bodies.size() && sws.broadphase.boxes.size() == bodies.size();
  for (std::size_t b = 0; fits && b < bodies.size(); ++b) {
    const BodyModel& body = bodies[b];
    const std::size_t triangles = body.has_local ? body.tessellation.triangles.size() : 0;
    fits = sws.broadphase.boxes[b].size() == triangles;
    if (!fits) break;
    fits = sws.x_start[b].size() == (body.has_local ? static_cast<std::size_t>(body.n_nodes()) : 0);
  }
  if (fits) return;
  const std::size_t n_bodies = bodies.size();
  sws.topology.assign(n_bodies, {});
  sws.x_start.assign(n_bodies, {});
  sws.start_kinematics.assign(n_bodies, BodyWorkspace{});
  sws.recorded = false;
  std::vector<int> counts(n_bodies, 0);
  int largest = 0;
  for (std::size_t b = 0; b < n_bodies; ++b) {
    const BodyModel& body = bodies[b];
    if (!body.has_local) continue;
    sws.topology[b] = build_topology(body);
    sws.x_start[b].assign(static_cast<std::size_t>(body.n_nodes()), Vec3::Zero());
    resize_workspace(body, sws.start_kinematics[b]);
    counts[b] = static_cast<int>(body.tessellation.triangles.size());
    largest = std::max(largest, body.n_nodes());
  }
  resize_broadphase(counts, sws.broadphase);
  const auto n = static_cast<std::size_t>(largest);
  sws.zone.assign(n, 0);
  sws.zone_motion.assign(n, Vec3::Zero());
  sws.zone_momentum.assign(n, Vec3::Zero());
  sws.zone_mass.assign(n, 0.0);
  sws.zone_count.assign(n, 0);
}

void record_step_start(std::span<const BodyModel> bodies, const VecX& q, const VecX& v, Real time,
                       Real dt, const BodyCollisionOptions& options, SelfCollisionWorkspace& sws) {
  if (!options.enabled || !options.self_collision) return;
  size_self_collision_workspace(bodies, sws);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyModel& body = bodies[b];
    if (!body.has_local) continue;
    BodyWorkspace& bw = sws.start_kinematics[b];
    compute_body_kinematics(body, body_q(body, q), body_v(body, v), bw, false);
    sws.x_start[b] = bw.x;
  }
  // advance_substep adds dt to the time the same way: equal bits mark the step recorded here.
  sws.recorded_time = time + dt;
  sws.recorded = true;
}

bool resolve_self_collisions(const BodyModel& body, int b, const std::vector<Vec3>& x_start,
                             std::vector<Vec3>& x, std::vector<Vec3>& x_dot, Real dt,
                             const BodyCollisionOptions& options, SelfCollisionWorkspace& sws,
                             SelfCollisionStats& stats) {
  if (!(dt > 0)) return false;
  const Real margin = options.margin;
  ++stats.bodies;
  auto t0 = Clock::now();
  gather_candidates(body, b, x_start, x, margin, sws);
  stats.triangle_pairs += static_cast<int>(sws.triangle_pairs.size());
  stats.node_face_pairs += static_cast<int>(sws.node_face.size());
  stats.edge_edge_pairs += static_cast<int>(sws.edge_edge.size());
  stats.seconds_candidates += seconds_since(t0);

  t0 = Clock::now();
  find_proximity(body, b, x_start, x, margin, sws);
  stats.proximity_pairs += static_cast<int>(sws.proximity.size());
  solve_proximity(body, x_start, x, x_dot, dt, options, sws);
  for (const Pair& p : sws.proximity) stats.proximity_impulse += p.impulse[0];
  bool moved = !sws.proximity.empty();
  stats.seconds_proximity += seconds_since(t0);

  t0 = Clock::now();
  const Topology& topo = sws.topology[b];
  bool clean = false;  // the last pass found nothing (and so changed nothing)
  for (int pass = 0; pass < kContinuousPasses && !clean; ++pass) {
    if (pass > 0) gather_candidates(body, b, x_start, x, margin, sws);
    ++stats.continuous_passes;
    int hits = 0;
    for (const std::array<int, 2>& cand : sws.node_face) {
      hits += resolve_continuous(body, node_face_nodes(body, cand), true, x_start, x, x_dot, dt,
                                 margin);
    }
    for (const std::array<int, 2>& cand : sws.edge_edge) {
      hits += resolve_continuous(body, edge_edge_nodes(topo, cand), false, x_start, x, x_dot, dt,
                                 margin);
    }
    stats.continuous_collisions += hits;
    moved |= hits > 0;
    clean = hits == 0;
  }
  stats.seconds_continuous += seconds_since(t0);

  if (clean) return moved;
  t0 = Clock::now();
  const int rounds = resolve_impact_zones(body, b, x_start, x, x_dot, margin, sws, stats);
  stats.zone_rounds += rounds;
  moved |= rounds > 0;
  stats.seconds_zones += seconds_since(t0);
  return moved;
}

int count_self_intersections(const std::vector<std::array<int, 3>>& triangles,
                             const std::vector<Vec3>& x) {
  int count = 0;
  const std::size_t n = triangles.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<int, 3>& a = triangles[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::array<int, 3>& c = triangles[j];
      bool shared = false;
      for (int u : a) {
        for (int v : c) shared |= u == v;
      }
      if (shared) continue;
      count += triangles_intersect(x[a[0]], x[a[1]], x[a[2]], x[c[0]], x[c[1]], x[c[2]]);
    }
  }
  return count;
}

}  // namespace pbm
