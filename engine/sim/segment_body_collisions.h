// Collisions between the figures' segments and the deformable bodies (sec. 15.3's "collisions
// with the deformable models", resolved as the book resolves two deformable bodies, sec. 5.2.2):
// a segment dents a body and is pushed back by it. After the step, at the body_collisions stage:
//  1. Detection: each body's nodes against each segment whose box (fattened by the bodies'
//     margin, solver.collision_margin) overlaps the nodes' box; the segment's exact signed
//     distance (collide/convex_contacts.h) pairs a node with the closest point of the segment's
//     surface and its outward normal n. Nodes within the margin are contacts (speculative while
//     apart), none deeper than BodyCollisionOptions::max_depth.
//  2. Impulses: inelastic, equal and opposite (j on the node, -j on the segment at the same
//     point), with Coulomb's cone (5.13) |j_t| <= mu j_n, mu the geometric mean of the figure's
//     friction and the bodies' b_f; projected Gauss-Seidel in alternating sweeps. The body's side
//     moves with its nodal mass (local) or through its mass block (rigid, global:
//     collide/body_contact_side.h); the segment's with the figure's joint-space inertia: an
//     impulse J at the point changes the figure's q-dot by H^-1 J_p^T J (J_p the point's
//     Jacobian, as in the impact stage (15.1)-(15.8)), so the joints carry it to the whole
//     figure and no joint impulse works along a joint's axis (15.7).
//  3. Projection: the penetrating nodes are moved out to the segment's surface (the dent, q_d, of
//     a local body; c of a rigid or global body). The figure is not moved: its joint coordinates
//     have no translation of their own to give, and the push returns the overlap as a velocity.
//  4. Push (5.11): a local body's global surface c + R s_i inside a segment is pushed out with
//     a K_ii (-phi) (a = solver.body_elasticity), the same capped law as between bodies
//     (collide/body_push.h), and the segment receives the opposite impulse.
// Total linear momentum is kept by every step but the projection (which moves positions only).
// In sim/ because figure/ and collide/ share a layer.
#pragma once

#include <vector>

#include "collide/body_contact_side.h"
#include "collide/convex_contacts.h"
#include "figure/figure_impact.h"

namespace pbm {

struct Model;

// One node of a body against a segment.
struct SegmentBodyContact {
  int body = 0, node = 0;
  int figure = 0, segment = 0;
  Vec3 point = Vec3::Zero();         // the segment's surface point closest to the node, world [m]
  Mat3 basis;                        // columns n (the segment's outward normal), t1, t2; world
  Real gap = 0;                      // n . (x_node - point) at detection [m], < 0 inside
  Vec3 inverse_mass = Vec3::Zero();  // of the pair along n, t1, t2 [1/kg]
  Real position_inverse_mass = 0;    // the body's along n [1/kg]
  Vec3 impulse = Vec3::Zero();       // accumulated (j_n, j_t1, j_t2) on the node [N s]
  int column = 0;                    // its three rows of the figure's J_p (columns of H^-1 J_p^T)
};

// Cost and outcome of one call.
struct SegmentBodyStats {
  int contacts = 0;          // node-segment pairs within the margin
  int penetrating = 0;       // of those, with the node inside
  Real max_penetration = 0;  // deepest before the projection [m]
  Real normal_impulse = 0;   // sum of j_n [N s]
  int pressing = 0;          // global surface points pushed out by (5.11)
  Real push_impulse = 0;     // sum of their impulses [N s]
};

// Scratch, rebuilt at will: results never depend on it. Sized by size_segment_body_workspace.
struct SegmentBodyWorkspace {
  std::vector<BodyContactScratch> bodies;  // one per body
  std::vector<Box3> body_boxes;            // the nodes' bounds, fattened by the margin
  std::vector<ConvexSolid> solids;         // every segment, figure by figure
  std::vector<Box3> boxes;                 // their bounds
  std::vector<int> first;                  // index of each figure's first segment in solids
  std::vector<SegmentBodyContact> contacts;
  // Per figure: the rows of its contacts' J_p so far; its H (then the Cholesky factor), J_p
  // (3 m_f x n_v) and H^-1 J_p^T (n_v x 3 m_f), column-major, grow-only.
  std::vector<int> rows;
  std::vector<std::vector<Real>> H, J, HinvJt;
  std::vector<FigureWorkspace> figures;  // the inertia's recursions
  std::vector<Real> push_rows;           // a figure's J_y (3 x n_v) for the push
  VecX push_jn, push_column;             // J_y^T n and H^-1 J_y^T n (the largest n_v)
  std::vector<Real> push;                // per contact: the push's impulse [N s]
  std::vector<Real> pair_stiffness;      // per (body, figure): the pressing points' stiffness
};

void size_segment_body_workspace(const Model& model, SegmentBodyWorkspace& sws);

// Detects and resolves the contacts of every body with every segment of the figures whose
// body_collisions is on, at the state the step produced (set.q, set.v hold the figures' slices
// too). each and worlds: every figure's kinematics at that state (figure_kinematics with v,
// segment_world_transforms). Changes the bodies' q and v and the figures' v; leaves the bodies'
// workspaces with the new state's kinematics.
SegmentBodyStats resolve_segment_body_collisions(
    const Model& model, const BodySet& set, std::vector<FigureWorkspace>& each,
    const std::vector<std::vector<SpatialTransform>>& worlds, Real dt, SegmentBodyWorkspace& sws);

}  // namespace pbm
