#include "deform/body_dynamics.h"

#include <cmath>
#include <cstring>

#include "core/bits.h"
#include "core/quaternion.h"
#include "deform/reference_shape.h"
#include "deform/superquadric.h"

namespace pbm {
namespace {

// Offsets of a body's q_s and q_d in its q, and of their rates in its v (deform/body_layout.h).
struct BodySlices {
  int s_q, d_q;  // offsets of q_s and q_d in q
  int s_v, d_v;  // offsets of q_s-dot and d-dot in v
};
BodySlices slices(const BodyModel& body) {
  return {BodyLayout::kShapeInQ, body.layout.displacement_in_q(), BodyLayout::kShapeInV,
          body.layout.displacement_in_v()};
}

// P_i^T y for P_i = [I, -p~_i, J_i]: (y, p_i x y, J_i^T y).
template <class Out>
void add_Pt(const BodyModel& body, const BodyWorkspace& ws, int i, const Vec3& y, Out& out) {
  linear_part(out) += y;
  angular_part(out) += ws.p[i].cross(y);
  if (body.n_s > 0) add_Jt_y(ws, i, y, 1.0, out.data() + BodyLayout::kShapeInV);
}

// P_i g for a k-vector g: g_c + g_omega x p_i + J_i g_s.
Vec3 apply_P(const BodyModel& body, const BodyWorkspace& ws, int i, const VecX& g) {
  Vec3 r = linear_part(g) + angular_part(g).cross(ws.p[i]);
  if (body.n_s > 0) r += J_times(ws, i, g.data() + BodyLayout::kShapeInV);
  return r;
}

}  // namespace

Vec3 node_from_generalized(const BodyModel& body, const BodyWorkspace& ws, int i, const VecX& g) {
  return apply_P(body, ws, i, g);
}

VecX generalized_from_node(const BodyModel& body, const BodyWorkspace& ws, int i, const Vec3& y) {
  VecX out = VecX::Zero(body.n_generalized());
  add_Pt(body, ws, i, y, out);
  return out;
}

void gauge_direction(const VecX& q_s, VecX& n) {
  n.setZero(q_s.size());
  n[0] = q_s[0];
  n.segment<3>(1) = -q_s.segment<3>(1);
  n.normalize();  // the same division by |n| as normalized()
}

VecX gauge_direction(const VecX& q_s) {
  VecX n;
  gauge_direction(q_s, n);
  return n;
}

void resize_workspace(const BodyModel& body, BodyWorkspace& ws) {
  const int n = body.n_nodes();
  const int k = body.n_generalized();
  ws.q_s.resize(body.n_shape);
  ws.q_s_rest = body.q_s0;
  ws.s.assign(n, Vec3::Zero());
  ws.p.assign(n, Vec3::Zero());
  ws.p_dot.assign(n, Vec3::Zero());
  ws.d_dot_body.assign(n, Vec3::Zero());
  ws.a_vp.assign(n, Vec3::Zero());
  ws.x.assign(n, Vec3::Zero());
  ws.x_dot.assign(n, Vec3::Zero());
  ws.force.assign(n, Vec3::Zero());
  ws.contact.assign(n, -1);
  ws.Jt.setZero(body.n_s, 3 * n);
  ws.J_node.setZero(3, body.n_shape);
  ws.basis.assign(body.shape == ShapeKind::superquadric ? n : 0, SuperquadricBasis{});
  ws.u_powers.assign(body.grid_u.size(), SignedPowers{});
  ws.v_powers.assign(body.grid_v.size(), SignedPowers{});
  ws.sample_u_powers.assign(body.sample_grid_u.size(), SignedPowers{});
  ws.sample_v_powers.assign(body.sample_grid_v.size(), SignedPowers{});
  ws.sample_u_stamp.assign(body.sample_grid_u.size(), 0);
  ws.sample_v_stamp.assign(body.sample_grid_v.size(), 0);
  ws.sample_stamp = 0;
  ws.contact_generalized.setZero(k);
  ws.q_s_dot.setZero(body.n_s);
  ws.q_plus.setZero(body.n_s);
  ws.q_minus.setZero(body.n_s);
  ws.gauge.setZero(body.n_s);
  ws.gauge_scaled.setZero(body.n_s);
  ws.shape_scratch.setZero(body.n_s);
  ws.mass_pJ_a.setZero(body.n_s);
  ws.mass_pJ_b.setZero(body.n_s);
  ws.surface_distance.assign(n, 0.0);
  ws.pressing.clear();
  ws.pressing.reserve(3 * 2 * static_cast<std::size_t>(n));
  ws.slipping.clear();
  ws.slipping.reserve(3 * 2 * static_cast<std::size_t>(n));
  ws.penetrating.clear();
  ws.penetrating.reserve(static_cast<std::size_t>(n));
  // Room for every contact sample pressing at once, so a contact that spreads never allocates
  // inside a step.
  const auto samples = static_cast<Eigen::Index>(body.contact_samples.size());
  ws.contact_directions.setZero(k, samples);
  ws.contact_rotated.setZero(k, samples);
  ws.contact_magnitude.setZero(samples);
  ws.contact_mobility.setZero(samples);
  ws.K_q.setZero(body.has_local ? 3 * n : 0);
  ws.A.setZero(k, k);
  ws.A_eigen.reserve(k);
  ws.A_inverse_eigenvalues.setZero(k);
  ws.A_tmp.setZero(k);
  ws.r_g.setZero(k);
  ws.b.setZero(k);
  ws.gamma.setZero(k);
  ws.alpha.setZero(k);
  ws.mass_J.setZero(3, body.n_s);
  ws.mass_pJ.setZero(3, body.n_s);
  ws.mass_JtJ.setZero(body.n_s, body.n_s);
  ws.mass_Jt.setZero(body.n_s, 3 * n);
  ws.node_mass_3.resize(3 * n);
  for (int i = 0; i < n; ++i) ws.node_mass_3.segment<3>(3 * i).setConstant(body.node_mass[i]);
  ws.kinematics_valid = false;
  // The caches keyed on q_s and q describe the s, Jt and A just cleared: a workspace resized
  // again (init_workspace after an edit) must not reuse them.
  ws.shape_key.resize(0);
  ws.shape_has_J = false;
  ws.mass_key.resize(0);
}

void compute_node_bases(const BodyModel& body, const VecX& q_s, BodyWorkspace& ws) {
  for (std::size_t k = 0; k < body.grid_u.size(); ++k) {
    ws.u_powers[k] = latitude_powers(body.grid_u[k], q_s(4));
  }
  for (std::size_t k = 0; k < body.grid_v.size(); ++k) {
    ws.v_powers[k] = longitude_powers(body.grid_v[k], q_s(5));
  }
  for (int i = 0; i < body.n_nodes(); ++i) {
    const std::array<int, 2>& g = body.node_grid[i];
    ws.basis[i] = combine_powers(ws.u_powers[g[0]], ws.v_powers[g[1]]);
  }
}

void compute_reference_positions(const BodyModel& body, const VecX& q_s, BodyWorkspace& ws) {
  if (body.n_s == 0) {
    for (int i = 0; i < body.n_nodes(); ++i) ws.s[i] = body.s_fixed[i];
    return;
  }
  if (same_bits(ws.shape_key, q_s)) return;
  if (body.shape == ShapeKind::superquadric) {
    compute_node_bases(body, q_s, ws);
    for (int i = 0; i < body.n_nodes(); ++i) {
      evaluate_superquadric(q_s, ws.basis[i], 1.0, ws.s[i], nullptr);
    }
  } else {
    for (int i = 0; i < body.n_nodes(); ++i) {
      evaluate_reference_shape(body.shape, q_s, body.node_angles[i], 1.0, ws.s[i], nullptr);
    }
  }
  ws.shape_key = q_s;
  ws.shape_has_J = false;
}

void compute_body_kinematics(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                             const Eigen::Ref<const VecX>& v, BodyWorkspace& ws,
                             bool with_accelerations) {
  const int n = body.n_nodes();
  const BodySlices sl = slices(body);
  const Vec3 c = position_of(q);
  ws.R = rotation_from_quaternion(quaternion_of(q));
  const Vec3 c_dot = velocity_of(v);
  const Vec3 omega = omega_of(v);
  ws.omega = omega;
  if (body.n_s > 0) {
    ws.q_s = q.segment(sl.s_q, body.n_s);
  } else {
    ws.q_s = body.q_s_fixed;
  }
  const bool second = body.order == DynamicsOrder::second && with_accelerations;
  const bool reuse_shape = body.n_s > 0 && ws.shape_has_J && same_bits(ws.shape_key, ws.q_s);
  if (body.n_s > 0 && !reuse_shape && body.shape == ShapeKind::superquadric) {
    compute_node_bases(body, ws.q_s, ws);
  }
  // J-dot q_s-dot: exact for the superquadric; for the deformed shapes a second difference of s
  // along q_s-dot, h keeping h*q_s-dot ~ 1e-4 so the truncation (h^2) and rounding (eps/h^2)
  // errors both stay near 1e-8 relative.
  VecX& q_s_dot = ws.q_s_dot;
  Real h = 0;
  VecX& q_plus = ws.q_plus;
  VecX& q_minus = ws.q_minus;
  if (body.n_s > 0) {
    q_s_dot = v.segment(sl.s_v, body.n_s);
    const Real vmax = q_s_dot.cwiseAbs().maxCoeff();
    if (second && vmax > 0 && body.shape != ShapeKind::superquadric) {
      h = 1e-4 / vmax;
      q_plus = ws.q_s + h * q_s_dot;
      q_minus = ws.q_s - h * q_s_dot;
    }
  }
  const Vec3 V = ws.R.transpose() * c_dot;
  for (int i = 0; i < n; ++i) {
    const SuperquadricAngles& angles = body.node_angles[i];
    Vec3 jq = Vec3::Zero();
    if (body.n_s > 0) {
      if (!reuse_shape) {
        if (body.shape == ShapeKind::superquadric) {
          SuperquadricJacobian J_e;
          evaluate_superquadric(ws.q_s, ws.basis[i], 1.0, ws.s[i], &J_e);
          ws.Jt.middleCols(3 * i, 3) = J_e.transpose();
        } else {
          evaluate_reference_shape(body.shape, ws.q_s, angles, 1.0, ws.s[i], &ws.J_node);
          ws.Jt.middleCols(3 * i, 3) = ws.J_node.leftCols(body.n_s).transpose();
        }
      }
      ws.p_dot[i] = J_times(ws, i, q_s_dot.data());
      if (second && body.shape == ShapeKind::superquadric) {
        jq = superquadric_second_derivative(ws.q_s, ws.basis[i], angles, 1.0, q_s_dot);
      } else if (h > 0) {
        Vec3 s_plus, s_minus;
        evaluate_reference_shape(body.shape, q_plus, angles, 1.0, s_plus, nullptr);
        evaluate_reference_shape(body.shape, q_minus, angles, 1.0, s_minus, nullptr);
        jq = (s_plus - 2.0 * ws.s[i] + s_minus) / (h * h);
      }
    } else {
      ws.s[i] = body.s_fixed[i];
      ws.p_dot[i].setZero();
    }
    ws.p[i] = ws.s[i];
    if (body.has_local) {
      ws.p[i] += q.segment<3>(sl.d_q + 3 * i);
      ws.d_dot_body[i] = v.segment<3>(sl.d_v + 3 * i);
      ws.p_dot[i] += ws.d_dot_body[i];
    }
    ws.x[i] = c + ws.R * ws.p[i];
    ws.x_dot[i] = ws.R * (V + omega.cross(ws.p[i]) + ws.p_dot[i]);
    if (second) {
      ws.a_vp[i] = omega.cross(omega.cross(ws.p[i])) + 2.0 * omega.cross(ws.p_dot[i]) + jq;
    }
  }
  if (body.n_s > 0 && !reuse_shape) {
    ws.shape_key = ws.q_s;
    ws.shape_has_J = true;
  }
  ws.kinematics_valid = true;
}

void compute_elastic_forces(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            BodyWorkspace& ws) {
  if (!body.has_local || ws.dormant) return;  // a dormant body's q_d is zero
  ws.K_q.setZero();
  add_membrane_forces(body.tessellation, body.stiffness, displacement_of(body.layout, q), ws.K_q);
}

void factor_generalized_mass(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                             BodyWorkspace& ws) {
  if (ws.mass_key.size() == q.size() &&
      std::memcmp(ws.mass_key.data(), q.data(),
                  sizeof(Real) * static_cast<std::size_t>(q.size())) == 0) {
    return;
  }
  ws.mass_key = q;
  const int n = body.n_nodes();
  const int ns = body.n_s;
  // Blocks of (3.16) in the body frame: the 3 x 3 ones node by node, the ones with J as products
  // over all nodes of the mass-weighted Jt (vectorized, where per-node loops over a run-time n_s
  // are not).
  Real m = 0;
  Vec3 mp = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  MatX& mJ = ws.mass_J;
  MatX& mpJ = ws.mass_pJ;
  MatX& JtJ = ws.mass_JtJ;
  if (ns == kSuperquadricParameters) {
    // One pass over the nodes in fixed-size blocks: m J, m p~ J and m J^T J accumulate in
    // registers, where the run-time path below streams a scaled copy of J^T through three
    // products.
    using Block36 = Eigen::Matrix<Real, 3, kSuperquadricParameters>;
    using Block6 = Eigen::Matrix<Real, kSuperquadricParameters, kSuperquadricParameters>;
    Block36 sum_mJ = Block36::Zero(), sum_mpJ = Block36::Zero();
    Block6 sum_JtJ = Block6::Zero();
    for (int i = 0; i < n; ++i) {
      const Eigen::Map<const SuperquadricJt> Jt_i(ws.Jt.data() + 3 * i * ns);
      const Real mi = body.node_mass[i];
      const Vec3& p = ws.p[i];
      m += mi;
      mp += mi * p;
      inertia += mi * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
      const Block36 mJ_i = mi * Jt_i.transpose();
      sum_mJ += mJ_i;
      // Row r of p~ (m J) is p_{r+1} (m J)_{r+2} - p_{r+2} (m J)_{r+1}.
      sum_mpJ.row(0) += p.y() * mJ_i.row(2) - p.z() * mJ_i.row(1);
      sum_mpJ.row(1) += p.z() * mJ_i.row(0) - p.x() * mJ_i.row(2);
      sum_mpJ.row(2) += p.x() * mJ_i.row(1) - p.y() * mJ_i.row(0);
      sum_JtJ.noalias() += Jt_i * mJ_i;
    }
    mJ = sum_mJ;
    mpJ = sum_mpJ;
    JtJ = sum_JtJ;
  } else {
    for (int i = 0; i < n; ++i) {
      const Real mi = body.node_mass[i];
      const Vec3& p = ws.p[i];
      m += mi;
      mp += mi * p;
      inertia += mi * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
    }
  }
  if (ns > 0 && ns != kSuperquadricParameters) {
    using Strided = Eigen::Map<const MatX, 0, Eigen::OuterStride<>>;
    using Coordinates = Eigen::Map<const VecX, 0, Eigen::InnerStride<3>>;
    ws.mass_Jt.noalias() = ws.Jt * ws.node_mass_3.asDiagonal();
    // Columns of mass_Jt for coordinate r of every node: n_s x n.
    auto component = [&](int r) { return Strided(ws.mass_Jt.data() + r * ns, ns, n, {3 * ns}); };
    auto coordinate = [&](int r) { return Coordinates(ws.p[0].data() + r, n); };
    for (int r = 0; r < 3; ++r) mJ.row(r) = component(r).rowwise().sum().transpose();  // M_cs
    // M_theta s = sum m p~ J: row r of p x (m J_k) is p_{r+1} mJ_{r+2} - p_{r+2} mJ_{r+1}.
    for (int r = 0; r < 3; ++r) {
      const int a = (r + 1) % 3, b = (r + 2) % 3;
      // Each product into its own scratch, as Eigen would into temporaries, without allocating.
      ws.mass_pJ_a.noalias() = component(b) * coordinate(a);
      ws.mass_pJ_b.noalias() = component(a) * coordinate(b);
      mpJ.row(r) = (ws.mass_pJ_a - ws.mass_pJ_b).transpose();
    }
    JtJ.noalias() = ws.mass_Jt * ws.Jt.transpose();  // M_ss = sum m J^T J
  }
  MatX& A = ws.A;
  A.setZero();
  A.block<3, 3>(0, 0) = m * Mat3::Identity();  // M_cc
  A.block<3, 3>(0, 3) = -skew(mp);             // M_c theta: sum m (-p~)
  A.block<3, 3>(3, 0) = skew(mp);
  A.block<3, 3>(3, 3) = inertia;  // M_theta theta = sum m p~^T p~
  if (ns > 0) {
    A.block(0, 6, 3, ns) = mJ;  // M_cs
    A.block(6, 0, ns, 3) = mJ.transpose();
    A.block(3, 6, 3, ns) = mpJ;  // M_theta s = sum m p~ J
    A.block(6, 3, ns, 3) = mpJ.transpose();
    A.block(6, 6, ns, ns) = JtJ;  // M_ss
    A.block(6, 6, ns, ns).diagonal() += body.parameter_inertia_floor;
    if (ns >= 4) {
      VecX& n_gauge = ws.gauge;
      gauge_direction(ws.q_s, n_gauge);
      ws.gauge_scaled = body.parameter_inertia * n_gauge;
      A.block(6, 6, ns, ns).noalias() += ws.gauge_scaled * n_gauge.transpose();
    }
  }
  ws.A_eigen.compute(A);
  const VecX& lambda = ws.A_eigen.eigenvalues();
  const Real cutoff = 1e-10 * lambda.cwiseAbs().maxCoeff();
  for (int j = 0; j < lambda.size(); ++j) {
    ws.A_inverse_eigenvalues[j] = lambda[j] > cutoff ? 1.0 / lambda[j] : 0.0;
  }
}

void solve_generalized_mass(BodyWorkspace& ws, const VecX& y, VecX& x) {
  const MatX& V = ws.A_eigen.eigenvectors();
  ws.A_tmp.noalias() = V.transpose() * y;
  ws.A_tmp.array() *= ws.A_inverse_eigenvalues.array();
  x.noalias() = V * ws.A_tmp;
}

void inverse_effective_masses(BodyWorkspace& ws, const Eigen::Ref<const MatX>& G,
                              Eigen::Ref<VecX> out) {
  const Eigen::Index m = G.cols();
  if (ws.contact_rotated.cols() < m) ws.contact_rotated.resize(G.rows(), 2 * m);
  auto Y = ws.contact_rotated.leftCols(m);
  Y.noalias() = ws.A_eigen.eigenvectors().transpose() * G;
  out.noalias() = Y.cwiseAbs2().transpose() * ws.A_inverse_eigenvalues;
}

void solve_body_dynamics(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                         const Eigen::Ref<const VecX>& v, BodyWorkspace& ws, Eigen::Ref<VecX> out) {
  const int n = body.n_nodes();
  const int ns = body.n_s;
  const BodySlices sl = slices(body);
  const bool second = body.order == DynamicsOrder::second;
  // A dormant "auto" body runs as a global one: d-ddot = 0 keeps q_d = d-dot = 0, and the
  // membrane and the local solve are skipped (sim/level_of_detail.h).
  const bool local = body.has_local && !ws.dormant;
  const Mat3 Rt = ws.R.transpose();
  ws.r_g.setZero();
  ws.b.setZero();
  for (int i = 0; i < n; ++i) {
    Vec3 r = Rt * ws.force[i];                        // f_i in the body frame (3.48)
    if (second) r -= body.node_mass[i] * ws.a_vp[i];  // g_q (3.24)
    add_Pt(body, ws, i, r, ws.r_g);
    if (local) {
      r -= ws.K_q.segment<3>(3 * i);
      add_Pt(body, ws, i, r, ws.b);
    }
  }
  // Collision forces on the rigid + global rows (see collide/rigid_contact.h).
  ws.r_g += ws.contact_generalized;
  if (ns > 0) {
    // Global elastic force (3.33) and the damping of the parameter inertia.
    const auto q_s = q.segment(sl.s_q, ns);
    ws.r_g.tail(ns) -= body.k_s.cwiseProduct(q_s - ws.q_s_rest);
    if (second) {
      ws.r_g.tail(ns) -=
          body.damping * body.parameter_inertia_floor.cwiseProduct(v.segment(sl.s_v, ns));
    }
    if (second && ns >= 4) {
      VecX& n_gauge = ws.gauge;
      gauge_direction(ws.q_s, n_gauge);
      ws.r_g.tail(ns) -=
          body.damping * body.parameter_inertia * n_gauge.dot(v.segment(sl.s_v, ns)) * n_gauge;
    }
  }
  // First-order bodies: nu M q-dot = f_q - K q (3.51); second-order: M alpha = rhs (3.13).
  const Real scale = second ? 1.0 : 1.0 / body.damping;
  VecX& alpha = ws.alpha;
  solve_generalized_mass(ws, ws.r_g, alpha);
  alpha *= scale;
  // c-ddot (or c-dot) back to the world frame.
  velocity_of(out) = ws.R * linear_part(alpha);
  omega_of(out) = angular_part(alpha);
  if (ns > 0) out.segment(sl.s_v, ns) = alpha.tail(ns);
  if (body.has_local && !local) out.segment(sl.d_v, 3 * n).setZero();
  if (local) {
    solve_generalized_mass(ws, ws.b, ws.gamma);
    for (int i = 0; i < n; ++i) {
      Vec3 r = Rt * ws.force[i] - ws.K_q.segment<3>(3 * i);
      if (second) r -= body.node_mass[i] * ws.a_vp[i];
      out.segment<3>(sl.d_v + 3 * i) =
          (r / body.node_mass[i] - apply_P(body, ws, i, ws.gamma)) * scale;
    }
  }
}

void resplit_velocities(const BodyModel& body, const Eigen::Ref<const VecX>& q, Eigen::Ref<VecX> v,
                        BodyWorkspace& ws) {
  (void)q;
  if (!body.has_local) return;
  const int n = body.n_nodes();
  const BodySlices sl = slices(body);
  ws.b.setZero();
  for (int i = 0; i < n; ++i) {
    add_Pt(body, ws, i, Vec3(body.node_mass[i] * v.segment<3>(sl.d_v + 3 * i)), ws.b);
  }
  // The parameter inertia's share of the q_s rows is not part of sum m P^T P.
  solve_generalized_mass(ws, ws.b, ws.gamma);
  velocity_of(v) += ws.R * linear_part(ws.gamma);
  omega_of(v) += angular_part(ws.gamma);
  if (body.n_s > 0) v.segment(sl.s_v, body.n_s) += ws.gamma.tail(body.n_s);
  for (int i = 0; i < n; ++i) v.segment<3>(sl.d_v + 3 * i) -= apply_P(body, ws, i, ws.gamma);
}

void restore_velocity_split(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                            Eigen::Ref<VecX> v, BodyWorkspace& ws) {
  if (!body.has_local || ws.dormant) return;
  compute_body_kinematics(body, q, v, ws, false);
  factor_generalized_mass(body, q, ws);
  resplit_velocities(body, q, v, ws);
}

Vec3 recenter_displacements(const BodyModel& body, Eigen::Ref<VecX> q, Eigen::Ref<VecX> v) {
  if (!body.has_local) return Vec3::Zero();
  const int n = body.n_nodes();
  const int d_q = body.layout.displacement_in_q();
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < n; ++i) mean += body.node_mass[i] * q.segment<3>(d_q + 3 * i);
  mean /= body.mass;
  const Mat3 R = rotation_from_quaternion(quaternion_of(q));
  position_of(q) += R * mean;
  for (int i = 0; i < n; ++i) q.segment<3>(d_q + 3 * i) -= mean;
  velocity_of(v) += R * Vec3(omega_of(v)).cross(mean);
  return mean;
}

BodyEnergy compute_body_energy(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                               const Eigen::Ref<const VecX>& v, const Vec3& gravity,
                               BodyWorkspace& ws) {
  BodyEnergy e;
  const int n = body.n_nodes();
  const BodySlices sl = slices(body);
  for (int i = 0; i < n; ++i) {
    const Real m = body.node_mass[i];
    e.kinetic += 0.5 * m * ws.x_dot[i].squaredNorm();
    e.potential -= m * gravity.dot(ws.x[i]);
    e.linear_momentum += m * ws.x_dot[i];
    e.angular_momentum += m * ws.x[i].cross(ws.x_dot[i]);
  }
  if (body.n_s > 0) {
    const auto q_s_dot = v.segment(sl.s_v, body.n_s);
    e.kinetic += 0.5 * q_s_dot.dot(body.parameter_inertia_floor.cwiseProduct(q_s_dot));
    if (body.n_s >= 4) {
      gauge_direction(ws.q_s, ws.gauge);
      const Real rate = ws.gauge.dot(q_s_dot);
      e.kinetic += 0.5 * body.parameter_inertia * rate * rate;
    }
    VecX& dq = ws.shape_scratch;
    dq = q.segment(sl.s_q, body.n_s) - ws.q_s_rest;
    e.elastic += 0.5 * dq.dot(body.k_s.cwiseProduct(dq));
  }
  if (body.has_local) {
    e.elastic += membrane_energy(body.tessellation, body.stiffness, q.segment(sl.d_q, 3 * n));
  }
  return e;
}

}  // namespace pbm
