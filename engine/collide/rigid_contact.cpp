#include "collide/rigid_contact.h"

#include <algorithm>
#include <cmath>

#include "collide/obstacle.h"
#include "deform/reference_shape.h"
#include "sim/state.h"

namespace pbm {
namespace {

// Share of the slip a touching node's friction may stop in one step (see add_contact_forces).
constexpr Real kFrictionStopFraction = 0.5;
// Share of the frame's normal velocity the contact dashpot removes per step (see below).
constexpr Real kContactDamping = 0.5;

// Positions only (no Jacobian): the cheap pass that detects penetration.
void compute_node_positions(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            BodyWorkspace& ws) {
  const Vec3 c = q.segment<3>(0);
  ws.R = rotation_from_quaternion(q.segment<4>(3));
  ws.q_s = body.n_s > 0 ? VecX(q.segment(7, body.n_s)) : body.q_s_fixed;
  compute_reference_positions(body, ws.q_s, ws);
  for (int i = 0; i < body.n_nodes(); ++i) {
    Vec3 p = ws.s[i];
    if (body.has_local) p += q.segment<3>(7 + body.n_s + 3 * i);
    ws.p[i] = p;
    ws.x[i] = c + ws.R * p;
  }
}

// Deepest obstacle for x: returns the signed distance and sets the obstacle index and normal.
Real deepest(const Model& model, const Vec3& x, int& which, Vec3& normal) {
  Real best = 1e300;
  which = -1;
  for (int o = 0; o < static_cast<int>(model.obstacles.size()); ++o) {
    Vec3 n;
    const Real d = signed_distance(model.obstacles[o], x, n);
    if (d < best) {
      best = d;
      which = o;
      normal = n;
    }
  }
  return best;
}

// Inelastic contact impulses on nu_g at the given nodes, mapped by L^T (P_i^T R^T in the body
// frame) through the k x k mass block, with Coulomb's cone |j_t| <= beta_f j_n (5.12) on the
// accumulated impulses. Jacobi, not Gauss-Seidel: every contact sees the same velocities in an
// iteration and takes 1 / n_contacts of what would stop it, so the distribution over a
// statically indeterminate patch does not depend on the order of the nodes (a sequential sweep
// puts the impulse on the first nodes and gives a symmetric ball a spurious spin).
void resolve_generalized_impulses(const Model& model, const BodyModel& body,
                                  const std::vector<int>& nodes, Eigen::Ref<VecX> v,
                                  BodyWorkspace& ws) {
  const int k = body.n_generalized();
  const int n_c = static_cast<int>(nodes.size());
  if (n_c == 0) return;
  const Mat3 Rt = ws.R.transpose();
  VecX nu(k);  // nu_g in the body frame
  nu.segment<3>(0) = Rt * v.segment<3>(0);
  nu.segment(3, k - 3) = v.segment(3, k - 3);
  // Per contact, in the body frame: the basis (n, t1, t2), Minv P^T of each direction and the
  // 3x3 Delassus block W = B^T P Minv P^T B, so the iterations only do vector updates.
  struct ContactPoint {
    Mat3 basis;       // columns n, t1, t2
    MatX minv_pb;     // k x 3
    Mat3 W;
    Real friction = 0;
    Vec3 j = Vec3::Zero();  // accumulated (normal, t1, t2) impulse
  };
  std::vector<ContactPoint> contacts(nodes.size());
  for (int c = 0; c < n_c; ++c) {
    int o = -1;
    Vec3 n;
    deepest(model, ws.x[nodes[c]], o, n);
    ContactPoint& cp = contacts[c];
    const Vec3 n_b = Rt * n;
    const Vec3 t1 = n_b.unitOrthogonal();
    cp.basis.col(0) = n_b;
    cp.basis.col(1) = t1;
    cp.basis.col(2) = n_b.cross(t1);
    cp.friction = model.obstacles[o].friction;
    cp.minv_pb.resize(k, 3);
    for (int d = 0; d < 3; ++d) {
      VecX col(k);
      solve_generalized_mass(ws, generalized_from_node(body, ws, nodes[c], cp.basis.col(d)), col);
      cp.minv_pb.col(d) = col;
    }
    for (int d = 0; d < 3; ++d) {
      cp.W.col(d) = cp.basis.transpose() * node_from_generalized(body, ws, nodes[c],
                                                                  VecX(cp.minv_pb.col(d)));
    }
  }
  VecX delta(k);
  for (int iter = 0; iter < 16; ++iter) {
    delta.setZero();
    Real change = 0, largest = 0;  // converged when the impulses stop changing
    for (int c = 0; c < n_c; ++c) {
      ContactPoint& cp = contacts[c];
      const Real w_n = cp.W(0, 0);
      if (!(w_n > 0)) continue;
      const Vec3 vel = cp.basis.transpose() * node_from_generalized(body, ws, nodes[c], nu);
      Vec3 j = cp.j;
      j[0] = std::max(0.0, j[0] - vel[0] / (w_n * n_c));
      if (cp.friction > 0) {
        // Stop the slip along each tangent, then clamp to the cone |j_t| <= beta_f j_n.
        for (int d = 1; d < 3; ++d) {
          if (cp.W(d, d) > 0) j[d] -= vel[d] / (cp.W(d, d) * n_c);
        }
        const Real jt = std::sqrt(j[1] * j[1] + j[2] * j[2]);
        const Real limit = cp.friction * j[0];
        if (jt > limit) {
          j[1] *= limit / jt;
          j[2] *= limit / jt;
        }
      } else {
        j[1] = j[2] = 0;
      }
      change = std::max(change, (j - cp.j).cwiseAbs().maxCoeff());
      largest = std::max(largest, j.cwiseAbs().maxCoeff());
      delta.noalias() += cp.minv_pb * (j - cp.j);
      cp.j = j;
    }
    nu += delta;
    if (change <= 1e-9 * largest) break;
  }
  v.segment<3>(0) = ws.R * nu.segment<3>(0);
  v.segment(3, k - 3) = nu.segment(3, k - 3);
}

}  // namespace

int add_contact_forces(const Model& model, const BodyModel& body, BodyWorkspace& ws) {
  int touching = 0;
  for (int i = 0; i < body.n_nodes(); ++i) {
    ws.contact[i] = -1;
    ws.contact_force[i].setZero();
    if (!body.has_local || model.obstacles.empty()) continue;
    int o = -1;
    Vec3 n;
    if (deepest(model, ws.x[i], o, n) > kContactBand) continue;
    ws.contact[i] = o;
    ++touching;
  }
  if (touching == 0) return 0;
  // Both dashpots below are sized on the whole frame: shared by the touching nodes, they remove
  // a fixed share of the frame's normal (or slip) velocity per step, whatever the node count,
  // which keeps them explicit-stable at the book's steps.
  const Real frame_mass_share = body.mass / touching;
  const Real rate = ws.dt > 0 ? 1.0 / ws.dt : 0.0;
  for (int i = 0; i < body.n_nodes(); ++i) {
    const int o = ws.contact[i];
    if (o < 0) continue;
    const ObstacleModel& obs = model.obstacles[o];
    Vec3 n;
    signed_distance(obs, ws.x[i], n);
    // (5.10)-(5.11): the node's elastic force, in the world frame, pushes back along n.
    const Vec3 f_i = ws.R * ws.K_q.segment<3>(3 * i);
    Real f_normal = obs.elasticity * std::max(0.0, f_i.dot(n));
    // The frame's own velocity at the node (x-dot without d-dot): the projection stops the node,
    // and a Kelvin-Voigt dashpot stops the frame bouncing on the stiff a K q_d spring (an
    // inelastic contact, as the book's balls come to rest). It never pulls: the total is >= 0.
    const Vec3 v_frame = ws.x_dot[i] - ws.R * ws.d_dot(body, i);
    f_normal -= kContactDamping * frame_mass_share * rate * v_frame.dot(n);
    f_normal = std::max(0.0, f_normal);
    Vec3 f = f_normal * n;
    // (5.12) on the frame's slip at the node (a rolling ball's contact nodes do not slip),
    // capped at the force that stops the slip within one step: below that the explicit Coulomb
    // regularization would be unstable (rate * dt >> 1 at 0.031 s).
    const Vec3 v_p = v_frame - v_frame.dot(n) * n;
    const Real speed = v_p.norm();
    if (speed > 0) {
      const Real magnitude =
          std::min(obs.friction * f_normal, kFrictionStopFraction * frame_mass_share * rate * speed);
      f -= magnitude * v_p / speed;
    }
    ws.contact_force[i] = f;
  }
  return touching;
}

ContactResolution resolve_penetrations(const Model& model, const BodyModel& body,
                                       Eigen::Ref<VecX> q, Eigen::Ref<VecX> v, BodyWorkspace& ws) {
  ContactResolution result;
  compute_node_positions(body, q, ws);
  std::vector<int> nodes;
  for (int i = 0; i < body.n_nodes() && !model.obstacles.empty(); ++i) {
    int o;
    Vec3 n;
    if (deepest(model, ws.x[i], o, n) < 0) nodes.push_back(i);
  }
  result.penetrating_nodes = static_cast<int>(nodes.size());
  if (nodes.empty() && body.has_local) {
    // No contact: still restore the mean-axis split, whose velocity form drifts between steps.
    compute_body_kinematics(body, q, v, ws, false);
    factor_generalized_mass(body, q, ws);
    resplit_velocities(body, q, v, ws);
  }
  if (!nodes.empty()) {
    compute_body_kinematics(body, q, v, ws, false);
    factor_generalized_mass(body, q, ws);
    if (body.has_local) {
      const Mat3 Rt = ws.R.transpose();
      const int d_q = 7 + body.n_s, d_v = 6 + body.n_s;
      for (int i : nodes) {
        // Repeat for a node inside two obstacles (a corner): each pass leaves one of them.
        for (int pass = 0; pass < 4; ++pass) {
          int o;
          Vec3 n;
          const Real phi = deepest(model, ws.x[i], o, n);
          if (phi >= kProjectionMargin * 0.5) break;
          const Vec3 dx = (kProjectionMargin - phi) * n;  // step 1: project along n
          q.segment<3>(d_q + 3 * i) += Rt * dx;           // step 2: the new d
          ws.p[i] += Rt * dx;
          ws.x[i] += dx;
          const Real vn = ws.x_dot[i].dot(n);
          if (vn < 0) {
            v.segment<3>(d_v + 3 * i) -= vn * (Rt * n);
            ws.x_dot[i] -= vn * n;
          }
        }
      }
      recenter_displacements(body, q);
      const Vec3 c = q.segment<3>(0);
      for (int i = 0; i < body.n_nodes(); ++i) ws.p[i] = ws.R.transpose() * (ws.x[i] - c);
      resplit_velocities(body, q, v, ws);
      // The frame too: its approach at the touching nodes is removed by impulses (inelastic,
      // Coulomb-bounded), so a resting body really rests (static friction), and only (5.11)'s
      // elastic push sends it back up.
      resolve_generalized_impulses(model, body, nodes, v, ws);
    } else {
      resolve_generalized_impulses(model, body, nodes, v, ws);
      // Position: translate c out of each obstacle by its deepest penetration.
      for (int pass = 0; pass < 8; ++pass) {
        Real worst = 0;
        Vec3 push = Vec3::Zero();
        for (int i = 0; i < body.n_nodes(); ++i) {
          int o;
          Vec3 n;
          const Real phi = deepest(model, ws.x[i], o, n);
          if (phi < worst) {
            worst = phi;
            push = (kProjectionMargin - phi) * n;
          }
        }
        if (worst >= 0) break;
        q.segment<3>(0) += push;
        for (Vec3& x : ws.x) x += push;
      }
    }
  }
  if (!model.obstacles.empty()) result.min_distance = min_obstacle_distance(model, ws);
  return result;
}

Real min_obstacle_distance(const Model& model, const BodyWorkspace& ws) {
  Real best = 1e300;
  for (const Vec3& x : ws.x) {
    for (const ObstacleModel& o : model.obstacles) {
      Vec3 n;
      best = std::min(best, signed_distance(o, x, n));
    }
  }
  return best;
}

}  // namespace pbm
