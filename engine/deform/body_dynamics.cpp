#include "deform/body_dynamics.h"

#include <cmath>
#include <cstring>

#include "core/bits.h"
#include "core/quaternion.h"
#include "deform/reference_shape.h"
#include "deform/superquadric.h"
#include "deform/superquadric_jacobian.h"

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
[[gnu::always_inline]] inline void add_Pt(const BodyModel& body, const BodyWorkspace& ws, int i,
                                          const Vec3& y, Out& out) {
  linear_part(out) += y;
  angular_part(out) += ws.p[i].cross(y);
  if (sparse_superquadric(body)) {
    add_superquadric_Jt_y(node_J(ws, i), y, out.data() + BodyLayout::kShapeInV);
  } else if (body.n_s > 0) {
    add_Jt_y(ws, i, y, 1.0, out.data() + BodyLayout::kShapeInV);
  }
}

// sum_i P_i^T r_i into r_g with r_i = R^T f_i - m_i a_i (3.13), and for local bodies
// sum_i P_i^T (r_i - (K_dd q_d)_i) into b.
void accumulate_node_forces(const BodyModel& body, const BodyWorkspace& ws, bool second, bool local,
                            VecX& r_g, VecX& b) {
  r_g.setZero();
  b.setZero();
  const Mat3 Rt = ws.R.transpose();
  for (int i = 0; i < body.n_nodes(); ++i) {
    Vec3 r = Rt * ws.force[i];                        // f_i in the body frame (3.48)
    if (second) r -= body.node_mass[i] * ws.a_vp[i];  // g_q (3.24)
    add_Pt(body, ws, i, r, r_g);
    if (local) {
      r -= ws.K_q.segment<3>(3 * i);
      add_Pt(body, ws, i, r, b);
    }
  }
}

// P_i g for a k-vector g: g_c + g_omega x p_i + J_i g_s.
[[gnu::always_inline]] inline Vec3 apply_P(const BodyModel& body, const BodyWorkspace& ws, int i,
                                           const VecX& g) {
  Vec3 r = linear_part(g) + angular_part(g).cross(ws.p[i]);
  if (sparse_superquadric(body)) {
    r += superquadric_J_times(node_J(ws, i), g.data() + BodyLayout::kShapeInV);
  } else if (body.n_s > 0) {
    r += J_times(ws, i, g.data() + BodyLayout::kShapeInV);
  }
  return r;
}

// The node sums of (3.16) for the plain superquadric over J_i's 11 non-zeros (see
// sparse_superquadric). Only those products are formed (26 for J^T J's upper triangle, 22 for p~
// J), where the dense 3 x 6 blocks take 108 and 36, and the inertia comes from the second moments
// sum m p p^T. This pass was a fifth of a resting ball's step at 1k nodes.
// BodyDynamics.MassBlockIsTheSumOfTheNodesPTransposeP checks it against sum m P^T P.
struct SuperquadricMassSums {
  Real m = 0;
  Vec3 mp = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();
  Eigen::Matrix<Real, 3, kSuperquadricParameters> mJ, mpJ;
  Eigen::Matrix<Real, kSuperquadricParameters, kSuperquadricParameters> JtJ;
};

SuperquadricMassSums superquadric_mass_sums(const BodyModel& body, const BodyWorkspace& ws) {
  // Accumulators as plain scalars, so the compiler keeps the hot ones in registers.
  Real m = 0, mx = 0, my = 0, mz = 0, sxx = 0, syy = 0, szz = 0, sxy = 0, sxz = 0, syz = 0;
  Real cx0 = 0, cx1 = 0, cx4 = 0, cx5 = 0, cy0 = 0, cy2 = 0, cy4 = 0, cy5 = 0, cz0 = 0, cz3 = 0,
       cz4 = 0;  // sum m J
  Real r00 = 0, r02 = 0, r03 = 0, r04 = 0, r05 = 0, r10 = 0, r11 = 0, r13 = 0, r14 = 0, r15 = 0,
       r20 = 0, r21 = 0, r22 = 0, r24 = 0, r25 = 0;  // sum m p~ J, row and column
  Real t00 = 0, t01 = 0, t02 = 0, t03 = 0, t04 = 0, t05 = 0, t11 = 0, t14 = 0, t15 = 0, t22 = 0,
       t24 = 0, t25 = 0, t33 = 0, t34 = 0, t44 = 0, t45 = 0, t55 = 0;  // sum m J^T J, upper
  const int n = body.n_nodes();
  for (int i = 0; i < n; ++i) {
    // Node i's block of Jt is J_i's rows x, y, z, six entries each.
    const Real* x = ws.Jt.data() + 3 * kSuperquadricParameters * i;
    const Real* y = x + kSuperquadricParameters;
    const Real* z = y + kSuperquadricParameters;
    const Real mi = body.node_mass[i];
    const Real px = ws.p[i].x(), py = ws.p[i].y(), pz = ws.p[i].z();
    m += mi;
    mx += mi * px;
    my += mi * py;
    mz += mi * pz;
    sxx += mi * px * px;
    syy += mi * py * py;
    szz += mi * pz * pz;
    sxy += mi * px * py;
    sxz += mi * px * pz;
    syz += mi * py * pz;
    const Real wx0 = mi * x[0], wx1 = mi * x[1], wx4 = mi * x[4], wx5 = mi * x[5];
    const Real wy0 = mi * y[0], wy2 = mi * y[2], wy4 = mi * y[4], wy5 = mi * y[5];
    const Real wz0 = mi * z[0], wz3 = mi * z[3], wz4 = mi * z[4];
    cx0 += wx0;
    cx1 += wx1;
    cx4 += wx4;
    cx5 += wx5;
    cy0 += wy0;
    cy2 += wy2;
    cy4 += wy4;
    cy5 += wy5;
    cz0 += wz0;
    cz3 += wz3;
    cz4 += wz4;
    // Row r of p~ (m J) is p_{r+1} (m J)_{r+2} - p_{r+2} (m J)_{r+1}.
    r00 += py * wz0 - pz * wy0;
    r02 -= pz * wy2;
    r03 += py * wz3;
    r04 += py * wz4 - pz * wy4;
    r05 -= pz * wy5;
    r10 += pz * wx0 - px * wz0;
    r11 += pz * wx1;
    r13 -= px * wz3;
    r14 += pz * wx4 - px * wz4;
    r15 += pz * wx5;
    r20 += px * wy0 - py * wx0;
    r21 -= py * wx1;
    r22 += px * wy2;
    r24 += px * wy4 - py * wx4;
    r25 += px * wy5 - py * wx5;
    t00 += wx0 * x[0] + wy0 * y[0] + wz0 * z[0];
    t01 += wx0 * x[1];
    t02 += wy0 * y[2];
    t03 += wz0 * z[3];
    t04 += wx0 * x[4] + wy0 * y[4] + wz0 * z[4];
    t05 += wx0 * x[5] + wy0 * y[5];
    t11 += wx1 * x[1];
    t14 += wx1 * x[4];
    t15 += wx1 * x[5];
    t22 += wy2 * y[2];
    t24 += wy2 * y[4];
    t25 += wy2 * y[5];
    t33 += wz3 * z[3];
    t34 += wz3 * z[4];
    t44 += wx4 * x[4] + wy4 * y[4] + wz4 * z[4];
    t45 += wx4 * x[5] + wy4 * y[5];
    t55 += wx5 * x[5] + wy5 * y[5];
  }
  SuperquadricMassSums s;
  s.m = m;
  s.mp = Vec3(mx, my, mz);
  // sum m (|p|^2 I - p p^T) from the second moments.
  s.inertia << syy + szz, -sxy, -sxz, -sxy, sxx + szz, -syz, -sxz, -syz, sxx + syy;
  s.mJ << cx0, cx1, 0, 0, cx4, cx5,  //
      cy0, 0, cy2, 0, cy4, cy5,      //
      cz0, 0, 0, cz3, cz4, 0;
  s.mpJ << r00, 0, r02, r03, r04, r05,  //
      r10, r11, 0, r13, r14, r15,       //
      r20, r21, r22, 0, r24, r25;
  s.JtJ << t00, t01, t02, t03, t04, t05,  //
      t01, t11, 0, 0, t14, t15,           //
      t02, 0, t22, 0, t24, t25,           //
      t03, 0, 0, t33, t34, 0,             //
      t04, t14, t24, t34, t44, t45,       //
      t05, t15, t25, 0, t45, t55;
  return s;
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
  ws.A_solver.reserve(k);
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

namespace {

// The deformed shapes (and bodies whose shape is fixed): s_i and J_i from the reference shape
// (2.10)-(2.27), J_i q_s-dot, and J-dot q_s-dot by a second difference of s along q_s-dot
// (step h; 0 when the accelerations are not wanted).
template <class Finish>
void general_kinematics(const BodyModel& body, BodyWorkspace& ws, bool reuse_shape, Real h,
                        const Finish& finish_node) {
  const int n = body.n_nodes();
  const VecX& q_s_dot = ws.q_s_dot;
  const VecX& q_plus = ws.q_plus;
  const VecX& q_minus = ws.q_minus;
  for (int i = 0; i < n; ++i) {
    const SuperquadricAngles& angles = body.node_angles[i];
    Vec3 jq = Vec3::Zero();
    if (body.n_s > 0) {
      if (!reuse_shape) {
        evaluate_reference_shape(body.shape, ws.q_s, angles, 1.0, ws.s[i], &ws.J_node);
        ws.Jt.middleCols(3 * i, 3) = ws.J_node.leftCols(body.n_s).transpose();
      }
      ws.p_dot[i] = J_times(ws, i, q_s_dot.data());
      if (h > 0) {
        Vec3 s_plus, s_minus;
        evaluate_reference_shape(body.shape, q_plus, angles, 1.0, s_plus, nullptr);
        evaluate_reference_shape(body.shape, q_minus, angles, 1.0, s_minus, nullptr);
        jq = (s_plus - 2.0 * ws.s[i] + s_minus) / (h * h);
      }
    } else {
      ws.s[i] = body.s_fixed[i];
      ws.p_dot[i].setZero();
    }
    finish_node(i, jq);
  }
}

// J-dot q_s-dot of the superquadric, exactly: d^2/dt^2 of e (2.7) along q_s + t r. Each
// coordinate is a product A U V of a scale A = a0 a_k and signed powers U, V of one angle each,
// so (A U V)'' = A'' U V + A U'' V + A U V'' + 2 (A' U' V + A' U V' + A U' V'), with
// A' = r0 a_k + a0 r_k, A'' = 2 r0 r_k, U' = ln|cos u| C_u r4 (the basis' lnC_u r4) and
// U'' = ln|cos u| U' r4. The same as superquadric_second_derivative (the test
// BodyDynamics.SuperquadricKinematicsAreTheShapesAndItsJacobian compares them) in a third of
// its instructions, without its series products.
[[gnu::always_inline]] inline Vec3 superquadric_jdot_qdot(Real a0, Real a1, Real a2, Real a3,
                                                          const SuperquadricBasis& b,
                                                          const SuperquadricAngles& angles,
                                                          const VecX& r) {
  const Real r0 = r[0], r4 = r[4], r5 = r[5];
  // First and second derivatives of the signed powers along r.
  const Real dCu = b.lnC_u * r4, dSu = b.lnS_u * r4, dCv = b.lnC_v * r5, dSv = b.lnS_v * r5;
  const Real ddCu = angles.ln_cos_u * dCu * r4, ddSu = angles.ln_sin_u * dSu * r4;
  const Real ddCv = angles.ln_cos_v * dCv * r5, ddSv = angles.ln_sin_v * dSv * r5;
  // (A U V)'' for A = a0 a_k (A'' = 2 r0 r_k).
  const auto product = [&](Real ak, Real rk, Real U, Real dU, Real ddU, Real V, Real dV, Real ddV) {
    const Real A = a0 * ak, dA = r0 * ak + a0 * rk, ddA = 2 * r0 * rk;
    return ddA * U * V + A * (ddU * V + U * ddV) + 2 * (dA * (dU * V + U * dV) + A * dU * dV);
  };
  const Real A3 = a0 * a3, dA3 = r0 * a3 + a0 * r[3], ddA3 = 2 * r0 * r[3];
  return Vec3(product(a1, r[1], b.C_u, dCu, ddCu, b.C_v, dCv, ddCv),
              product(a2, r[2], b.C_u, dCu, ddCu, b.S_v, dSv, ddSv),
              ddA3 * b.S_u + 2 * dA3 * dSu + A3 * ddSu);
}

// The plain superquadric (n_s = 6): s_i and J_i by (2.7) and (2.9), written straight into J_i's
// block of Jt with the same expressions as evaluate_superquadric (so s is bitwise the same
// whichever computed it), and J_i q_s-dot over J_i's 11 non-zeros: 15% fewer instructions at
// 1k nodes than the general pass, which builds a 3 x 6 Jacobian, copies it transposed and
// multiplies it whole.
template <class Finish>
void superquadric_kinematics(const BodyModel& body, BodyWorkspace& ws, bool reuse_shape,
                             bool second, const Finish& finish_node) {
  const int n = body.n_nodes();
  const VecX& q_s = ws.q_s;
  const Real a0 = q_s[0], a1 = q_s[1], a2 = q_s[2], a3 = q_s[3];
  const VecX& r = ws.q_s_dot;
  for (int i = 0; i < n; ++i) {
    const SuperquadricBasis& b = ws.basis[i];
    Real* x = ws.Jt.data() + 3 * kSuperquadricParameters * i;  // rows x, y, z of J_i
    Real* y = x + kSuperquadricParameters;
    Real* z = y + kSuperquadricParameters;
    if (!reuse_shape) {
      ws.s[i] = Vec3(a0 * (a1 * b.C_u * b.C_v), a0 * (a2 * b.C_u * b.S_v), a0 * (a3 * b.S_u));
      x[0] = a1 * b.C_u * b.C_v;
      x[1] = a0 * b.C_u * b.C_v;
      x[2] = x[3] = 0;
      x[4] = a0 * a1 * b.lnC_u * b.C_v;
      x[5] = a0 * a1 * b.C_u * b.lnC_v;
      y[0] = a2 * b.C_u * b.S_v;
      y[1] = y[3] = 0;
      y[2] = a0 * b.C_u * b.S_v;
      y[4] = a0 * a2 * b.lnC_u * b.S_v;
      y[5] = a0 * a2 * b.C_u * b.lnS_v;
      z[0] = a3 * b.S_u;
      z[1] = z[2] = z[5] = 0;
      z[3] = a0 * b.S_u;
      z[4] = a0 * a3 * b.lnS_u;
    }
    ws.p_dot[i] = superquadric_J_times(x, r.data());
    Vec3 jq = Vec3::Zero();
    if (second) jq = superquadric_jdot_qdot(a0, a1, a2, a3, b, body.node_angles[i], r);
    finish_node(i, jq);
  }
}

}  // namespace

void compute_body_kinematics(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                             const Eigen::Ref<const VecX>& v, BodyWorkspace& ws,
                             bool with_accelerations) {
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
  // The rest of node i from s_i and J_i q_s-dot in p_dot: its dent, world position, velocity and
  // velocity-product acceleration (3.18).
  const auto finish_node = [&](int i, const Vec3& jq) __attribute__((always_inline)) {
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
  };
  if (sparse_superquadric(body)) {
    superquadric_kinematics(body, ws, reuse_shape, second, finish_node);
  } else {
    general_kinematics(body, ws, reuse_shape, h, finish_node);
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
  if (sparse_superquadric(body)) {
    const SuperquadricMassSums sums = superquadric_mass_sums(body, ws);
    m = sums.m;
    mp = sums.mp;
    inertia = sums.inertia;
    mJ = sums.mJ;
    mpJ = sums.mpJ;
    JtJ = sums.JtJ;
  } else {
    for (int i = 0; i < n; ++i) {
      const Real mi = body.node_mass[i];
      const Vec3& p = ws.p[i];
      m += mi;
      mp += mi * p;
      inertia += mi * (p.squaredNorm() * Mat3::Identity() - p * p.transpose());
    }
  }
  if (ns > 0 && !sparse_superquadric(body)) {
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
  ws.A_solver.compute(A);
}

void solve_generalized_mass(BodyWorkspace& ws, const VecX& y, VecX& x) {
  ws.A_solver.solve(y, x);
}

void inverse_effective_masses(BodyWorkspace& ws, const Eigen::Ref<const MatX>& G,
                              Eigen::Ref<VecX> out) {
  ws.A_solver.inverse_quadratic_forms(G, out, ws.contact_rotated);
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
  accumulate_node_forces(body, ws, second, local, ws.r_g, ws.b);
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
