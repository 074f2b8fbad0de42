// Collisions of a deformable (local) body with itself: the folds and the squashed shell whose
// faces meet (sec. 5.2.2 within one model), after Bridson, Fedkiw and Anderson 2002 ("Robust
// treatment of collisions, contact and friction for cloth animation").
//
// The book pairs points of two models and tells inside from outside by the distance to the model
// frame; within one surface both sides of every face are outside somewhere, so the side has to
// come from the motion. The step is taken as straight-line motion of every node from x_start (the
// state at the step's start, recorded by record_step_start; else estimated as x - dt x-dot) to x
// (the integrator's result), and that motion, the average velocity v = (x - x_start) / dt, is
// what gets corrected. Stages:
//  1. Candidates: the body's btDbvt (collide/surface_broadphase.h) over boxes covering each
//     triangle at x_start and at x, fattened by the margin. From each overlapping pair of
//     triangles come node-face pairs (the node not a corner of the face) and edge-edge pairs (no
//     shared node), sorted and unique.
//  2. Proximity at the step's start: node-face and edge-edge pairs closer than the margin are
//     held by inelastic impulses (only elements sharing a node are skipped, as in Bridson: a
//     shell crumpled flat brings neighbours of neighbours together, and an earlier ring-based
//     skip let them cross; at rest they sit about an edge's length apart): along the
//     normal n at the start, the pair may approach down to half the margin and no further; Coulomb
//     friction (5.13), |j_t| <= b_f j_n, against the tangential slip. Bridson's weighted impulse:
//     for weights c_k (1 and -w for a node and a face point, (1 - s, s) and -(1 - u, -u) for two
//     edge points, sum 0), J moves node k by c_k J / m_k, the pair's inverse mass is
//     sum c_k^2 / m_k (I / (1 + sum w^2) for equal masses). Projected Gauss-Seidel in
//     alternating sweeps, as for pairs of bodies (body_collisions.h).
//  3. Continuous collision detection (collide/continuous_collision.h) over all candidates, a few
//     passes: each pair found touching at some t of the step gets the impulse that ends it at
//     least 1e-3 margin apart along its normal at t (inelastic, no friction: the proximity stage
//     has handled the resting contacts), applied at once (Gauss-Seidel).
//  4. Fail-safe for what is left: translational impact zones. The nodes of every pair still
//     colliding are merged (union-find) into zones; each zone moves by the mass-weighted mean of
//     its nodes' motions and takes their mean velocity. A translated zone has the shape it had
//     at the step's start, so nothing inside it can cross, and the means conserve linear
//     momentum; zones that then hit other nodes grow, so the loop ends at the latest with the
//     whole body translated (Provot 1997; Bridson's rigid zones also keep the rotation, which
//     would need the zone's inertia and a polar decomposition, for a case that should be rare).
// Every impulse acts with c_k summing to 0, so the body's linear momentum sum m x-dot is unchanged
// to rounding; x-dot (the velocity at the step's end) gets the same velocity changes as the
// average velocity. Nodes are moved in x and x_dot only: the caller turns them into q_d and d-dot
// (body_collisions.cpp, write_back). Requires an intersection-free start: a crossing present at
// x_start is kept, not undone.
#pragma once

#include <array>
#include <vector>

#include <span>

#include "collide/body_collision_model.h"
#include "collide/surface_broadphase.h"
#include "core/types.h"
#include "deform/body_dynamics.h"

namespace pbm {

// Cost and outcome of the self-collision stage of one call, summed over the bodies.
struct SelfCollisionStats {
  int bodies = 0;                 // local bodies that collided with themselves
  int estimated_starts = 0;       // of those, with x_start estimated as x - dt x-dot
  int triangle_pairs = 0;         // overlapping swept boxes (first pass)
  int node_face_pairs = 0;        // candidates of stage 1 (first pass)
  int edge_edge_pairs = 0;        //
  int proximity_pairs = 0;        // within the margin at the start (stage 2)
  Real proximity_impulse = 0;     // sum of their j_n [N s]
  int continuous_collisions = 0;  // found by stage 3, over its passes
  int continuous_passes = 0;      // passes of stage 3 run
  int zone_rounds = 0;            // rounds of stage 4
  int zone_nodes = 0;             // nodes in impact zones at the end
  double seconds_candidates = 0, seconds_proximity = 0, seconds_continuous = 0, seconds_zones = 0;
};

// Scratch of the stage, sized on first use for the model (results never depend on it, except
// x_start, which record_step_start writes from the state every step before it is read).
struct SelfCollisionWorkspace {
  SurfaceBroadphase broadphase;  // swept boxes; empty trees for the bodies without q_d
  struct BodyTopology {
    std::vector<std::array<int, 2>> edges;           // unique, (lower, higher) node, sorted
    std::vector<std::array<int, 3>> triangle_edges;  // per triangle, into edges
  };
  std::vector<BodyTopology> topology;  // per body (empty without q_d)
  // Per body: node positions at the step's start, world [m]; valid when recorded_time equals
  // the state's time (record_step_start stores the start time plus dt).
  std::vector<std::vector<Vec3>> x_start;
  Real recorded_time = -1e300;
  bool recorded = false;
  std::vector<BodyWorkspace> start_kinematics;  // per body, for record_step_start
  std::vector<std::array<int, 2>> triangle_pairs;
  std::vector<std::array<int, 2>> node_face;  // (node, triangle)
  std::vector<std::array<int, 2>> edge_edge;  // (edge, edge), first < second
  struct Pair {
    std::array<int, 4> nodes{};
    std::array<Real, 4> weights{};  // c_k, sum 0
    Mat3 basis;                     // columns n, t1, t2 (world)
    Real allowed = 0;               // approach allowed over the step along n [m]
    Vec3 inverse_mass = Vec3::Zero();
    Vec3 impulse = Vec3::Zero();  // accumulated (j_n, j_t1, j_t2) on the first element [N s]
  };
  std::vector<Pair> proximity;
  std::vector<int> zone;          // per node: union-find parent
  std::vector<Vec3> zone_motion;  // per zone root: sum m (x - x_start), then the mean
  std::vector<Vec3> zone_momentum;
  std::vector<Real> zone_mass;
  std::vector<int> zone_count;  // nodes per zone root
};

// Sizes the workspace for the bodies (a no-op when it already fits).
void size_self_collision_workspace(std::span<const BodyModel> bodies, SelfCollisionWorkspace& sws);

// Node positions of every local body at the state (q, v at `time`), the start of the step of
// length dt about to be taken, into sws.x_start. Only when options.enabled and
// options.self_collision.
void record_step_start(std::span<const BodyModel> bodies, const VecX& q, const VecX& v, Real time,
                       Real dt, const BodyCollisionOptions& options, SelfCollisionWorkspace& sws);

// Stages 1-4 for local body b: x (n_nodes, world [m]) and x_dot (world [m/s]) at the step's end
// are corrected in place; x_start is the step's start (n_nodes). Returns whether a node moved.
bool resolve_self_collisions(const BodyModel& body, int b, const std::vector<Vec3>& x_start,
                             std::vector<Vec3>& x, std::vector<Vec3>& x_dot, Real dt,
                             const BodyCollisionOptions& options, SelfCollisionWorkspace& sws,
                             SelfCollisionStats& stats);

// Pairs of triangles of a body that share no node and intersect (Moller, triangle_geometry.h),
// all pairs tested: the ground truth of the tests and the statistics, O(n^2).
int count_self_intersections(const std::vector<std::array<int, 3>>& triangles,
                             const std::vector<Vec3>& x);

}  // namespace pbm
