#include "figure/joint_limits.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"
#include "core/quaternion.h"
#include "figure/joint_space_inertia.h"

namespace pbm {
namespace {

// Projected Gauss-Seidel as the contacts' (figure/figure_impact.cpp).
constexpr Real kSweepTolerance = 1e-13;
constexpr int kMaxSweeps = 20000;
constexpr Real kFeasibilityTolerance = 1e-10;

// The spring's omega dt and damping ratio (see the header).
constexpr Real kOmegaStep = 0.5;

// Which way the limit pushes: -1 at the upper (into smaller x), +1 at the lower.
Real push_sign(const JointLimit& l, Real x) {
  return x > l.upper ? -1.0 : 1.0;
}

// How far past its limit the coordinate x is (> 0 past it).
Real overshoot(const JointLimit& l, Real x) {
  return std::max(x - l.upper, l.lower - x);
}

int row_width(const JointLimit& l) {
  return l.swing || l.twist ? 3 : 1;
}

// The coordinate's rate g . v.
Real limit_rate(const JointLimit& l, const Vec3& g, const Real* v) {
  Real rate = 0;
  for (int k = 0; k < row_width(l); ++k) rate += g[k] * v[l.v_index + k];
  return rate;
}

// The swing's cos theta = R_zz of the joint's unit quaternion (w, x, y, z), normalized here.
Real swing_cosine(const Real* q) {
  const Real w = q[0], x = q[1], y = q[2], z = q[3];
  return (w * w - x * x - y * y + z * z) / (w * w + x * x + y * y + z * z);
}

// The impulses of one impact: A p = b with each p of its limit's sign.
template <class System>
void solve_limit_impulses(const std::vector<JointLimit>& limits, const std::vector<int>& rows,
                          const Real* q, const Real* v, const Eigen::Map<MatX>& HinvGt,
                          System& sys) {
  const int r = static_cast<int>(rows.size());
  sys.A.resize(r, r);
  sys.b.resize(r);
  sys.u.resize(r);  // each coordinate's rate before the impact
  for (int i = 0; i < r; ++i) {
    const JointLimit& l = limits[rows[i]];
    const Vec3 g = limit_row(l, q);
    for (int j = 0; j < r; ++j) {
      sys.A(i, j) = 0;
      for (int k = 0; k < row_width(l); ++k) sys.A(i, j) += g[k] * HinvGt(l.v_index + k, j);
    }
    sys.u[i] = limit_rate(l, g, v);
    sys.b[i] = -(1 + l.restitution) * sys.u[i];
  }
  sys.cod.compute(sys.A);
  sys.p_n = sys.cod.solve(sys.b);
  const Real largest = std::max<Real>(sys.p_n.cwiseAbs().maxCoeff(), 1e-300);
  bool feasible = true;
  for (int i = 0; i < r; ++i) {
    const JointLimit& l = limits[rows[i]];
    feasible &=
        push_sign(l, limit_coordinate(l, q)) * sys.p_n[i] >= -kFeasibilityTolerance * largest;
  }
  if (feasible) return;
  // An impulse that would pull the DOF out of its range is zero, the others solve again.
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    Real change = 0;
    for (int i = 0; i < r; ++i) {
      const JointLimit& l = limits[rows[i]];
      const Real after = sys.u[i] + sys.A.row(i).dot(sys.p_n);
      const Real target = -l.restitution * sys.u[i];
      const Real sign = push_sign(l, limit_coordinate(l, q));
      const Real old = sys.p_n[i];
      sys.p_n[i] = sign * std::max<Real>(sign * (old + (target - after) / sys.A(i, i)), 0);
      change = std::max(change, std::abs(sys.p_n[i] - old));
    }
    if (change <= kSweepTolerance * std::max<Real>(sys.p_n.cwiseAbs().maxCoeff(), 1e-300)) break;
  }
}

}  // namespace

Real limit_coordinate(const JointLimit& limit, const Real* q) {
  if (limit.twist) {
    // q and -q are one rotation: with w >= 0, psi lies in [-pi, pi].
    const Real* r = q + limit.q_index;
    const Real sign = r[0] < 0 ? -1 : 1;
    return 2 * std::atan2(sign * r[3], sign * r[0]);
  }
  if (!limit.swing) return q[limit.q_index];
  return std::acos(std::clamp<Real>(swing_cosine(q + limit.q_index), -1, 1));
}

Vec3 limit_row(const JointLimit& limit, const Real* q) {
  if (limit.twist) {
    // psi-dot = 2 (w z-dot - z w-dot) / (w^2 + z^2) with q-dot = q (0, omega) / 2; quadratic in
    // q, so the same for -q. At a swing of pi (w = z = 0) the twist is undefined: no row.
    const Real* r = q + limit.q_index;
    const Vec4 u = Vec4(r[0], r[1], r[2], r[3]).normalized();
    const Real w = u[0], x = u[1], y = u[2], z = u[3];
    const Real n = w * w + z * z;
    if (!(n > 0)) return Vec3::Zero();
    return Vec3(z * x - w * y, w * x + z * y, n) / n;
  }
  if (!limit.swing) return Vec3::UnitX();
  const Real* r = q + limit.q_index;
  const Vec4 quaternion = Vec4(r[0], r[1], r[2], r[3]).normalized();
  // w = R^T z, the joint frame's z in the child's; theta-dot = omega . (w x z) / sin theta.
  const Vec3 w = rotation_from_quaternion(quaternion).transpose() * Vec3::UnitZ();
  const Vec3 a = w.cross(Vec3::UnitZ());
  const Real length = a.norm();
  // At theta = 0 (or pi) every swing direction is one: none is limited there.
  return length > 0 ? Vec3(a / length) : Vec3::Zero();
}

std::vector<JointLimit> compile_joint_limits(const FigureDef& def, const FigureModel& figure,
                                             const std::string& file, const std::string& path) {
  std::vector<JointLimit> limits;
  for (int i = 0; i < figure.size(); ++i) {
    const JointDef& jd = def.segments[i].joint;
    const SegmentModel& s = figure.segments[i];
    const std::string at = path + ".segments[" + std::to_string(i) + "].joint";
    // A spherical joint's swing cone and twist limit: each an angle in (0, pi).
    const auto ball_limit = [&](Real angle, const char* key, const char* what, bool swing) {
      if (angle == 0) return;
      if (jd.kind != JointKind::spherical) {
        throw Error(file, at + "." + key, std::string("only spherical joints have a ") + what);
      }
      if (!(angle > 0 && angle < std::numbers::pi)) {
        throw Error(file, at + "." + key, "must be in (0, pi)");
      }
      if (!(jd.limit_restitution >= 0 && jd.limit_restitution <= 1)) {
        throw Error(file, at + ".limit_restitution", "must be in [0, 1]");
      }
      limits.push_back({.segment = i,
                        .swing = swing,
                        .twist = !swing,
                        .q_index = s.q_offset,
                        .v_index = s.v_offset,
                        .lower = swing ? -std::numeric_limits<Real>::infinity() : -angle,
                        .upper = angle,
                        .restitution = jd.limit_restitution});
    };
    ball_limit(jd.swing_limit, "swing_limit", "swing cone", true);
    ball_limit(jd.twist_limit, "twist_limit", "twist limit", false);
    if (jd.lower.empty() && jd.upper.empty()) continue;
    const bool scalar = jd.kind == JointKind::revolute || jd.kind == JointKind::prismatic ||
                        jd.kind == JointKind::universal;
    if (!scalar) {
      throw Error(file, at + (jd.lower.empty() ? ".upper" : ".lower"),
                  "only revolute, prismatic and universal joints have limits");
    }
    const std::size_t n = static_cast<std::size_t>(joint_v_size(jd.kind));
    for (const auto& [values, key] : {std::pair{&jd.lower, ".lower"}, {&jd.upper, ".upper"}}) {
      if (values->size() != n) {
        throw Error(file, at + key,
                    "needs " + std::to_string(n) + " number" + (n > 1 ? "s" : "") +
                        ", one per DOF (give both lower and upper)");
      }
      for (const Real x : *values) {
        if (!std::isfinite(x)) throw Error(file, at + key, "must be finite");
      }
    }
    if (!(jd.limit_restitution >= 0 && jd.limit_restitution <= 1)) {
      throw Error(file, at + ".limit_restitution", "must be in [0, 1]");
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (!(jd.lower[k] < jd.upper[k])) {
        throw Error(file, at + ".upper", "each must be greater than lower's");
      }
      limits.push_back({.segment = i,
                        .dof = static_cast<int>(k),
                        .q_index = s.q_offset + static_cast<int>(k),
                        .v_index = s.v_offset + static_cast<int>(k),
                        .lower = jd.lower[k],
                        .upper = jd.upper[k],
                        .restitution = jd.limit_restitution});
    }
  }
  return limits;
}

void size_joint_limits(const FigureModel& figure, const VecX& q0, Real dt,
                       std::vector<JointLimit>& limits) {
  if (limits.empty()) return;
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  MatX H;
  joint_space_inertia(figure, q0.data(), ws, H);
  const MatX H_inv = H.llt().solve(MatX::Identity(figure.n_v, figure.n_v));
  const Real omega = kOmegaStep / dt;
  for (JointLimit& l : limits) {
    Real inertia = 1 / H_inv(l.v_index, l.v_index);
    if (l.swing) {
      // The least over the swing's directions, which are across the child's z (a = w x z): the
      // largest eigenvalue of the x, y block of H^-1 (the twist about z is never limited).
      const Eigen::Matrix2d block = H_inv.block<2, 2>(l.v_index, l.v_index);
      inertia = 1 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(block).eigenvalues().maxCoeff();
    }
    if (l.twist) {
      // Along the twist's row g at q0: 1 / (g^T H^-1 g) (g = z at no swing).
      const Vec3 g = limit_row(l, q0.data());
      const Real along = g.dot(H_inv.block<3, 3>(l.v_index, l.v_index) * g);
      if (along > 0)
        inertia = 1 / along;
      else
        inertia = 1 / H_inv(l.v_index + 2, l.v_index + 2);
    }
    l.stiffness = inertia * omega * omega;
    l.damping = 2 * inertia * omega;  // critical: 2 sqrt(k I)
  }
}

void add_joint_limit_forces(const std::vector<JointLimit>& limits, const Real* q, const Real* v,
                            Real impact_speed, Real* tau) {
  for (const JointLimit& l : limits) {
    const Real coordinate = limit_coordinate(l, q);
    const Real x = overshoot(l, coordinate);
    if (!(x > 0)) continue;
    const Real sign = push_sign(l, coordinate);
    const Vec3 g = limit_row(l, q);
    const Real rate = limit_rate(l, g, v);
    // Arriving faster than impact_speed, it is the impact stage's, at the step's end: the
    // damper would otherwise take the arrival's speed before the e-law sees it (as a contact's).
    if (-sign * rate > impact_speed) continue;
    // Along the push: the spring on x, the damper on x's rate (-sign rate), never pulling; a
    // generalized force along the coordinate acts through its row, tau += g^T f.
    const Real push = std::max<Real>(l.stiffness * x - l.damping * sign * rate, 0);
    for (int k = 0; k < row_width(l); ++k) tau[l.v_index + k] += sign * push * g[k];
  }
}

Real joint_limit_energy(const std::vector<JointLimit>& limits, const Real* q) {
  Real energy = 0;
  for (const JointLimit& l : limits) {
    const Real x = overshoot(l, limit_coordinate(l, q));
    if (x > 0) energy += 0.5 * l.stiffness * x * x;
  }
  return energy;
}

int resolve_limit_impacts(const FigureModel& figure, const std::vector<JointLimit>& limits,
                          const Real* q, Real* v, Real impact_speed, ImpactWorkspace& ws) {
  ws.limit_rows.clear();
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const JointLimit& l = limits[k];
    const Real coordinate = limit_coordinate(l, q);
    const Real x = overshoot(l, coordinate);
    // Past the limit and moving further out faster than impact_speed.
    if (x > 0 && -push_sign(l, coordinate) * limit_rate(l, limit_row(l, q), v) > impact_speed) {
      ws.limit_rows.push_back(static_cast<int>(k));
    }
  }
  const int r = static_cast<int>(ws.limit_rows.size());
  if (r == 0) return 0;
  if (ws.figures.empty()) reserve_impact_workspace(1, figure.size(), figure.n_v, r, ws);
  const int n_v = figure.n_v;
  size_figure_workspace(figure, ws.figures[0]);
  Eigen::Map<MatX> H = grown_matrix(ws.H[0], n_v, n_v);
  joint_space_inertia(figure, q, ws.figures[0], H);
  Eigen::LLT<Eigen::Ref<MatX>> llt(H);
  // H^-1 G^T: G's rows are the limits' rows g (a DOF's: a row of the identity).
  Eigen::Map<MatX> HinvGt = grown_matrix(ws.HinvJt[0], n_v, r);
  HinvGt.setZero();
  for (int i = 0; i < r; ++i) {
    const JointLimit& l = limits[ws.limit_rows[i]];
    const Vec3 g = limit_row(l, q);
    for (int k = 0; k < row_width(l); ++k) HinvGt(l.v_index + k, i) = g[k];
  }
  llt.solveInPlace(HinvGt);
  const auto apply = [&](auto& sys) {
    solve_limit_impulses(limits, ws.limit_rows, q, v, HinvGt, sys);
    Eigen::Map<VecX>(v, n_v).noalias() += HinvGt * sys.p_n;
  };
  if (r <= kImpactRowsInPlace) {
    if (ws.in_place.empty()) ws.in_place.resize(1);
    apply(ws.in_place.front());
  } else {
    apply(ws.on_heap);
  }
  return r;
}

}  // namespace pbm
