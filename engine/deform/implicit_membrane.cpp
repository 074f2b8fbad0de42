#include "deform/implicit_membrane.h"

#include "deform/body_dynamics.h"

namespace pbm {

void prepare_implicit_membrane(const BodyModel& body, BodyWorkspace& ws) {
  ImplicitMembraneWorkspace& im = ws.implicit;
  if (!body.has_local) return;
  const int n = body.n_nodes();
  const int k = body.n_generalized();
  im.K = assemble_scalar_membrane_stiffness(body.tessellation, body.stiffness);
  im.K.makeCompressed();
  // Every node lies in an element, so K's diagonal is in its pattern and H = a M + b K shares it.
  im.H = im.K;
  im.factor = {};
  im.factorizations = 0;
  im.columns.setZero(n, 3 * (k + 1));
  im.solved.setZero(n, 3 * (k + 1));
  im.P.setZero(3 * n, k);
  im.Z.setZero(3 * n, k + 1);
  im.PtZ.setZero(k, k + 1);
  im.A_pinv.setZero(k, k);
  im.S.setZero(k, k);
  im.lu = Eigen::PartialPivLU<MatX>(k);
  im.g.setZero(3 * n);
  im.z.setZero(3 * n);
  im.t3n.setZero(3 * n);
  im.mu.setZero(k);
  im.rhs.setZero(k);
  im.tk.setZero(k);
}

namespace {

// H = a M + b K on K's pattern, factored numerically (the symbolic analysis is kept).
void factor_system(const BodyModel& body, ImplicitMembraneWorkspace& im, Real a, Real b) {
  ImplicitMembraneWorkspace::Factor& f = im.factor;
  if (f.analyzed && a == f.a && b == f.b) return;
  if (!f.analyzed) {
    f.llt.analyzePattern(im.H);
    f.analyzed = true;
  }
  const Real* k_values = im.K.valuePtr();
  Real* h_values = im.H.valuePtr();
  for (Eigen::Index j = 0; j < im.K.nonZeros(); ++j) h_values[j] = b * k_values[j];
  for (int i = 0; i < body.n_nodes(); ++i) im.H.coeffRef(i, i) += a * body.node_mass[i];
  f.llt.factorize(im.H);
  f.a = a;
  f.b = b;
  ++im.factorizations;
}

// The rows P_i = [I, -p~_i, J_i] of every node, stacked (body frame).
void stack_P(const BodyModel& body, const BodyWorkspace& ws, MatX& P) {
  const int ns = body.n_s;
  for (int i = 0; i < body.n_nodes(); ++i) {
    P.block<3, 3>(3 * i, 0).setIdentity();
    P.block<3, 3>(3 * i, 3) = -skew(ws.p[i]);
    if (ns > 0) P.block(3 * i, 6, 3, ns) = ws.Jt.middleCols(3 * i, 3).transpose();
  }
}

}  // namespace

void implicit_membrane_rates(const BodyModel& body, const Eigen::Ref<const VecX>& v,
                             BodyWorkspace& ws, Real h, Eigen::Ref<VecX> rates) {
  if (!body.has_local || !(h > 0)) return;
  ImplicitMembraneWorkspace& im = ws.implicit;
  const int n = body.n_nodes();
  const int k = body.n_generalized();
  const bool second = body.order == DynamicsOrder::second;
  const Real nu = body.damping;
  if (!second && !(nu > 0)) return;  // (3.51) needs nu > 0; the model refuses it otherwise
  const int d_v = body.layout.displacement_in_v();
  auto d_rate = rates.segment(d_v, 3 * n);
  const Real a = second ? 1.0 + h * nu : 1.0;
  const Real b = second ? h * h : h / nu;
  factor_system(body, im, a, b);
  stack_P(body, ws, im.P);
  // A^+ on A's range, from the mass block's eigen-decomposition at this state.
  const MatX& V = ws.A_eigen.eigenvectors();
  im.S.noalias() = V * ws.A_inverse_eigenvalues.asDiagonal();
  im.A_pinv.noalias() = im.S * V.transpose();
  if (second) {
    // g = h d-ddot - h^2 T K d-dot, T y = M^-1 y - P A^+ P^T y.
    im.t3n.setZero();
    add_membrane_forces(body.tessellation, body.stiffness, v.segment(d_v, 3 * n), im.t3n);
    im.tk.noalias() = im.P.transpose() * im.t3n;
    im.mu.noalias() = im.A_pinv * im.tk;
    im.g.noalias() = im.P * im.mu;
    for (int i = 0; i < 3 * n; ++i) im.g[i] = im.t3n[i] / body.node_mass[i / 3] - im.g[i];
    im.g = h * d_rate - (h * h) * im.g;
  } else {
    im.g = d_rate;
  }
  // Right-hand sides M P (k columns) and M g, coordinate by coordinate: column 3 j + c holds
  // coordinate c of every node.
  for (int i = 0; i < n; ++i) {
    const Real m = body.node_mass[i];
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < k; ++j) im.columns(i, 3 * j + c) = m * im.P(3 * i + c, j);
      im.columns(i, 3 * k + c) = m * im.g[3 * i + c];
    }
  }
  im.solved = im.factor.llt.solve(im.columns);  // Y and y0
  // Z = [M (P - Y) | M (g - y0)], so P^T Z = [P^T B Y | P^T B y0].
  for (int i = 0; i < n; ++i) {
    const Real m = body.node_mass[i];
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < k; ++j) {
        im.Z(3 * i + c, j) = im.columns(i, 3 * j + c) - m * im.solved(i, 3 * j + c);
      }
      im.Z(3 * i + c, k) = im.columns(i, 3 * k + c) - m * im.solved(i, 3 * k + c);
    }
  }
  im.PtZ.noalias() = im.P.transpose() * im.Z;
  im.S.noalias() = -im.A_pinv * im.PtZ.leftCols(k);
  im.S.diagonal().array() += 1.0;
  im.rhs.noalias() = im.A_pinv * im.PtZ.col(k);
  im.lu.compute(im.S);
  im.mu = im.lu.solve(im.rhs);
  // z = y0 + Y mu.
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      Real zi = im.solved(i, 3 * k + c);
      for (int j = 0; j < k; ++j) zi += im.solved(i, 3 * j + c) * im.mu[j];
      im.z[3 * i + c] = zi;
    }
  }
  if (second) {
    d_rate = im.z / h;
  } else {
    d_rate = im.z;
  }
}

void implicit_node_correction(const BodyModel& body, BodyWorkspace& ws, std::span<const int> nodes,
                              std::span<const Vec3> normals, std::span<const Real> amounts,
                              const MatX& global, Eigen::Ref<VecX> dx, VecX& lambda) {
  ImplicitMembraneWorkspace& im = ws.implicit;
  dx.setZero();
  const int m = static_cast<int>(nodes.size());
  lambda.setZero(m);
  if (m == 0 || !im.factor.analyzed || im.factor.a < 0) return;
  const int n = body.n_nodes();
  // Columns H_s^-1 e_i of the listed nodes (H = H_s (x) I_3).
  MatX unit = MatX::Zero(n, m);
  for (int j = 0; j < m; ++j) unit(nodes[j], j) = 1;
  const MatX columns = im.factor.llt.solve(unit);
  std::vector<int> active(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) active[j] = j;
  VecX solution;
  // Each pass drops the nodes the solution would pull; m passes at most.
  for (int pass = 0; pass <= m && !active.empty(); ++pass) {
    const int a = static_cast<int>(active.size());
    MatX G(a, a);
    VecX rhs(a);
    for (int r = 0; r < a; ++r) {
      rhs[r] = amounts[active[r]];
      for (int c = 0; c < a; ++c) {
        G(r, c) = columns(nodes[active[r]], active[c]) * normals[active[r]].dot(normals[active[c]]);
        if (global.size() > 0) G(r, c) += global(active[r], active[c]);
      }
    }
    solution = G.ldlt().solve(rhs);
    std::vector<int> kept;
    for (int r = 0; r < a; ++r) {
      if (solution[r] >= 0) kept.push_back(active[r]);
    }
    if (static_cast<int>(kept.size()) == a) break;
    active = std::move(kept);
    solution.resize(0);
  }
  for (int r = 0; r < solution.size(); ++r) {
    const int j = active[r];
    lambda[j] = solution[r];
    const Vec3 push = solution[r] * normals[j];
    for (int i = 0; i < n; ++i) dx.segment<3>(3 * i) += columns(i, j) * push;
  }
}

}  // namespace pbm
