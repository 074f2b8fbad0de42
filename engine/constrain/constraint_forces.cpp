#include "constrain/constraint_forces.h"

#include <algorithm>

#include "constrain/hinge_spring.h"
#include "constrain/point_constraint.h"

namespace pbm {
namespace {

// Relative regularization of N (see the header).
constexpr Real kRegularization = 1e-9;

Real end_sign(int end) {
  return end == 0 ? 1.0 : -1.0;
}

// Visits every pair of ends two constraints have on a shared body, with the sign product of
// (7.38)-(7.41); the pair of an end with itself gives (7.37)'s terms.
template <typename Visit>
void for_each_shared_body_pair(const ConstraintWorkspace& cw, Visit visit) {
  for (const std::vector<std::array<int, 2>>& ends : cw.body_ends) {
    for (const std::array<int, 2>& e1 : ends) {
      for (const std::array<int, 2>& e2 : ends) visit(e1, e2, end_sign(e1[1]) * end_sign(e2[1]));
    }
  }
}

}  // namespace

void init_constraint_workspace(const ConstrainedSystem& system, ConstraintWorkspace& cw) {
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  const int m = static_cast<int>(points.size());
  cw.n_constraints = m;
  cw.sparse = system.constraints.solver == ConstraintSolverKind::sparse;
  cw.body_ends.assign(system.bodies.size(), {});
  cw.G.assign(m, {});
  cw.Y.assign(m, {});
  int k_max = 0;
  for (const BodyModel& body : system.bodies) k_max = std::max(k_max, body.n_generalized());
  for (int l = 0; l < m; ++l) {
    for (int e = 0; e < 2; ++e) {
      const int b = points[l].ends[e].body;
      if (b < 0) continue;
      const int k = system.bodies[b].n_generalized();
      cw.G[l][e].setZero(k, 3);
      cw.Y[l][e].setZero(k, 3);
      cw.body_ends[b].push_back({l, e});
    }
  }
  cw.column.resize(system.bodies.size());
  cw.response.resize(system.bodies.size());
  cw.hinge_force.resize(system.bodies.size());
  cw.hinge_delta.resize(system.bodies.size());
  for (std::size_t b = 0; b < system.bodies.size(); ++b) {
    const int k = system.bodies[b].n_generalized();
    cw.column[b].setZero(k);
    cw.response[b].setZero(k);
    cw.hinge_force[b].setZero(k);
    cw.hinge_delta[b].setZero(k);
  }
  cw.delta.setZero(k_max);
  cw.C.setZero(3 * m);
  cw.C_dot.setZero(3 * m);
  cw.r.setZero(3 * m);
  cw.f_c.setZero(3 * m);
  if (m == 0) return;
  if (!cw.sparse) {
    cw.N.setZero(3 * m, 3 * m);
    cw.lu = Eigen::PartialPivLU<MatX>(3 * m);
    return;
  }
  // The pattern of (7.36): a 3 x 3 block wherever two constraints share a body, the diagonal
  // always (a constraint between two world anchors has none otherwise).
  std::vector<Eigen::Triplet<Real>> pattern;
  auto add_block = [&](int l, int n) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) pattern.emplace_back(3 * l + i, 3 * n + j, 0.0);
    }
  };
  for (int l = 0; l < m; ++l) add_block(l, l);
  for_each_shared_body_pair(cw, [&](const std::array<int, 2>& e1, const std::array<int, 2>& e2,
                                    Real) { add_block(e1[0], e2[0]); });
  cw.N_sparse.resize(3 * m, 3 * m);
  cw.N_sparse.setFromTriplets(pattern.begin(), pattern.end());
  cw.N_sparse.makeCompressed();
  cw.ldlt.analyze(cw.N_sparse);
}

void factor_constraint_matrix(ConstraintWorkspace& cw) {
  Real max_diagonal = 0;
  const int m = cw.n_constraints;
  if (cw.sparse) {
    std::fill(cw.N_sparse.valuePtr(), cw.N_sparse.valuePtr() + cw.N_sparse.nonZeros(), 0.0);
    for_each_shared_body_pair(
        cw, [&](const std::array<int, 2>& e1, const std::array<int, 2>& e2, Real sign) {
          const Mat3 block = sign * cw.G[e1[0]][e1[1]].transpose() * cw.Y[e2[0]][e2[1]];
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j)
              cw.N_sparse.coeffRef(3 * e1[0] + i, 3 * e2[0] + j) += block(i, j);
          }
        });
    for (int i = 0; i < 3 * m; ++i) max_diagonal = std::max(max_diagonal, cw.N_sparse.coeff(i, i));
    cw.regularization = kRegularization * std::max(max_diagonal, Real(1e-300));
    for (int i = 0; i < 3 * m; ++i) cw.N_sparse.coeffRef(i, i) += cw.regularization;
    cw.ldlt.factorize_values(cw.N_sparse);
  } else {
    cw.N.setZero();
    for_each_shared_body_pair(
        cw, [&](const std::array<int, 2>& e1, const std::array<int, 2>& e2, Real sign) {
          cw.N.block<3, 3>(3 * e1[0], 3 * e2[0]).noalias() +=
              sign * cw.G[e1[0]][e1[1]].transpose() * cw.Y[e2[0]][e2[1]];
        });
    max_diagonal = cw.N.diagonal().maxCoeff();
    cw.regularization = kRegularization * std::max(max_diagonal, Real(1e-300));
    cw.N.diagonal().array() += cw.regularization;
    cw.lu.compute(cw.N);
  }
}

void solve_constraint_matrix_negated(ConstraintWorkspace& cw, const VecX& rhs, VecX& out) {
  if (cw.sparse) {
    cw.ldlt.solve_negated(rhs, out);
  } else {
    out.noalias() = cw.lu.solve(rhs);
    out = -out;
  }
}

void fill_end_responses(const ConstrainedSystem& system, std::vector<BodyWorkspace>& bodies,
                        ConstraintWorkspace& cw) {
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  for (int l = 0; l < cw.n_constraints; ++l) {
    for (int e = 0; e < 2; ++e) {
      const ConstraintPoint& end = points[l].ends[e];
      if (end.body < 0) continue;
      const BodyModel& body = system.bodies[end.body];
      BodyWorkspace& bw = bodies[end.body];
      const MatX& G = cw.G[l][e];
      MatX& Y = cw.Y[l][e];
      const Real scale = body.order == DynamicsOrder::first ? 1.0 / body.damping : 1.0;
      for (int j = 0; j < 3; ++j) {
        cw.column[end.body] = G.col(j);
        solve_generalized_mass(bw, cw.column[end.body], cw.response[end.body]);
        Y.col(j) = scale * cw.response[end.body];
      }
    }
  }
}

void add_constraint_rates(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                          std::vector<BodyWorkspace>& bodies, ConstraintWorkspace& cw,
                          VecX& rates) {
  if (!system.constraints.hinges.empty()) {
    add_hinge_spring_rates(system, v, bodies, cw.hinge_force, cw.hinge_delta, rates);
  }
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  const int m = cw.n_constraints;
  if (m == 0) return;

  // L^T and M^-1 L^T of every end (7.20).
  for (int l = 0; l < m; ++l) {
    for (int e = 0; e < 2; ++e) {
      const ConstraintPoint& end = points[l].ends[e];
      if (end.body < 0) continue;
      constraint_end_jacobian_transpose(end, system.bodies[end.body], bodies[end.body], cw.G[l][e]);
    }
  }
  fill_end_responses(system, bodies, cw);

  // r of (7.24), (7.35): the free relative rate plus Baumgarte's feedback (7.14).
  for (int l = 0; l < m; ++l) {
    const PointConstraintModel& c = points[l];
    const ConstraintPoint& a = c.ends[0];
    const ConstraintPoint& b = c.ends[1];
    const Vec3 C = constraint_end_position(a, bodies, system, q) -
                   constraint_end_position(b, bodies, system, q);
    const Vec3 C_dot = constraint_end_velocity(a, bodies, system, v) -
                       constraint_end_velocity(b, bodies, system, v);
    const Vec3 free = constraint_end_rate(a, bodies, system, rates) -
                      constraint_end_rate(b, bodies, system, rates);
    cw.C.segment<3>(3 * l) = C;
    cw.C_dot.segment<3>(3 * l) = C_dot;
    const bool first = system.bodies[a.body].order == DynamicsOrder::first;
    // First order: C-dot + alpha C = 0, the velocity-level form whose solution is (7.16).
    cw.r.segment<3>(3 * l) =
        first ? Vec3(free + c.alpha * C) : Vec3(free + 2.0 * c.alpha * C_dot + c.beta * c.beta * C);
  }

  // N by (7.37)-(7.41), then solve (7.33).
  factor_constraint_matrix(cw);
  solve_constraint_matrix_negated(cw, cw.r, cw.f_c);

  // f_gc = s L^T f_c on each end's body (7.9), (7.20): its rates gain s M^-1 L^T f_c = s Y f_c.
  for (int l = 0; l < m; ++l) {
    const Vec3 f = cw.f_c.segment<3>(3 * l);
    for (int e = 0; e < 2; ++e) {
      const int b = points[l].ends[e].body;
      if (b < 0) continue;
      const BodyModel& body = system.bodies[b];
      VecX& delta = cw.response[b];
      delta.noalias() = end_sign(e) * cw.Y[l][e] * f;
      add_generalized_rate(body, bodies[b], delta, rates);
    }
  }
}

Real measure_constraint_violations(const ConstrainedSystem& system, const VecX& q,
                                   const std::vector<BodyWorkspace>& bodies, VecX& violations) {
  const std::vector<PointConstraintModel>& points = system.constraints.points;
  violations.resize(static_cast<Eigen::Index>(points.size()));
  Real worst = 0;
  for (std::size_t l = 0; l < points.size(); ++l) {
    const PointConstraintModel& c = points[l];
    const Vec3 C = constraint_end_position(c.ends[0], bodies, system, q) -
                   constraint_end_position(c.ends[1], bodies, system, q);
    violations[static_cast<Eigen::Index>(l)] = C.norm();
    worst = std::max(worst, C.norm());
  }
  return worst;
}

Real constraint_energy_allowance(const ConstrainedSystem& system, const VecX& q, const VecX& v,
                                 const std::vector<BodyWorkspace>& bodies) {
  Real allowance = 0;
  for (const PointConstraintModel& c : system.constraints.points) {
    const Vec3 C = constraint_end_position(c.ends[0], bodies, system, q) -
                   constraint_end_position(c.ends[1], bodies, system, q);
    const Vec3 C_dot = constraint_end_velocity(c.ends[0], bodies, system, v) -
                       constraint_end_velocity(c.ends[1], bodies, system, v);
    Real mass = 0;
    for (const ConstraintPoint& end : c.ends) {
      if (end.body >= 0) mass += system.bodies[end.body].mass;
    }
    const Real speed = std::max(c.alpha, c.beta) * C.norm() + C_dot.norm();
    allowance += mass * speed * speed;
  }
  return allowance;
}

}  // namespace pbm
