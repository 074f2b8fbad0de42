// Collisions of deformable bodies with rigid obstacles (sec. 5.2.1).
//
// Local bodies follow the book: a penetrating node is projected along the collision normal back
// to the surface by updating its q_d (step 1-2), and while it touches, it receives the normal
// force f_n = a (f_i . n) n from its elastic force f_i = (K q_d)_i (5.10, 5.11) and the Coulomb
// friction f_c = -beta_f |f_n| v_p / |v_p| (5.12). Its approaching normal velocity is removed at
// the projection (an inelastic node impact); the velocity split is then restored (resplit).
// The forces act on the rows of c and theta only: the projection already holds the node, and on
// its own d row the contact stiffness a K_ii / m_i would need omega dt < 2, i.e. dt < 0.03 s for
// the jello-ball's a = 670 (its book step is 0.031 s); through J^T they would drive the light
// squareness modes of q_s just as hard. Through the frame the whole body's mass carries them,
// and the c and theta rows stay exact linear and angular momentum balances.
//
// Rigid and global bodies have no q_d to absorb a projection: their contacts are resolved in the
// generalized coordinates. Sequential normal + Coulomb impulses at the penetrating nodes are
// mapped by L^T (P_i^T R^T in the body frame) through the k x k mass block, then c is translated
// along each obstacle's normal by the deepest remaining penetration. Either way no node ends a
// step inside an obstacle.
#pragma once

#include "deform/body_dynamics.h"
#include "sim/model.h"

namespace pbm {

// Nodes within this distance of a surface count as touching (after projection they sit on it).
inline constexpr Real kContactBand = 1e-6;
// Nodes are projected this far outside, so rounding never leaves them at -1e-17.
inline constexpr Real kProjectionMargin = 1e-9;

// Sets ws.contact_force to (5.11) + (5.12) for the touching nodes of a local body and records the
// obstacle in ws.contact. Needs kinematics and elastic forces. Returns the number of touching
// nodes.
int add_contact_forces(const Model& model, const BodyModel& body, BodyWorkspace& ws);

struct ContactResolution {
  int penetrating_nodes = 0;
  Real min_distance = 1e300;  // over all nodes and obstacles, after resolution [m]
};

// After a step: makes every node of the body lie outside every obstacle (see above). Leaves ws
// with the kinematics of the resolved state when it changed anything.
ContactResolution resolve_penetrations(const Model& model, const BodyModel& body,
                                       Eigen::Ref<VecX> q, Eigen::Ref<VecX> v, BodyWorkspace& ws);

// Signed distance of the closest node to any obstacle, from ws.x.
Real min_obstacle_distance(const Model& model, const BodyWorkspace& ws);

}  // namespace pbm
