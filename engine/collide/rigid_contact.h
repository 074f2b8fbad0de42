// Collisions of deformable bodies with rigid obstacles (sec. 5.2.1).
//
// Local bodies follow the book's two steps. A penetrating node is projected along the normal back
// to the surface by updating its q_d (steps 1-2); its approaching normal velocity is removed and
// its slip reduced by at most beta_f times that change (an inelastic impact with Coulomb's law
// on the impulse, (5.12)); the velocity split is then restored (resplit). The obstacle's push
// (5.11), f_n = a (f_i . n) n with f_i = (K q_d)_i (5.10), is written where the projection puts
// the dent: at the global surface c + R s, which the dent keeps out of the obstacle. With
// d = -phi n at one node, f_i . n = K_ii (-phi), so (5.11) becomes a spring a K (-phi) at the
// points of the global surface inside the obstacle: the gradient of 0.5 a K phi^2, a potential of
// q (read from the current q_d, the force would pump energy in at every step of a resting
// contact, as the projection and the membrane keep changing q_d). K is the book's sum of K_ii
// spread by area over three points per surface triangle (BodyModel::contact_samples). The force
// acts through P^T = (I, s~^T, J^T) on c, theta and q_s, the rows of the global surface: on c and
// theta alone its J^T part would be missing and the mass block's coupling would turn a push into
// accelerations of the light q_s parameters. A Kelvin-Voigt dashpot and (5.12) on the point's
// slip complete it; all three are sized on the mass the point moves with (g^T A^+ g), so they stay
// explicit-stable whatever the shape's parameters.
//
// Rigid and global bodies have no q_d to absorb a projection: their contacts are resolved in the
// generalized coordinates. Jacobi normal + Coulomb impulses at the penetrating nodes are
// mapped by L^T (P_i^T R^T in the body frame) through the k x k mass block, then c is translated
// along each obstacle's normal by the deepest remaining penetration. Either way no node ends a
// step inside an obstacle.
//
// Obstacles may move (tracks, Drive::obstacles): every function takes them placed at the time of
// the state it looks at. Distances are taken against that placement, and every velocity the
// contact acts on (the dashpot, the impacts, the slip of (5.12)) is the body point's velocity
// minus the obstacle material's there: a moving obstacle is infinitely massive, so an inelastic
// impact leaves the point with the obstacle's normal velocity and friction drags it along.
#pragma once

#include <span>

#include "collide/obstacle_model.h"
#include "deform/body_dynamics.h"

namespace pbm {

// Nodes within this distance of a surface count as touching (after projection they sit on it).
inline constexpr Real kContactBand = 1e-6;
// Nodes are projected this far outside, so rounding never leaves them at -1e-17.
inline constexpr Real kProjectionMargin = 1e-9;

// Sets ws.contact_generalized to (5.11) + (5.12) and the dashpot for a local body, and records
// the obstacle each node touches in ws.contact. Needs kinematics and the factored mass block.
// Returns the number of touching nodes.
int add_contact_forces(Obstacles obstacles, const BodyModel& body, BodyWorkspace& ws);

struct ContactResolution {
  int penetrating_nodes = 0;
  Real min_distance = 1e300;  // over all nodes and obstacles, after resolution [m]
};

// After a step: makes every node of the body lie outside every obstacle (see above). Leaves ws
// with the kinematics of the resolved state when it changed anything.
// implicit: the implicit integrator's compliant correction (resolve_compliant in the .cpp) for
// local bodies, in the metric of the substep's factor.
ContactResolution resolve_penetrations(Obstacles obstacles, const BodyModel& body,
                                       Eigen::Ref<VecX> q, Eigen::Ref<VecX> v, BodyWorkspace& ws,
                                       bool implicit = false);

// Energy stored in the obstacles' push (5.11) on a local body, sum of 0.5 a K_ii phi^2 over its
// pressing frame points. Needs kinematics.
Real contact_potential_energy(Obstacles obstacles, const BodyModel& body, BodyWorkspace& ws);

// Signed distance of the closest node to any obstacle, from ws.x.
Real min_obstacle_distance(Obstacles obstacles, const BodyWorkspace& ws);

}  // namespace pbm
