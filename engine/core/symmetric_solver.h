// x = A^+ y for a symmetric positive semi-definite A, such as a body's mass block (3.16): a
// Cholesky factor A = L L^T where A is comfortably positive definite (every body with mass and
// a positive parameter inertia floor), else the pseudo-inverse of the eigen-decomposition: 1 over
// lambda on A's range, 0 on its null space. Factoring a 12 x 12 block by Cholesky (and keeping
// L^-1) takes under a quarter of the instructions of its eigen-decomposition, which was a fifth
// of a 66-node ball's step.
// Allocation-free once reserve() has sized it (docs/architecture.md: a step allocates nothing).
#pragma once

#include <Eigen/Cholesky>

#include "core/symmetric_eigen.h"
#include "core/types.h"

namespace pbm {

class SymmetricSolver {
 public:
  // Sizes the scratch for n x n matrices.
  void reserve(Eigen::Index n);
  // Factors A; reads its lower triangle only.
  void compute(const MatX& A);
  // True when A was factored by Cholesky; false when it fell back to the pseudo-inverse.
  bool cholesky() const { return cholesky_; }
  // x = A^+ y; x may not alias y.
  void solve(const VecX& y, VecX& x);
  // B = A^+ B, column by column.
  void solve_in_place(Eigen::Ref<MatX> B);
  // out_j = g_j^T A^+ g_j for the columns g_j of G: the inverse effective masses of directions.
  // 12 rows under Cholesky (the superquadric's block) are fixed-size products over L^-1's lower
  // triangle; other sizes and the fallback use scratch, grown (by doubling) to G's size.
  void inverse_quadratic_forms(const Eigen::Ref<const MatX>& G, Eigen::Ref<VecX> out,
                               MatX& scratch);
  // A^+ itself.
  void pseudo_inverse(MatX& out);

 private:
  // Below this ratio of the smallest to the largest squared Cholesky pivot the matrix is treated
  // as semi-definite: a pivot bounds A's smallest eigenvalue from above, and the eigen-
  // decomposition's cut-off is 1e-10 of the largest.
  static constexpr Real kPivotRatio = 1e-8;
  // The superquadric's block (6 rigid + 6 shape rows) is factored at compile-time size by the
  // loops of factor_fixed: Eigen's LLT works on run-time-sized blocks even in a fixed-size matrix,
  // and with L^-1 by its triangular solves it took 12k instructions a factor, a twentieth of a
  // 66-node ball's step.
  static constexpr int kFixed = 12;
  using MatFixed = Eigen::Matrix<Real, kFixed, kFixed>;
  using VecFixed = Eigen::Matrix<Real, kFixed, 1>;
  // L and L^-1 of A = L L^T, lower triangles (the upper ones zero); false where a pivot is not
  // positive.
  bool factor_fixed(const MatX& A);
  bool fixed_ = false;  // A is 12 x 12: L in L_fixed_, L^-1 in L_inv_fixed_ (when cholesky_)
  MatFixed L_fixed_;
  MatFixed L_inv_fixed_;
  Eigen::LLT<MatX> llt_;
  SymmetricEigenSolver eigen_;
  VecX inverse_eigenvalues_;  // 1 / lambda on A's range, 0 on its null space
  VecX tmp_;
  MatX work_;  // k x k: L^-1 after a Cholesky factor, else scratch for V diag(1 / lambda)
  bool cholesky_ = false;
};

}  // namespace pbm
