#include "collide/rigid_contact.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "collide/implicit_contact.h"
#include "collide/obstacle.h"
#include "core/quaternion.h"
#include "deform/implicit_membrane.h"
#include "deform/reference_shape.h"
#include "deform/superquadric_jacobian.h"

namespace pbm {
namespace {

// Share of a contact point's slip its friction may stop in one step (see add_contact_forces).
constexpr Real kFrictionStopFraction = 0.5;
// Share of a contact point's normal velocity the dashpot removes per step (see below).
constexpr Real kContactDamping = 0.5;

// Positions only (no Jacobian): the cheap pass that detects penetration.
void compute_node_positions(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            BodyWorkspace& ws) {
  const Vec3 c = position_of(q);
  ws.R = rotation_from_quaternion(quaternion_of(q));
  ws.q_s = body.n_s > 0 ? VecX(shape_of(body.layout, q)) : body.q_s_fixed;
  compute_reference_positions(body, ws.q_s, ws);
  for (int i = 0; i < body.n_nodes(); ++i) {
    Vec3 p = ws.s[i];
    if (body.has_local) p += q.segment<3>(body.layout.displacement_in_q() + 3 * i);
    ws.p[i] = p;
    ws.x[i] = c + ws.R * p;
  }
}

// Deepest obstacle for x: returns the signed distance and sets the obstacle index and normal.
[[gnu::always_inline]] inline Real deepest(Obstacles obstacles, const Vec3& x, int& which,
                                           Vec3& normal) {
  Real best = 1e300;
  which = -1;
  for (int o = 0; o < static_cast<int>(obstacles.size()); ++o) {
    Vec3 n;
    const Real d = signed_distance(obstacles[o], x, n);
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
// accumulated impulses. Both act on the node's velocity relative to the obstacle's material
// there, so a moving obstacle leaves the node with at least its normal velocity (momentum goes
// into the body) and drags it by friction. Jacobi, not Gauss-Seidel: every contact sees the same
// velocities in an iteration and takes 1 / n_contacts of what would stop it, so the distribution
// over a statically indeterminate patch does not depend on the order of the nodes (a sequential
// sweep puts the impulse on the first nodes and gives a symmetric ball a spurious spin).
void resolve_generalized_impulses(Obstacles obstacles, const BodyModel& body,
                                  const std::vector<int>& nodes, Eigen::Ref<VecX> v,
                                  BodyWorkspace& ws) {
  const int k = body.n_generalized();
  const int n_c = static_cast<int>(nodes.size());
  if (n_c == 0) return;
  const Mat3 Rt = ws.R.transpose();
  VecX nu(k);  // nu_g in the body frame
  linear_part(nu) = Rt * velocity_of(v);
  after_translation(nu, k) = after_translation(v, k);
  // Per contact, in the body frame: the basis (n, t1, t2), Minv P^T of each direction and the
  // 3x3 Delassus block W = B^T P Minv P^T B, so the iterations only do vector updates.
  struct ContactPoint {
    Mat3 basis;    // columns n, t1, t2
    MatX minv_pb;  // k x 3
    Mat3 W;
    Real friction = 0;
    Vec3 v_obstacle = Vec3::Zero();  // the obstacle's velocity at the node, in (n, t1, t2)
    Vec3 j = Vec3::Zero();           // accumulated (normal, t1, t2) impulse
  };
  std::vector<ContactPoint> contacts(nodes.size());
  for (int c = 0; c < n_c; ++c) {
    int o = -1;
    Vec3 n;
    deepest(obstacles, ws.x[nodes[c]], o, n);
    ContactPoint& cp = contacts[c];
    const Vec3 n_b = Rt * n;
    const Vec3 t1 = n_b.unitOrthogonal();
    cp.basis.col(0) = n_b;
    cp.basis.col(1) = t1;
    cp.basis.col(2) = n_b.cross(t1);
    cp.friction = obstacles[o].friction;
    cp.v_obstacle = cp.basis.transpose() * (Rt * obstacles[o].velocity_at(ws.x[nodes[c]]));
    cp.minv_pb.resize(k, 3);
    for (int d = 0; d < 3; ++d) {
      VecX col(k);
      solve_generalized_mass(ws, generalized_from_node(body, ws, nodes[c], cp.basis.col(d)), col);
      cp.minv_pb.col(d) = col;
    }
    for (int d = 0; d < 3; ++d) {
      cp.W.col(d) =
          cp.basis.transpose() * node_from_generalized(body, ws, nodes[c], VecX(cp.minv_pb.col(d)));
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
      const Vec3 vel =
          cp.basis.transpose() * node_from_generalized(body, ws, nodes[c], nu) - cp.v_obstacle;
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
  velocity_of(v) = ws.R * linear_part(nu);
  after_translation(v, k) = after_translation(nu, k);
}

}  // namespace

namespace {

// Blend of the sample's triangle nodes' reference positions, body frame: within about
// contact_sample_gap of the exact point, so it screens out the samples far from any obstacle.
Vec3 blended_point(const ContactSample& sample, const BodyWorkspace& ws) {
  return sample.weights[0] * ws.s[sample.nodes[0]] + sample.weights[1] * ws.s[sample.nodes[1]] +
         sample.weights[2] * ws.s[sample.nodes[2]];
}

// Signed distance of the sample's point on the global surface c + R s(u, v) (no dent) to the
// deepest obstacle; s is evaluated exactly only near an obstacle. Sets s (body frame), o and n.
// distance(s, o, n) is the deepest obstacle's signed distance of the body-frame point s.
template <class Distance>
Real sample_distance(const BodyModel& body, const ContactSample& sample, BodyWorkspace& ws,
                     Real band, const Distance& distance, Vec3& s, int& o, Vec3& n) {
  s = blended_point(sample, ws);
  const Real screen = distance(s, o, n);
  if (screen > band + 4.0 * body.contact_sample_gap * ws.q_s[0] / body.q_s_fixed[0]) return screen;
  if (body.shape == ShapeKind::superquadric) {
    // The superquadric from its latitude's and longitude's powers, shared by many samples.
    const auto [iu, iv] = sample.grid;
    if (ws.sample_u_stamp[iu] != ws.sample_stamp) {
      ws.sample_u_powers[iu] = latitude_powers(body.sample_grid_u[iu], ws.q_s[4]);
      ws.sample_u_stamp[iu] = ws.sample_stamp;
    }
    if (ws.sample_v_stamp[iv] != ws.sample_stamp) {
      ws.sample_v_powers[iv] = longitude_powers(body.sample_grid_v[iv], ws.q_s[5]);
      ws.sample_v_stamp[iv] = ws.sample_stamp;
    }
    evaluate_superquadric(ws.q_s, combine_powers(ws.sample_u_powers[iu], ws.sample_v_powers[iv]),
                          1.0, s, nullptr);
  } else {
    evaluate_reference_shape(body.shape, ws.q_s, sample.angles, 1.0, s, nullptr);
  }
  return distance(s, o, n);
}

// c, from any node's x = c + R p.
Vec3 frame_origin(const BodyWorkspace& ws) {
  return ws.x[0] - ws.R * ws.p[0];
}

// Planes seen from the body frame: n . (c + R s - x_o) = (R^T n) . s + n . (c - x_o), so a
// body-frame point's distance is one dot product, where the world form rotates the point first:
// 28% of gather_pressing_samples' instructions on a resting 1k-node ball went to those rotations
// and the obstacle loop's copies.
constexpr int kBodyFramePlanes = 8;
struct BodyFramePlanes {
  int count = 0;
  std::array<Vec3, kBodyFramePlanes> normal;  // R^T n, body frame
  std::array<Real, kBodyFramePlanes> offset;  // n . (c - x_o)
};

// Fills ws.pressing with the samples whose point on the global surface is inside an obstacle, or
// within `band` of one (the implicit contact's candidates, collide/implicit_contact.h).
// A signed distance is 1-Lipschitz, so a sample is at least its nearest node's distance minus its
// triangle's reach: triangles whose nodes all stand farther are skipped unevaluated.
// all_planes: every obstacle is a plane (then the deepest distance is concave, see below).
template <class Distance>
void gather_samples(const BodyModel& body, BodyWorkspace& ws, Real band, bool all_planes,
                    const Distance& distance) {
  for (int i = 0; i < body.n_nodes(); ++i) {
    int o;
    Vec3 n;
    ws.surface_distance[i] = distance(ws.s[i], o, n);
  }
  // The reach and the gap were measured on the initial shape; a0 scales them, and the factor 2
  // covers the rest of a shape's change.
  const Real scale = 2.0 * ws.q_s[0] / body.q_s_fixed[0];
  const Real gap = scale * body.contact_sample_gap;
  const auto& triangles = body.tessellation.triangles;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const std::array<int, 3>& tri = triangles[t];
    const Real phi0 = ws.surface_distance[tri[0]], phi1 = ws.surface_distance[tri[1]],
               phi2 = ws.surface_distance[tri[2]];
    if (std::min({phi0, phi1, phi2}) > band + scale * body.contact_triangle_reach[t]) continue;
    for (int k = 0; k < body.samples_per_triangle; ++k) {
      const int index = static_cast<int>(body.samples_per_triangle * t) + k;
      const ContactSample& sample = body.contact_samples[index];
      // Among planes the deepest distance is a minimum of affine functions, concave: at the blend
      // of the nodes it is at least the blend of theirs, and the exact point is within the gap.
      if (all_planes &&
          sample.weights[0] * phi0 + sample.weights[1] * phi1 + sample.weights[2] * phi2 >
              band + gap) {
        continue;
      }
      BodyWorkspace::PressingPoint point;
      point.sample = index;
      point.phi =
          sample_distance(body, sample, ws, band, distance, point.s, point.obstacle, point.n);
      if (point.phi < band) ws.pressing.push_back(point);
    }
  }
}

void gather_pressing_samples(Obstacles obstacles, const BodyModel& body, BodyWorkspace& ws,
                             const Vec3& c, Real band = 0) {
  ws.pressing.clear();
  if (!body.has_local || obstacles.empty()) return;
  if (++ws.sample_stamp == 0) {  // wrapped: no entry may look current
    std::fill(ws.sample_u_stamp.begin(), ws.sample_u_stamp.end(), 0u);
    std::fill(ws.sample_v_stamp.begin(), ws.sample_v_stamp.end(), 0u);
    ws.sample_stamp = 1;
  }
  bool all_planes = true;
  for (const ObstacleModel& o : obstacles) all_planes &= o.kind == ObstacleKind::plane;
  if (all_planes && obstacles.size() <= kBodyFramePlanes) {
    BodyFramePlanes planes;
    planes.count = static_cast<int>(obstacles.size());
    for (int o = 0; o < planes.count; ++o) {
      planes.normal[o] = ws.R.transpose() * obstacles[o].normal;
      planes.offset[o] = obstacles[o].normal.dot(c - obstacles[o].point);
    }
    gather_samples(body, ws, band, true, [&](const Vec3& s, int& which, Vec3& normal) {
      Real best = planes.normal[0].dot(s) + planes.offset[0];
      which = 0;
      for (int o = 1; o < planes.count; ++o) {
        const Real d = planes.normal[o].dot(s) + planes.offset[o];
        if (d < best) {
          best = d;
          which = o;
        }
      }
      normal = obstacles[which].normal;
      return best;
    });
    return;
  }
  gather_samples(body, ws, band, all_planes, [&](const Vec3& s, int& which, Vec3& normal) {
    return deepest(obstacles, c + ws.R * s, which, normal);
  });
}

// P^T y for a body-frame force y at a sample: (y, s x y, J_s^T y), J_s blended like s.
void sample_generalized(const BodyModel& body, const BodyWorkspace& ws, const ContactSample& sample,
                        const Vec3& s, const Vec3& y, Eigen::Ref<VecX> out) {
  linear_part(out) = y;
  angular_part(out) = s.cross(y);
  if (sparse_superquadric(body)) {
    // Over J's 11 non-zeros, into a fixed-size column: under half the instructions of the
    // run-time-sized loop below, and this runs for every pressing and slipping point.
    Eigen::Matrix<Real, kSuperquadricParameters, 1> shape;
    shape.setZero();
    for (int m = 0; m < 3; ++m) {
      add_superquadric_Jt_y(node_J(ws, sample.nodes[m]), sample.weights[m] * y, shape.data());
    }
    out.segment<kSuperquadricParameters>(BodyLayout::kShapeInV) = shape;
    return;
  }
  if (body.n_s == 0) return;
  out.tail(body.n_s).setZero();
  for (int m = 0; m < 3; ++m)
    add_Jt_y(ws, sample.nodes[m], y, sample.weights[m], out.data() + BodyLayout::kShapeInV);
}

// Room for m columns in a scratch matrix of k rows, grown by doubling (no allocation in a steady
// contact).
void reserve_columns(MatX& matrix, VecX& vector, VecX& other, int k, int m) {
  if (matrix.cols() >= m) return;
  matrix.resize(k, 2 * m);
  vector.resize(2 * m);
  other.resize(2 * m);
}

// How far a point of the global surface may travel toward an obstacle in one step: dt times the
// fastest node's speed relative to any obstacle after the step's external push (f_i / m_i over
// dt), doubled for the global surface's own motion (a node's speed holds its dent's rate, the
// global point's does not).
Real approach_band(Obstacles obstacles, const BodyModel& body, const BodyWorkspace& ws) {
  Real speed = 0;
  for (std::size_t i = 0; i < ws.x.size(); ++i) {
    const Real pushed = ws.dt * ws.force[i].norm() / body.node_mass[i];
    for (const ObstacleModel& o : obstacles) {
      speed = std::max(speed, (ws.x_dot[i] - o.velocity_at(ws.x[i])).norm() + pushed);
    }
  }
  return 2.0 * ws.dt * speed;
}

}  // namespace

int add_contact_forces(Obstacles obstacles, const BodyModel& body, BodyWorkspace& ws) {
  ws.contact_generalized.setZero();
  for (int i = 0; i < body.n_nodes(); ++i) ws.contact[i] = -1;
  if (!body.has_local || obstacles.empty()) return 0;
  int touching = 0;
  for (int i = 0; i < body.n_nodes(); ++i) {
    int o = -1;
    Vec3 n;
    if (deepest(obstacles, ws.x[i], o, n) > kContactBand) continue;
    ws.contact[i] = o;
    ++touching;
  }
  const Vec3 c = frame_origin(ws);
  const Mat3 Rt = ws.R.transpose();
  ImplicitContactWorkspace& ic = ws.implicit_contact;
  ic.candidates = 0;
  const bool implicit = ic.on && ws.dt > 0;
  gather_pressing_samples(obstacles, body, ws, c,
                          implicit ? approach_band(obstacles, body, ws) : 0.0);
  Real pressing_stiffness = 0;
  for (const auto& point : ws.pressing) {
    pressing_stiffness += body.contact_samples[point.sample].stiffness;
  }
  if (pressing_stiffness == 0) return touching;
  // c-dot in the body frame, from any node's x-dot = R (V + omega x p + p-dot).
  const Vec3 V = Rt * ws.x_dot[0] - ws.omega.cross(ws.p[0]) - ws.p_dot[0];
  const Real rate = ws.dt > 0 ? 1.0 / ws.dt : 0.0;
  const int k = body.n_generalized();
  const int m = static_cast<int>(ws.pressing.size());
  reserve_columns(ws.contact_directions, ws.contact_magnitude, ws.contact_mobility, k, m);
  auto G = ws.contact_directions.leftCols(m);
  auto magnitude = ws.contact_magnitude.head(m);
  auto mobility = ws.contact_mobility.head(m);
  // The mass each point moves with along n, g^T A^+ g with g = P^T n: through c and theta, and
  // through every q_s parameter whose Jacobian is not 0 there (light ones, such as a squareness,
  // make it small). Its share (by stiffness) of the patch sizes the explicit-stable springs and
  // dashpots below.
  for (int p = 0; p < m; ++p) {
    const auto& point = ws.pressing[p];
    sample_generalized(body, ws, body.contact_samples[point.sample], point.s, Rt * point.n,
                       G.col(p));
  }
  inverse_effective_masses(ws, G, mobility);
  ws.slipping.clear();
  for (int p = 0; p < m; ++p) {
    const auto& point = ws.pressing[p];
    const ContactSample& sample = body.contact_samples[point.sample];
    const ObstacleModel& obs = obstacles[point.obstacle];
    const Real share = sample.stiffness / pressing_stiffness;
    const Real mass_n = share / mobility[p];
    // (5.11): the node projected back by -phi carries the dent d = -phi n, whose elastic force is
    // f_i = (K q_d)_i = K_ii (-phi) n (5.10) when the dent is the node's alone. Written on the
    // global surface, it is the gradient of 0.5 a K phi^2: a potential of q, so the contact
    // returns at most the energy it stored, where a force read from the current q_d (which the
    // projection and the membrane keep changing) pumps energy in at every step of a rest. A
    // spring stiffer than the step resolves is clamped to omega dt = 1.
    Real stiffness = obs.elasticity * sample.stiffness;
    // Kelvin-Voigt dashpot on the surface point's approach: an inelastic contact, so the book's
    // balls come to rest. With the book's stiffness it is sized on the step, c = m / (2 dt);
    // with a material's contact stiffness (per area, mesh-independent) it is a damping ratio of
    // the spring, c = 2 zeta sqrt(k m) with zeta = 1/4, the same where the spring is clamped, so
    // that halving the step approaches one answer (docs/architecture.md, "Knobs that converge").
    // Under the implicit integrator the spring and the dashpot act at the step's end
    // (collide/implicit_contact.h) and need no clamp.
    Real damping = kContactDamping * mass_n * rate;
    if (!implicit && rate > 0 && stiffness > mass_n * rate * rate) {
      stiffness = mass_n * rate * rate;
    } else if (body.contact_from_material) {
      damping = kContactDamping * std::sqrt(stiffness * mass_n);
    }
    Real f_normal = stiffness * (-point.phi);
    Vec3 s_dot = Vec3::Zero();  // J_s q_s-dot
    for (int c_k = 0; c_k < 3; ++c_k) {
      const int i = sample.nodes[c_k];
      s_dot += sample.weights[c_k] * (ws.p_dot[i] - ws.d_dot(body, i));
    }
    // Relative to the obstacle's material at the point (5.11 and 5.12 against a moving one).
    const Vec3 v_obstacle = obs.velocity_at(c + ws.R * point.s);
    const Vec3 v_point = ws.R * (V + ws.omega.cross(point.s) + s_dot) - v_obstacle;
    const Real u = v_point.dot(point.n);
    f_normal -= damping * u;  // it never pulls: the total is >= 0
    f_normal = std::max(0.0, f_normal);
    magnitude[p] = f_normal;
    if (implicit) {
      // The normal push is the implicit solve's (e_p, beta_p of collide/implicit_contact.h);
      // f_normal above only bounds the friction of the points inside.
      const Real h = ws.dt, spring = damping + h * stiffness;
      if (body.order == DynamicsOrder::second) {
        ic.excess[p] = -stiffness * point.phi - spring * u;
        ic.weight[p] = h * spring;
      } else {
        ic.excess[p] = -stiffness * point.phi + spring * v_obstacle.dot(point.n);
        ic.weight[p] = spring;
      }
      magnitude[p] = 0;
      if (point.phi >= 0) continue;  // a candidate not yet inside has no friction
    }
    const Vec3 v_p = v_point - v_point.dot(point.n) * point.n;
    const Real speed = v_p.norm();
    if (speed > 0 && obs.friction > 0 && f_normal > 0) {
      BodyWorkspace::SlipPoint slip;
      slip.sample = point.sample;
      slip.speed = speed;
      slip.share = share;
      slip.limit = obs.friction * f_normal;
      slip.s = point.s;
      slip.t = Rt * v_p / speed;
      ws.slipping.push_back(slip);
    }
  }
  ws.contact_generalized.noalias() += G * magnitude;
  if (implicit) {
    ic.G.leftCols(m) = G;  // the friction below reuses G's scratch
    ic.candidates = m;
  }
  // (5.12) on each point's slip (a rolling ball's contact points do not slip), capped at the
  // force that stops the slip within one step: beyond it the explicit Coulomb law would reverse
  // the slip (rate * dt >> 1 at 0.031 s). The cap uses the mass the point moves with along its
  // slip, as the dashpot does along n.
  const int m_t = static_cast<int>(ws.slipping.size());
  auto G_t = ws.contact_directions.leftCols(m_t);
  auto friction = ws.contact_magnitude.head(m_t);
  auto mobility_t = ws.contact_mobility.head(m_t);
  for (int p = 0; p < m_t; ++p) {
    const auto& slip = ws.slipping[p];
    sample_generalized(body, ws, body.contact_samples[slip.sample], slip.s, slip.t, G_t.col(p));
  }
  inverse_effective_masses(ws, G_t, mobility_t);
  for (int p = 0; p < m_t; ++p) {
    const auto& slip = ws.slipping[p];
    const Real mass_t = slip.share / mobility_t[p];
    friction[p] = -std::min(slip.limit, kFrictionStopFraction * mass_t * rate * slip.speed);
  }
  ws.contact_generalized.noalias() += G_t * friction;
  return touching;
}

namespace {

// The implicit integrator's contact (deform/implicit_membrane.h): the penetrating nodes are moved
// out, then the touching ones stopped along the normal, by the smallest change that shares each
// push between the body's local displacements (in the metric of the substep's H) and its rigid
// and global coordinates: positions through a translation of c (compliance 1 / mass), velocities
// through c-dot, omega and q_s-dot (compliance P A^+ P^T). A stiff membrane then moves and stops
// as a whole where the node-by-node projection below would dent it by the step's whole
// penetration. Coulomb's law limits each node's slip change by beta_f times its normal change
// (5.12), as there.
void resolve_compliant(Obstacles obstacles, const BodyModel& body, Eigen::Ref<VecX> q,
                       Eigen::Ref<VecX> v, BodyWorkspace& ws) {
  ImplicitMembraneWorkspace& im = ws.implicit;
  const int n = body.n_nodes();
  const int d_q = body.layout.displacement_in_q(), d_v = body.layout.displacement_in_v();
  std::fill(im.touching.begin(), im.touching.end(), -1);
  // A node pushed into a second obstacle is taken again in the next pass.
  for (int pass = 0; pass < 4; ++pass) {
    im.nodes.clear();
    im.normals.clear();
    im.amounts.clear();
    for (int i = 0; i < n; ++i) {
      int o;
      Vec3 normal;
      const Real phi = deepest(obstacles, ws.x[i], o, normal);
      if (phi >= kProjectionMargin * 0.5) continue;
      im.nodes.push_back(i);
      im.normals.push_back(normal);
      im.amounts.push_back(kProjectionMargin - phi);
      im.touching[i] = o;
      im.touching_normal[i] = normal;
    }
    const int m = static_cast<int>(im.nodes.size());
    if (m == 0) break;
    reserve_contact_nodes(body, ws, m);
    for (int r = 0; r < m; ++r)
      for (int c = 0; c < m; ++c) im.global(r, c) = im.normals[r].dot(im.normals[c]) / body.mass;
    implicit_node_correction(body, ws);
    Vec3 shift = Vec3::Zero();
    for (int r = 0; r < m; ++r) shift += im.lambda[r] * im.normals[r] / body.mass;
    position_of(q) += shift;
    const Mat3 Rt = ws.R.transpose();
    for (int i = 0; i < n; ++i) {
      const Vec3 dx = im.change.segment<3>(3 * i);
      q.segment<3>(d_q + 3 * i) += Rt * dx;
      ws.x[i] += dx + shift;
    }
  }
  // The mass block at the moved state, for the velocities' global compliance.
  recenter_displacements(body, q, v);
  compute_body_kinematics(body, q, v, ws, false);
  factor_generalized_mass(body, q, ws);
  im.nodes.clear();
  im.normals.clear();
  im.amounts.clear();
  for (int i = 0; i < n; ++i) {
    const int o = im.touching[i];
    if (o < 0) continue;
    const Vec3& normal = im.touching_normal[i];
    const Real vn = (ws.x_dot[i] - obstacles[o].velocity_at(ws.x[i])).dot(normal);
    if (vn >= 0) continue;
    im.nodes.push_back(i);
    im.normals.push_back(normal);
    im.amounts.push_back(-vn);
  }
  const int m = static_cast<int>(im.nodes.size());
  if (m == 0) return;
  reserve_contact_nodes(body, ws, m);
  const Mat3 Rt = ws.R.transpose();
  // P_i^T (R^T n_i) = (y, p_i x y, J_i^T y) for each listed node, then A^+ of them.
  auto G = im.G.leftCols(m);
  for (int r = 0; r < m; ++r) {
    const int i = im.nodes[r];
    const Vec3 y = Rt * im.normals[r];
    auto column = G.col(r);
    column.head<3>() = y;
    column.segment<3>(3) = ws.p[i].cross(y);
    if (body.n_s > 0) {
      column.tail(body.n_s).setZero();
      add_Jt_y(ws, i, y, 1.0, column.data() + BodyLayout::kShapeInV);
    }
  }
  auto AG = im.AG.leftCols(m);
  AG = G;
  ws.A_solver.solve_in_place(AG);
  im.global.topLeftCorner(m, m).noalias() = G.transpose() * AG;
  implicit_node_correction(body, ws);
  im.dnu.noalias() = AG * im.lambda.head(m);  // change of (R^T c-dot, omega, q_s-dot)
  velocity_of(v) += ws.R * im.dnu.head<3>();
  omega_of(v) += im.dnu.segment<3>(3);
  if (body.n_s > 0) v.segment(BodyLayout::kShapeInV, body.n_s) += im.dnu.tail(body.n_s);
  for (int i = 0; i < n; ++i) {
    Vec3 dv = im.change.segment<3>(3 * i);  // the local part, world frame
    const int o = im.touching[i];
    if (o >= 0 && obstacles[o].friction > 0) {
      const Vec3& normal = im.touching_normal[i];
      const Vec3 node_change = dv + ws.R * node_from_generalized(body, ws, i, im.dnu);
      const Real stopped = node_change.dot(normal);
      const Vec3 v_rel = ws.x_dot[i] + node_change - obstacles[o].velocity_at(ws.x[i]);
      const Vec3 slip = v_rel - v_rel.dot(normal) * normal;
      const Real speed = slip.norm();
      if (speed > 0 && stopped > 0) {
        dv -= std::min(speed, obstacles[o].friction * stopped) * slip / speed;
      }
    }
    v.segment<3>(d_v + 3 * i) += Rt * dv;
  }
  compute_body_kinematics(body, q, v, ws, false);
}

}  // namespace

ContactResolution resolve_penetrations(Obstacles obstacles, const BodyModel& body,
                                       Eigen::Ref<VecX> q, Eigen::Ref<VecX> v, BodyWorkspace& ws,
                                       bool implicit) {
  ContactResolution result;
  // Local bodies need their node velocities (and always a resplit); the shape and its Jacobian
  // computed here serve the next step's first evaluation too (q_s is not changed below).
  if (body.has_local) {
    compute_body_kinematics(body, q, v, ws, false);
  } else {
    compute_node_positions(body, q, ws);
  }
  std::vector<int>& nodes = ws.penetrating;
  nodes.clear();
  for (int i = 0; i < body.n_nodes() && !obstacles.empty(); ++i) {
    int o;
    Vec3 n;
    if (deepest(obstacles, ws.x[i], o, n) < 0) nodes.push_back(i);
  }
  result.penetrating_nodes = static_cast<int>(nodes.size());
  // A dormant "auto" body out of every obstacle has nothing to resolve and no split to restore
  // (its d-dot is zero); one a collision reached is dented as a local body is, and its
  // displacements are switched on at the next frame (sim/level_of_detail.h).
  if (ws.dormant && nodes.empty()) {
    if (!obstacles.empty()) result.min_distance = min_obstacle_distance(obstacles, ws);
    return result;
  }
  const bool compliant = body.has_local && implicit && !nodes.empty();
  if (compliant) {
    resolve_compliant(obstacles, body, q, v, ws);
    // What the correction left inside (a node it would have had to pull) is projected below.
    nodes.clear();
    for (int i = 0; i < body.n_nodes(); ++i) {
      int o;
      Vec3 n;
      if (deepest(obstacles, ws.x[i], o, n) < 0) nodes.push_back(i);
    }
  }
  if (body.has_local) {
    if (!nodes.empty() || compliant) {
      const Mat3 Rt = ws.R.transpose();
      const int d_q = body.layout.displacement_in_q(), d_v = body.layout.displacement_in_v();
      for (int i : nodes) {
        // Repeat for a node inside two obstacles (a corner): each pass leaves one of them.
        for (int pass = 0; pass < 4; ++pass) {
          int o;
          Vec3 n;
          const Real phi = deepest(obstacles, ws.x[i], o, n);
          if (phi >= kProjectionMargin * 0.5) break;
          const Vec3 dx = (kProjectionMargin - phi) * n;  // step 1: project along n
          q.segment<3>(d_q + 3 * i) += Rt * dx;           // step 2: the new d
          ws.x[i] += dx;
          // An inelastic node impact, with Coulomb's law on the impulse (5.12): the slip
          // changes by at most beta_f times the normal velocity change. Both act on the velocity
          // relative to the obstacle's material, so they only remove energy in its frame.
          const Vec3 v_rel = ws.x_dot[i] - obstacles[o].velocity_at(ws.x[i]);
          const Real vn = v_rel.dot(n);
          if (vn < 0) {
            Vec3 dv = -vn * n;
            const Vec3 slip = v_rel - vn * n;
            const Real speed = slip.norm();
            if (speed > 0) {
              dv -= std::min(speed, obstacles[o].friction * -vn) * slip / speed;
            }
            v.segment<3>(d_v + 3 * i) += Rt * dv;
            ws.x_dot[i] += dv;
            ws.d_dot_body[i] += Rt * dv;
            ws.p_dot[i] += Rt * dv;
          }
        }
      }
      // No node moves or changes velocity: only p, measured from the moved origin. Recomputed
      // from q as compute_body_kinematics does (s is unchanged), not updated in place: the
      // factorization below is keyed on q and reused by the next step, so it must be the one a
      // fresh workspace computes at this q, or results would depend on the workspace's history
      // (docs/architecture.md, "Determinism": a timeline re-simulation or a rebuilt workspace
      // would differ in the last bits).
      recenter_displacements(body, q, v);
      for (int i = 0; i < body.n_nodes(); ++i) ws.p[i] = ws.s[i] + q.segment<3>(d_q + 3 * i);
    }
    // With or without contact the mean-axis split is restored: its velocity form drifts between
    // steps. The factorization at the final q is the one the next step starts with.
    factor_generalized_mass(body, q, ws);
    resplit_velocities(body, q, v, ws);
  } else if (!nodes.empty()) {
    compute_body_kinematics(body, q, v, ws, false);
    factor_generalized_mass(body, q, ws);
    resolve_generalized_impulses(obstacles, body, nodes, v, ws);
    // Position: translate c out of each obstacle by its deepest penetration.
    for (int pass = 0; pass < 8; ++pass) {
      Real worst = 0;
      Vec3 push = Vec3::Zero();
      for (int i = 0; i < body.n_nodes(); ++i) {
        int o;
        Vec3 n;
        const Real phi = deepest(obstacles, ws.x[i], o, n);
        if (phi < worst) {
          worst = phi;
          push = (kProjectionMargin - phi) * n;
        }
      }
      if (worst >= 0) break;
      position_of(q) += push;
      for (Vec3& x : ws.x) x += push;
    }
  }
  if (!obstacles.empty()) result.min_distance = min_obstacle_distance(obstacles, ws);
  return result;
}

Real contact_potential_energy(Obstacles obstacles, const BodyModel& body, BodyWorkspace& ws) {
  gather_pressing_samples(obstacles, body, ws, frame_origin(ws));
  Real energy = 0;
  for (const auto& point : ws.pressing) {
    energy += 0.5 * obstacles[point.obstacle].elasticity *
              body.contact_samples[point.sample].stiffness * point.phi * point.phi;
  }
  return energy;
}

Real min_obstacle_distance(Obstacles obstacles, const BodyWorkspace& ws) {
  Real best = 1e300;
  for (const Vec3& x : ws.x) {
    for (const ObstacleModel& o : obstacles) {
      Vec3 n;
      best = std::min(best, signed_distance(o, x, n));
    }
  }
  return best;
}

}  // namespace pbm
