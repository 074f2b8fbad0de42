#include "deform/implicit_membrane.h"

#include <Eigen/Cholesky>
#include <algorithm>

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
  im.columns.setZero(n, 4 + 3 * body.n_s + 3);
  im.solved.setZero(n, 4 + 3 * body.n_s + 3);
  im.scratch.setZero(n, 4 + 3 * body.n_s + 3);
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
  im.nodes.reserve(static_cast<std::size_t>(n));
  im.active.reserve(static_cast<std::size_t>(n));
  im.normals.reserve(static_cast<std::size_t>(n));
  im.amounts.reserve(static_cast<std::size_t>(n));
  im.touching.assign(static_cast<std::size_t>(n), -1);
  im.touching_normal.assign(static_cast<std::size_t>(n), Vec3::Zero());
  im.capacity = 0;
  reserve_contact_nodes(body, ws, 8);
  im.change.setZero(3 * n);
  im.dnu.setZero(k);
}

void reserve_contact_nodes(const BodyModel& body, BodyWorkspace& ws, int m) {
  ImplicitMembraneWorkspace& im = ws.implicit;
  if (m <= im.capacity) return;
  const int n = body.n_nodes(), k = body.n_generalized();
  im.capacity = std::min(n, std::max(2 * m, 8));
  im.unit.setZero(n, im.capacity);
  im.node_columns.setZero(n, im.capacity);
  im.scratch_columns.setZero(n, im.capacity);
  im.system.setZero(im.capacity, im.capacity);
  im.global.setZero(im.capacity, im.capacity);
  im.G.setZero(k, im.capacity);
  im.AG.setZero(k, im.capacity);
  im.lambda.setZero(im.capacity);
  im.rhs_m.setZero(im.capacity);
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

// x = H^-1 b through the factor's parts, with `scratch` of b's shape: Eigen's own solve applies
// the inverse permutation in place, which allocates a mask at every call.
void solve_with_factor(const ImplicitMembraneWorkspace::Factor& f, const Eigen::Ref<const MatX>& b,
                       Eigen::Ref<MatX> x, Eigen::Ref<MatX> scratch) {
  scratch.noalias() = f.llt.permutationP() * b;
  f.llt.matrixL().solveInPlace(scratch);
  f.llt.matrixU().solveInPlace(scratch);
  x.noalias() = f.llt.permutationPinv() * scratch;
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
  // A^+ at this state (A's Cholesky factor, or its pseudo-inverse where A is singular).
  ws.A_solver.pseudo_inverse(im.A_pinv);
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
  // Right-hand sides M P and M g as scalar fields over the nodes (H = H_s (x) I_3): of P's 3 k
  // coordinate columns only 4 + 3 n_s differ. A translation e_a has coordinate a alone, 1 at
  // every node (field m); a rotation e_a gives (e_a x p_i)_c, a signed coordinate of p (fields
  // m p_x, m p_y, m p_z); each J column its three coordinates; then g's three. 25 solves for a
  // superquadric where 57 were.
  const int ns = body.n_s;
  const int g_col = 4 + 3 * ns;
  for (int i = 0; i < n; ++i) {
    const Real m = body.node_mass[i];
    im.columns(i, 0) = m;
    for (int l = 0; l < 3; ++l) im.columns(i, 1 + l) = m * ws.p[i][l];
    for (int kk = 0; kk < ns; ++kk)
      for (int c = 0; c < 3; ++c) im.columns(i, 4 + 3 * kk + c) = m * im.P(3 * i + c, 6 + kk);
    for (int c = 0; c < 3; ++c) im.columns(i, g_col + c) = m * im.g[3 * i + c];
  }
  solve_with_factor(im.factor, im.columns, im.solved, im.scratch);
  // Y(3 i + c, j) = (H^-1 M P)_{3 i + c, j} from the solved fields.
  auto Y = [&](int i, int c, int j) -> Real {
    if (j < 3) return j == c ? im.solved(i, 0) : 0.0;
    if (j < 6) {
      // (e_a x p)_c = -p_{a+2} for c = a + 1, p_{a+1} for c = a + 2 (indices mod 3), 0 for c = a.
      const int axis = j - 3;
      if (c == (axis + 1) % 3) return -im.solved(i, 1 + (axis + 2) % 3);
      if (c == (axis + 2) % 3) return im.solved(i, 1 + (axis + 1) % 3);
      return 0.0;
    }
    return im.solved(i, 4 + 3 * (j - 6) + c);
  };
  // Z = [M (P - Y) | M (g - y0)], so P^T Z = [P^T B Y | P^T B y0].
  for (int i = 0; i < n; ++i) {
    const Real m = body.node_mass[i];
    for (int c = 0; c < 3; ++c) {
      for (int j = 0; j < k; ++j) im.Z(3 * i + c, j) = m * (im.P(3 * i + c, j) - Y(i, c, j));
      im.Z(3 * i + c, k) = m * (im.g[3 * i + c] - im.solved(i, g_col + c));
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
      Real zi = im.solved(i, g_col + c);
      for (int j = 0; j < k; ++j) zi += Y(i, c, j) * im.mu[j];
      im.z[3 * i + c] = zi;
    }
  }
  if (second) {
    d_rate = im.z / h;
  } else {
    d_rate = im.z;
  }
}

void implicit_row_damping(const BodyModel& body, Real h, Eigen::Ref<VecX> rates) {
  if (body.order != DynamicsOrder::second || !(body.damping > 0) || !(h > 0)) return;
  rates.head(BodyLayout::kShapeInV + body.n_s) /= 1.0 + h * body.damping;
}

void implicit_node_correction(const BodyModel& body, BodyWorkspace& ws) {
  ImplicitMembraneWorkspace& im = ws.implicit;
  im.change.setZero();
  const int m = static_cast<int>(im.nodes.size());
  if (m == 0) return;
  reserve_contact_nodes(body, ws, m);  // the caller sized `global`; this only checks
  im.lambda.head(m).setZero();
  if (!im.factor.analyzed || im.factor.a < 0) return;
  const int n = body.n_nodes();
  // Columns H_s^-1 e_i of the listed nodes (H = H_s (x) I_3).
  auto unit = im.unit.leftCols(m);
  auto columns = im.node_columns.leftCols(m);
  unit.setZero();
  for (int j = 0; j < m; ++j) unit(im.nodes[j], j) = 1;
  solve_with_factor(im.factor, unit, columns, im.scratch_columns.leftCols(m));
  im.active.clear();
  for (int j = 0; j < m; ++j) im.active.push_back(j);
  // Each pass drops the nodes the solution would pull (the system is positive definite: a
  // Schur product of H^-1's block and the normals' Gram matrix, plus the global compliance).
  int a = m;
  for (int pass = 0; pass <= m && a > 0; ++pass) {
    auto system = im.system.topLeftCorner(a, a);
    auto rhs = im.rhs_m.head(a);
    for (int r = 0; r < a; ++r) {
      const int jr = im.active[r];
      rhs[r] = im.amounts[jr];
      for (int c = 0; c < a; ++c) {
        const int jc = im.active[c];
        system(r, c) =
            columns(im.nodes[jr], jc) * im.normals[jr].dot(im.normals[jc]) + im.global(jr, jc);
      }
    }
    Eigen::LLT<Eigen::Ref<MatX>> llt(system);  // in place
    llt.solveInPlace(rhs);
    int kept = 0;
    for (int r = 0; r < a; ++r) {
      if (rhs[r] >= 0) im.active[kept++] = im.active[r];
    }
    if (kept == a) break;
    a = kept;
  }
  for (int r = 0; r < a; ++r) {
    const int j = im.active[r];
    im.lambda[j] = im.rhs_m[r];
    const Vec3 push = im.rhs_m[r] * im.normals[j];
    for (int i = 0; i < n; ++i) im.change.segment<3>(3 * i) += columns(i, j) * push;
  }
}

}  // namespace pbm
