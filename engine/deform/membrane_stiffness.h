// Loaded-membrane stiffness K_dd of the local displacements q_d (sec. 4.5.1) for the C0 elements
// of tessellation.h, with constant weights w10 = w01 = w1 and w00 = w0 (end of sec. 4.5.1).
//
// Element matrix (4.52), identical for the three displacement components k = 1, 2, 3:
//   K^j_ddk = integral over E_j of Gamma^T D Gamma du dv,   Gamma rows gamma_i^T (4.48)-(4.49),
//   gamma_i = [dN_i/du, dN_i/dv, N_i],   D = diag(w1, w1, w0) (4.45),
// integrated in material coordinates as the book does (it drops det J_{x,u} of (4.4), end of
// sec. 4.2), with quadrature exact for its degree-2 integrand (2x2 Gauss-Legendre on quads, the
// 3-point Radau rule of Table A.2 on triangles). The result reproduces (4.55) and (4.56).
//
// Layout of q_d and forces: 3 * n_nodes, node-major (x, y, z of node 0, then node 1, ...), in
// the body frame. Energy of the element: E^j = q_dk^T K^j_ddk q_dk summed over k (4.41)-(4.43);
// membrane_energy returns the elastic energy 0.5 q_d^T K_dd q_d whose gradient is K_dd q_d.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/types.h"
#include "deform/tessellation.h"

namespace pbm {

// K^j_ddk of (4.52); the upper-left n x n block is used, n = element_node_count(e.kind), the
// rest is 0. Rows and columns follow the element's local node numbering (Element::nodes).
Eigen::Matrix4d element_membrane_stiffness(const Element& e, Real w0, Real w1);

// One K^j_ddk per element of the tessellation, in Tessellation::elements order. Built once per
// Model (it depends only on the tessellation and the material); constant while time runs.
struct MembraneStiffness {
  std::vector<Eigen::Matrix4d> K_e;
  // The assembled scalar K = sum_j K^j_ddk (4.38) by rows (compressed sparse rows, columns
  // sorted): node i's force is sum_j K_ij q_j over its neighbours, about 7 products per
  // coordinate where the element loop spends 27 per triangle, twice as many triangles as nodes.
  std::vector<int> row_start, column;
  std::vector<Real> value;
};
MembraneStiffness build_membrane_stiffness(const Tessellation& t, Real w0, Real w1);

// f += K_dd q_d, node by node over the assembled rows (sec. 6.1 assembles none; the rows are the
// same sums, formed once per Model). q_d and f have size 3 * t.node_count(). No allocation: safe
// for the per-step path.
void add_membrane_forces(const Tessellation& t, const MembraneStiffness& k,
                         const Eigen::Ref<const VecX>& q_d, Eigen::Ref<VecX> f);

// The scalar matrix sum_j K^j_ddk (n_nodes x n_nodes) shared by the three coordinates:
// K_dd = K (x) I_3 in the node-major layout.
Eigen::SparseMatrix<double> assemble_scalar_membrane_stiffness(const Tessellation& t,
                                                               const MembraneStiffness& k);

// K_dd = sum_j K^j_dd expanded to 3 n_nodes x 3 n_nodes (4.38), for tests and implicit solves.
Eigen::SparseMatrix<double> assemble_membrane_stiffness(const Tessellation& t,
                                                        const MembraneStiffness& k);

// Diagonal entry (K_dd)_ii of each node (the same for its three components): the force per unit
// displacement of node i alone.
VecX membrane_stiffness_diagonal(const Tessellation& t, const MembraneStiffness& k);

// Elastic energy 0.5 q_d^T K_dd q_d over the assembled rows. No allocation.
Real membrane_energy(const Tessellation& t, const MembraneStiffness& k,
                     const Eigen::Ref<const VecX>& q_d);

}  // namespace pbm
