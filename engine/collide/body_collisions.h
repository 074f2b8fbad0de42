// Collisions between deformable bodies, and of a body with itself (sec. 5.2.2).
//
// Runs after integration, in the collision stage beside the obstacles' resolve_penetrations
// (sec. 5.2.1). The book's steps, as implemented:
//  1. Polygons that may touch: a Bullet btDbvt per body over its surface triangles, fattened by
//     the margin (collide/surface_broadphase.h). A pair of triangles of two bodies whose boxes
//     overlap makes each triangle a candidate of the other's nodes (an intersection test would
//     miss a node near a face before the faces cross). The pairs are bucketed by triangle, and
//     a node's candidates are read from the buckets of the triangles around it.
//  2. Node pairing: a node x of one body is paired with the closest point y = sum w_k x_k of
//     the other body's candidate triangles (a weighted node of the other model: the book
//     pairs node with node, which lets a coarse mesh slip nodes between nodes). Interpenetration
//     is the sign of n . (x - y), n the other surface's outward normal at y (interpolated vertex
//     normals). The book's test (distances to the model frame) holds only for star-shaped models
//     and says nothing within one body: a body with itself is a stage of its own, after the pairs
//     of bodies (collide/self_collision.h: proximity and continuous detection of node-face and
//     edge-edge pairs over the step, impact zones as the fail-safe).
//  3. Mid-plane projection: a penetrating pair is moved apart along n to the plane between its
//     two points, each side by its share of the pair's inverse mass, so the mass centre does not
//     move (equal masses: the book's mid-plane).
//  4. Equal and opposite impulses j n and -j n (the time integral over the step of the book's
//     forces f_n, -f_n): inelastic, they stop the relative normal velocity of a touching pair; a
//     pair within the margin but apart may close its gap in one step and no more. Coulomb
//     friction (5.13) on the relative tangential velocity, |j_t| <= b_f j_n, and (5.12)'s
//     direction, against the slip. Projected Gauss-Seidel over the pairs in a fixed order,
//     alternating sweeps. Every impulse is applied to both sides at once, so the total linear
//     momentum is conserved exactly (to rounding) whatever the iteration count; each update
//     lowers the kinetic energy (it minimizes it along the pair's direction under the bounds).
// Body levels: a local body's side acts on its nodes alone, through q_d and d-dot with the lumped
// nodal masses (the mean-axis split is restored afterwards, resplit_velocities, which moves no
// node). Rigid and global bodies act through their generalized coordinates: an impulse J at
// y maps by sum w_k P_k^T R^T J through the k x k mass block (A^+), as for obstacles (5.2.1); their
// position correction translates c alone (inverse mass 1 / M), without turning or reshaping
// them. Self-collision needs q_d, so only local bodies collide with themselves; it starts from
// the node positions record_step_start stored at the step's start (collide/self_collision.h)
// and runs after the obstacles (resolve_body_self_collisions).
// Then the elastic push of step 4, (5.11) between the bodies' global surfaces, with
// solver.body_elasticity as a (collide/body_push.h; 0: the pairs are inelastic only).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "collide/body_collision_model.h"
#include "collide/body_contact_side.h"
#include "collide/self_collision.h"
#include "collide/surface_broadphase.h"
#include "core/types.h"
#include "deform/body_set.h"

namespace pbm {

// Cost and outcome of one call.
struct BodyCollisionStats {
  int triangle_pairs = 0;          // candidate triangle pairs after the broadphase
  int node_tests = 0;              // node-triangle closest-point evaluations
  int contacts = 0;                // node pairs within the margin
  int penetrating = 0;             // of those, interpenetrating before the projection
  Real max_penetration = 0;        // deepest interpenetration before the projection [m]
  Real max_penetration_after = 0;  // deepest left after it, over the contacts [m]
  Real normal_impulse = 0;         // sum of j_n [N s]
  int pressing = 0;                // pairs pushed apart by (5.11) (collide/body_push.h)
  Real push_impulse = 0;           // sum of their impulses [N s]
  int reinserted_leaves = 0;       // btDbvt leaves that moved
  SelfCollisionStats self;         // local bodies with themselves (collide/self_collision.h)
  double seconds_broadphase = 0, seconds_narrowphase = 0, seconds_response = 0;
  double seconds_self = 0;  // the self-collision stage, write-back included
  double seconds = 0;       // whole call
};

// One node paired with a point of another (or the same) body's triangle.
struct BodyContact {
  int body_a = 0, node_a = 0;      // the node side
  int body_b = 0, triangle_b = 0;  // the triangle side
  std::array<int, 3> nodes_b{};
  Vec3 w_b = Vec3::Zero();           // barycentric weights of y, sum 1
  Mat3 basis;                        // columns n (unit, from y toward x_a), t1, t2; world
  Real gap = 0;                      // n . (x_a - y) at detection [m]
  Vec3 inverse_mass = Vec3::Zero();  // of the pair along n, t1, t2 [1/kg]
  Real position_inverse_mass = 0;    // along n for the projection [1/kg]
  Vec3 impulse = Vec3::Zero();       // accumulated (j_n, j_t1, j_t2) on side a [N s]
};

// Scratch, rebuilt at will (results never depend on it). Sized on first use for the model.
struct BodyCollisionWorkspace {
  SurfaceBroadphase broadphase;
  std::vector<BodyContactScratch> bodies;  // one per body (collide/body_contact_side.h)
  // Per ordered pair of bodies whose boxes overlap: for each triangle of `body`, the triangles of
  // `other` whose fattened boxes overlap it, bucketed by a counting sort (triangle t's run is
  // partners[start[t]] .. partners[start[t + 1]]). The first n_sides are this step's.
  struct Side {
    int body = 0, other = 0;
    std::vector<int> start, partners;
  };
  std::vector<Side> sides;
  int n_sides = 0;
  std::vector<int> side_order;  // this step's sides by (body, other)
  std::vector<std::array<int, 2>> pairs;
  std::vector<BodyContact> contacts;
  SelfCollisionWorkspace self;  // and x_start, written by record_step_start
};

// Detects and resolves the contacts between bodies at the state the integrator produced (the
// step of length dt just taken): changes q and v of the bodies in contact (see above). Reads and
// leaves bodies.ws with the kinematics of the returned state for the bodies it changed. The
// speculative bound uses dt (0: contacts act only once touching).
BodyCollisionStats resolve_body_collisions(const BodyCollisionModel& model, const BodySet& bodies,
                                           Real dt, BodyCollisionWorkspace& cws);

// Each local body with itself (collide/self_collision.h) when options.self_collision, into
// stats.self and stats.seconds_self. The last word of the collision stage, after the obstacles:
// the obstacles' projection is then part of the motion checked, so a shell pressed flat on the
// ground is not pushed through itself by it (the price: an impulse may leave a node of the
// bottom sheet slightly inside the ground until the next step's obstacle pass). Uses
// cws.self.x_start when record_step_start was called for this step (the step does, when the
// model asks for self-collision), else x - dt x-dot.
void resolve_body_self_collisions(const BodyCollisionOptions& options, const BodySet& bodies,
                                  Real dt, BodyCollisionWorkspace& cws, BodyCollisionStats& stats);

}  // namespace pbm
