#include "deform/membrane_stiffness.h"

#include <cassert>

#include "deform/shape_functions.h"

namespace pbm {

Eigen::Matrix4d element_membrane_stiffness(const Element& e, Real w0, Real w1) {
  // gamma_i^T D gamma_j = w1 (dN_i/du dN_j/du + dN_i/dv dN_j/dv) + w0 N_i N_j (4.45), (4.48):
  // degree 2 in (xi, eta) per variable on quads and in total on the linear triangles.
  const ElementRule rule = element_quadrature_rule(e.kind, e.a, e.b, 2);
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  for (int q = 0; q < rule.n; ++q) {
    const Vec2& x = rule.xi_eta[static_cast<size_t>(q)];
    const ShapeFunctions s = evaluate_shape_functions(e, x.x(), x.y());
    // K^j_ddk = integral Gamma^T D Gamma (4.52)
    K += rule.weight[static_cast<size_t>(q)] *
         (w1 * (s.dN_du * s.dN_du.transpose() + s.dN_dv * s.dN_dv.transpose()) +
          w0 * (s.N * s.N.transpose()));
  }
  return K;
}

MembraneStiffness build_membrane_stiffness(const Tessellation& t, Real w0, Real w1) {
  MembraneStiffness k;
  k.K_e.reserve(t.elements.size());
  for (const Element& e : t.elements) k.K_e.push_back(element_membrane_stiffness(e, w0, w1));
  Eigen::SparseMatrix<double, Eigen::RowMajor> rows = assemble_scalar_membrane_stiffness(t, k);
  rows.makeCompressed();
  const auto n = static_cast<std::size_t>(rows.rows());
  const auto nnz = static_cast<std::size_t>(rows.nonZeros());
  k.row_start.assign(rows.outerIndexPtr(), rows.outerIndexPtr() + n + 1);
  k.column.assign(rows.innerIndexPtr(), rows.innerIndexPtr() + nnz);
  k.value.assign(rows.valuePtr(), rows.valuePtr() + nnz);
  return k;
}

namespace {

// (K q)_i for the three coordinates of node i, over its row.
[[gnu::always_inline]] inline Vec3 row_times(const MembraneStiffness& k, int i, const Real* q) {
  Real fx = 0, fy = 0, fz = 0;
  for (int e = k.row_start[i]; e < k.row_start[i + 1]; ++e) {
    const Real K_ij = k.value[e];
    const Real* q_j = q + 3 * k.column[e];
    fx += K_ij * q_j[0];
    fy += K_ij * q_j[1];
    fz += K_ij * q_j[2];
  }
  return Vec3(fx, fy, fz);
}

}  // namespace

void add_membrane_forces(const Tessellation& t, const MembraneStiffness& k,
                         const Eigen::Ref<const VecX>& q_d, Eigen::Ref<VecX> f) {
  assert(q_d.size() == 3 * t.node_count() && f.size() == q_d.size());
  assert(k.row_start.size() == static_cast<std::size_t>(t.node_count()) + 1);
  const Real* q = q_d.data();
  for (int i = 0; i < t.node_count(); ++i) f.segment<3>(3 * i) += row_times(k, i, q);
}

Eigen::SparseMatrix<double> assemble_scalar_membrane_stiffness(const Tessellation& t,
                                                               const MembraneStiffness& k) {
  assert(k.K_e.size() == t.elements.size());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(t.elements.size() * 16);
  for (size_t e = 0; e < t.elements.size(); ++e) {
    const Element& el = t.elements[e];
    const int n = element_node_count(el.kind);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) entries.emplace_back(el.nodes[i], el.nodes[j], k.K_e[e](i, j));
    }
  }
  Eigen::SparseMatrix<double> K(t.node_count(), t.node_count());
  K.setFromTriplets(entries.begin(), entries.end());  // sums duplicates: the assembly (4.38)
  return K;
}

Eigen::SparseMatrix<double> assemble_membrane_stiffness(const Tessellation& t,
                                                        const MembraneStiffness& k) {
  const Eigen::SparseMatrix<double> scalar = assemble_scalar_membrane_stiffness(t, k);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * static_cast<size_t>(scalar.nonZeros()));
  for (int col = 0; col < scalar.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(scalar, col); it; ++it) {
      for (int c = 0; c < 3; ++c) {
        entries.emplace_back(3 * static_cast<int>(it.row()) + c, 3 * col + c, it.value());
      }
    }
  }
  const int size = 3 * t.node_count();
  Eigen::SparseMatrix<double> K(size, size);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

VecX membrane_stiffness_diagonal(const Tessellation& t, const MembraneStiffness& k) {
  VecX diagonal = VecX::Zero(t.node_count());
  for (size_t e = 0; e < t.elements.size(); ++e) {
    const Element& el = t.elements[e];
    for (int i = 0; i < element_node_count(el.kind); ++i) diagonal[el.nodes[i]] += k.K_e[e](i, i);
  }
  return diagonal;
}

Real membrane_energy(const Tessellation& t, const MembraneStiffness& k,
                     const Eigen::Ref<const VecX>& q_d) {
  assert(q_d.size() == 3 * t.node_count());
  assert(k.row_start.size() == static_cast<std::size_t>(t.node_count()) + 1);
  const Real* q = q_d.data();
  Real E = 0;
  for (int i = 0; i < t.node_count(); ++i) E += q_d.segment<3>(3 * i).dot(row_times(k, i, q));
  return 0.5 * E;
}

}  // namespace pbm
