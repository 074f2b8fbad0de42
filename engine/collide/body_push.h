// The push between bodies in contact: step 4 of sec. 5.2.2, "forces f_n and -f_n ..."
// computed in the same way as in the previous algorithm", i.e. (5.11) f_n = a (f_i . n) n with
// f_i = (K q_d)_i, the force of the dent the projection left.
//
// As for obstacles (collide/rigid_contact.h), the dent's force is written on the global surfaces
// c + R s: the node's dent moved its surface point out of the other body, so its global point lies
// inside it by the dent. For a pair (node i of body A, point y = sum w_k x_k of a triangle of B),
// phi = n . (g_A - g_B) with g the two global points and n B's outward normal: the overlap of the
// two undented surfaces, the sum of both dents. Two membranes pressed together are springs in
// series, so the pair's stiffness is a K_A K_B / (K_A + K_B) (a rigid or global side has no dent:
// K = infinity, and the book's obstacle case a K_A results). K of a node is the book's K_ii spread
// by area (BodyModel::contact_samples' stiffness, summed per node).
//
// It acts on (c, theta, q_s) of each side through P^T = (I, s~^T, J^T) at the global points and
// the k x k mass block A^+, never on q_d: that node's dent is held by the projection and the
// membrane. Without it two soft bodies exchange momentum only through the touching nodes, and a
// balloon's skin dents by most of its radius before the frame behind it slows (the middle balloon
// of sec. 7.4 then cannot pass the blow on).
// The spring a K (-phi) and a critically damped dashpot are capped at the impulse that stops the
// pair's approach within the step and then parts its global points at 5/s times their overlap
// (0.05 m/s for 1 cm): the push is inelastic (the book's balloons "collide inelastically") and
// drives the bodies apart only as slowly as that; the membranes' own dents still spring back.
// A spring left free to push apart created energy: the pairs come from the actual surfaces'
// contacts, so a pair can enter with its global points already overlapping (measured: 45 J ->
// 50 J for two soft balls meeting head on). Without the recovery (stopping the approach only), a
// heavy soft ball resting on the see-saw's plank sank through it: once at rest it no longer
// approaches, and nothing undid the overlap that each landing left. Stiffness and dashpot
// are sized on the mass each pair moves with (its share, by stiffness, of its body pair's
// contacts) and clamped to omega dt = 1 and c dt = m. Jacobi over the pairs, applied once per step
// as impulses after the projection and the inelastic node impulses (collide/body_collisions.h),
// to second-order bodies.
#pragma once

#include "collide/body_collisions.h"

namespace pbm {

struct BodyPushStats {
  int pressing = 0;      // pairs whose global surfaces overlap
  Real max_overlap = 0;  // deepest such overlap [m]
  Real impulse = 0;      // sum of dt |f_n| [N s]
};

// Per node of a local body: its share of the membrane stiffness, sum over the contact samples
// of the sample's stiffness times its weight at the node [N/m]. Empty for other bodies.
std::vector<Real> node_contact_stiffness(const BodyModel& body);

// The global surface point of node k (c + R s_k for a local body, the node itself otherwise) and
// its velocity c-dot + R (omega x s_k + J_k q_s-dot), world. Needs the body's kinematics.
struct GlobalPoint {
  Vec3 x = Vec3::Zero(), x_dot = Vec3::Zero();
};
GlobalPoint global_point(const BodyModel& body, const BodyWorkspace& bw,
                         const Eigen::Ref<const VecX>& q, const Eigen::Ref<const VecX>& v, int k);

// g = sum w_k P_k^T R^T y at the global points (s_k, not s_k + d_k: the push acts on the global
// surface), k entries.
void push_direction(const BodyModel& body, const BodyWorkspace& bw, const int* nodes,
                    const Real* weights, int count, const Vec3& y_world, VecX& g);

// The law of one pair's push in a step of length dt: a spring of `stiffness` [N/m] on the
// overlap -phi [m] (phi < 0), with the pair's mass [kg] (its share of the contact), clamped to
// omega dt = 1 and a critically damped dashpot (c dt <= m) on the approach speed [m/s] (> 0
// closing); capped at the impulse that stops the approach and then parts the surfaces at
// 5/s times their overlap (see above). Returns the impulse [N s], >= 0.
Real push_impulse(Real stiffness, Real mass, Real phi, Real approach, Real dt);

// Applies the push of `elasticity` (a of 5.11) over cws.contacts to set.v. Needs set.ws with the
// kinematics of the state (as resolve_body_collisions leaves them) and cws.bodies[b].stiffness.
BodyPushStats apply_body_push(const BodySet& set, BodyCollisionWorkspace& cws, Real elasticity,
                              Real dt);

}  // namespace pbm
