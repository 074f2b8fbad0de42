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
  return k;
}

namespace {

// f_i += sum_j K_ij q_j over the element's n nodes; the three components share K (4.52).
template <int n>
void add_element_forces(const Eigen::Matrix4d& K, const std::array<int, 4>& nodes, const Real* q,
                        Real* f) {
  // Gather the element's nodal displacements once, then f_i += sum_j K_ij q_j per component.
  Real qx[n], qy[n], qz[n];
  for (int j = 0; j < n; ++j) {
    const Real* q_j = q + 3 * nodes[j];
    qx[j] = q_j[0];
    qy[j] = q_j[1];
    qz[j] = q_j[2];
  }
  for (int i = 0; i < n; ++i) {
    Real fx = 0, fy = 0, fz = 0;
    for (int j = 0; j < n; ++j) {
      const Real K_ij = K(j, i);  // symmetric; column access is contiguous
      fx += K_ij * qx[j];
      fy += K_ij * qy[j];
      fz += K_ij * qz[j];
    }
    Real* f_i = f + 3 * nodes[i];
    f_i[0] += fx;
    f_i[1] += fy;
    f_i[2] += fz;
  }
}

template <int n>
Real element_energy(const Eigen::Matrix4d& K, const std::array<int, 4>& nodes, const Real* q) {
  Real E = 0;
  for (int i = 0; i < n; ++i) {
    const Real* q_i = q + 3 * nodes[i];
    for (int j = 0; j < n; ++j) {
      const Real* q_j = q + 3 * nodes[j];
      E += K(i, j) * (q_i[0] * q_j[0] + q_i[1] * q_j[1] + q_i[2] * q_j[2]);
    }
  }
  return E;
}

}  // namespace

void add_membrane_forces(const Tessellation& t, const MembraneStiffness& k,
                         const Eigen::Ref<const VecX>& q_d, Eigen::Ref<VecX> f) {
  assert(q_d.size() == 3 * t.node_count() && f.size() == q_d.size());
  assert(k.K_e.size() == t.elements.size());
  const Real* q = q_d.data();
  Real* out = f.data();
  const size_t n_elements = t.elements.size();
  for (size_t e = 0; e < n_elements; ++e) {
    const std::array<int, 4>& nodes = t.elements[e].nodes;
    if (nodes[3] >= 0) {
      add_element_forces<4>(k.K_e[e], nodes, q, out);
    } else {
      add_element_forces<3>(k.K_e[e], nodes, q, out);
    }
  }
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
  assert(q_d.size() == 3 * t.node_count() && k.K_e.size() == t.elements.size());
  const Real* q = q_d.data();
  Real E = 0;
  for (size_t e = 0; e < t.elements.size(); ++e) {
    const std::array<int, 4>& nodes = t.elements[e].nodes;
    E += nodes[3] >= 0 ? element_energy<4>(k.K_e[e], nodes, q)
                       : element_energy<3>(k.K_e[e], nodes, q);
  }
  return 0.5 * E;
}

}  // namespace pbm
