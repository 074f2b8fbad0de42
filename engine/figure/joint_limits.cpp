#include "figure/joint_limits.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "figure/joint_space_inertia.h"

namespace pbm {
namespace {

// Projected Gauss-Seidel as the contacts' (figure/figure_impact.cpp).
constexpr Real kSweepTolerance = 1e-13;
constexpr int kMaxSweeps = 20000;
constexpr Real kFeasibilityTolerance = 1e-10;

// The spring's omega dt and damping ratio (see the header).
constexpr Real kOmegaStep = 0.5;

// Which way the limit pushes: -1 at the upper (into smaller q), +1 at the lower.
Real push_sign(const JointLimit& l, Real q) {
  return q > l.upper ? -1.0 : 1.0;
}

// How far past its limit the DOF is (> 0 past it) and that excursion's rate.
Real overshoot(const JointLimit& l, Real q) {
  return std::max(q - l.upper, l.lower - q);
}

// The impulses of one impact: A p = b with each p of its limit's sign.
template <class System>
void solve_limit_impulses(const std::vector<JointLimit>& limits, const std::vector<int>& rows,
                          const Real* q, const Real* v, const Eigen::Map<MatX>& HinvGt,
                          System& sys) {
  const int r = static_cast<int>(rows.size());
  sys.A.resize(r, r);
  sys.b.resize(r);
  for (int i = 0; i < r; ++i) {
    const JointLimit& l = limits[rows[i]];
    for (int j = 0; j < r; ++j) sys.A(i, j) = HinvGt(l.v_index, j);
    sys.b[i] = -(1 + l.restitution) * v[l.v_index];
  }
  sys.cod.compute(sys.A);
  sys.p_n = sys.cod.solve(sys.b);
  const Real largest = std::max<Real>(sys.p_n.cwiseAbs().maxCoeff(), 1e-300);
  bool feasible = true;
  for (int i = 0; i < r; ++i) {
    const JointLimit& l = limits[rows[i]];
    feasible &= push_sign(l, q[l.q_index]) * sys.p_n[i] >= -kFeasibilityTolerance * largest;
  }
  if (feasible) return;
  // An impulse that would pull the DOF out of its range is zero, the others solve again.
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    Real change = 0;
    for (int i = 0; i < r; ++i) {
      const JointLimit& l = limits[rows[i]];
      const Real after = -sys.b[i] / (1 + l.restitution) + sys.A.row(i).dot(sys.p_n);
      const Real target = -l.restitution * v[l.v_index];
      const Real sign = push_sign(l, q[l.q_index]);
      const Real old = sys.p_n[i];
      sys.p_n[i] = sign * std::max<Real>(sign * (old + (target - after) / sys.A(i, i)), 0);
      change = std::max(change, std::abs(sys.p_n[i] - old));
    }
    if (change <= kSweepTolerance * std::max<Real>(sys.p_n.cwiseAbs().maxCoeff(), 1e-300)) break;
  }
}

}  // namespace

std::vector<JointLimit> compile_joint_limits(const FigureDef& def, const FigureModel& figure,
                                             const std::string& file, const std::string& path) {
  std::vector<JointLimit> limits;
  for (int i = 0; i < figure.size(); ++i) {
    const JointDef& jd = def.segments[i].joint;
    const SegmentModel& s = figure.segments[i];
    const std::string at = path + ".segments[" + std::to_string(i) + "].joint";
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
    const Real inertia = 1 / H_inv(l.v_index, l.v_index);
    l.stiffness = inertia * omega * omega;
    l.damping = 2 * inertia * omega;  // critical: 2 sqrt(k I)
  }
}

void add_joint_limit_forces(const std::vector<JointLimit>& limits, const Real* q, const Real* v,
                            Real impact_speed, Real* tau) {
  for (const JointLimit& l : limits) {
    const Real x = overshoot(l, q[l.q_index]);
    if (!(x > 0)) continue;
    const Real sign = push_sign(l, q[l.q_index]);
    // Arriving faster than impact_speed, it is the impact stage's, at the step's end: the
    // damper would otherwise take the arrival's speed before the e-law sees it (as a contact's).
    if (-sign * v[l.v_index] > impact_speed) continue;
    // Along the push: the spring on x, the damper on x's rate (-sign v), never pulling.
    const Real push = std::max<Real>(l.stiffness * x - l.damping * sign * v[l.v_index], 0);
    tau[l.v_index] += sign * push;
  }
}

Real joint_limit_energy(const std::vector<JointLimit>& limits, const Real* q) {
  Real energy = 0;
  for (const JointLimit& l : limits) {
    const Real x = overshoot(l, q[l.q_index]);
    if (x > 0) energy += 0.5 * l.stiffness * x * x;
  }
  return energy;
}

int resolve_limit_impacts(const FigureModel& figure, const std::vector<JointLimit>& limits,
                          const Real* q, Real* v, Real impact_speed, ImpactWorkspace& ws) {
  ws.limit_rows.clear();
  for (std::size_t k = 0; k < limits.size(); ++k) {
    const JointLimit& l = limits[k];
    const Real x = overshoot(l, q[l.q_index]);
    // Past the limit and moving further out faster than impact_speed.
    if (x > 0 && -push_sign(l, q[l.q_index]) * v[l.v_index] > impact_speed) {
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
  // H^-1 G^T: G's rows are the limited DOFs' rows of the identity.
  Eigen::Map<MatX> HinvGt = grown_matrix(ws.HinvJt[0], n_v, r);
  HinvGt.setZero();
  for (int i = 0; i < r; ++i) HinvGt(limits[ws.limit_rows[i]].v_index, i) = 1;
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
