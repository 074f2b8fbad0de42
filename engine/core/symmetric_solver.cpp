#include "core/symmetric_solver.h"

#include <cmath>

namespace pbm {
namespace {

// out_j = |L g_j|^2 for the columns g_j of G and a lower-triangular 12 x 12 L (column-major):
// the superquadric's block (6 rigid + 6 shape rows). Fixed-size products that Eigen unrolls and
// vectorizes, in two row blocks so the upper triangle's zero 6 x 6 block is skipped (108 products
// a column of the full 144). Eigen's dynamic product of the whole 12 x m block of a contact patch
// (packing included) took 510 instructions a column, a plain loop over the triangle 815.
void squared_norms_12(const Eigen::Matrix<Real, 12, 12>& L, const Eigen::Ref<const MatX>& G,
                      Eigen::Ref<VecX> out) {
  using Block6 = Eigen::Matrix<Real, 6, 6>;
  using Rows6 = Eigen::Matrix<Real, 6, 12>;
  using Vec6 = Eigen::Matrix<Real, 6, 1>;
  const Block6 top = L.topLeftCorner<6, 6>();
  const Rows6 bottom = L.bottomRows<6>();
  for (Eigen::Index j = 0; j < G.cols(); ++j) {
    const Real* g = G.col(j).data();
    // y = sum_c g_c L(:, c), column by column: whole packets, no horizontal sums.
    Vec6 y_top = top.col(0) * g[0];
    Vec6 y_bottom = bottom.col(0) * g[0];
    for (int c = 1; c < 6; ++c) {
      y_top += top.col(c) * g[c];
      y_bottom += bottom.col(c) * g[c];
    }
    for (int c = 6; c < 12; ++c) y_bottom += bottom.col(c) * g[c];
    out[j] = y_top.squaredNorm() + y_bottom.squaredNorm();
  }
}

}  // namespace

bool SymmetricSolver::factor_fixed(const MatX& A) {
  MatFixed& L = L_fixed_;
  L.setZero();
  VecFixed inverse_pivot;
  // Cholesky-Crout, column by column: L(i, j) = (A(i, j) - sum_k<j L(i, k) L(j, k)) / L(j, j).
  for (int j = 0; j < kFixed; ++j) {
    Real d = A(j, j);
    for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
    if (!(d > 0)) return false;
    L(j, j) = std::sqrt(d);
    inverse_pivot[j] = 1.0 / L(j, j);
    for (int i = j + 1; i < kFixed; ++i) {
      Real sum = A(i, j);
      for (int k = 0; k < j; ++k) sum -= L(i, k) * L(j, k);
      L(i, j) = sum * inverse_pivot[j];
    }
  }
  // X = L^-1 by forward substitution on the columns of I: X(i, j) = -sum_{j<=k<i} L(i, k) X(k, j)
  // / L(i, i) below the diagonal, 1 / L(j, j) on it.
  MatFixed& X = L_inv_fixed_;
  X.setZero();
  for (int j = 0; j < kFixed; ++j) {
    X(j, j) = inverse_pivot[j];
    for (int i = j + 1; i < kFixed; ++i) {
      Real sum = 0;
      for (int k = j; k < i; ++k) sum += L(i, k) * X(k, j);
      X(i, j) = -sum * inverse_pivot[i];
    }
  }
  return true;
}

void SymmetricSolver::reserve(Eigen::Index n) {
  llt_ = Eigen::LLT<MatX>(n);
  eigen_.reserve(n);
  inverse_eigenvalues_.setZero(n);
  tmp_.setZero(n);
  work_.setZero(n, n);
  cholesky_ = false;
}

void SymmetricSolver::compute(const MatX& A) {
  // Comfortably positive definite: no pivot below the ratio (see kPivotRatio).
  const auto comfortable = [](const auto& pivots) {
    const Real smallest = pivots.minCoeff(), largest = pivots.maxCoeff();
    return smallest * smallest > kPivotRatio * largest * largest;
  };
  fixed_ = A.rows() == kFixed && A.cols() == kFixed;
  if (fixed_) {
    cholesky_ = factor_fixed(A) && comfortable(L_fixed_.diagonal());
    if (cholesky_) return;
  } else {
    llt_.compute(A);
    cholesky_ = llt_.info() == Eigen::Success &&
                (A.rows() == 0 || comfortable(llt_.matrixLLT().diagonal()));
    if (cholesky_) {
      work_.setIdentity(A.rows(), A.cols());
      llt_.matrixL().solveInPlace(work_);
      return;
    }
  }
  eigen_.compute(A);
  const VecX& lambda = eigen_.eigenvalues();
  const Real cutoff = 1e-10 * lambda.cwiseAbs().maxCoeff();
  inverse_eigenvalues_.resize(lambda.size());
  for (Eigen::Index j = 0; j < lambda.size(); ++j) {
    inverse_eigenvalues_[j] = lambda[j] > cutoff ? 1.0 / lambda[j] : 0.0;
  }
}

void SymmetricSolver::solve(const VecX& y, VecX& x) {
  if (cholesky_ && fixed_) {
    const VecFixed t = L_inv_fixed_ * y;  // x = L^-T L^-1 y
    x.noalias() = L_inv_fixed_.transpose() * t;
    return;
  }
  if (cholesky_) {
    x = y;
    llt_.solveInPlace(x);
    return;
  }
  const MatX& V = eigen_.eigenvectors();
  tmp_.noalias() = V.transpose() * y;
  tmp_.array() *= inverse_eigenvalues_.array();
  x.noalias() = V * tmp_;
}

void SymmetricSolver::solve_in_place(Eigen::Ref<MatX> B) {
  if (cholesky_ && fixed_) {
    L_fixed_.triangularView<Eigen::Lower>().solveInPlace(B);
    L_fixed_.transpose().triangularView<Eigen::Upper>().solveInPlace(B);
    return;
  }
  if (cholesky_) {
    llt_.matrixL().solveInPlace(B);
    llt_.matrixU().solveInPlace(B);
    return;
  }
  for (Eigen::Index j = 0; j < B.cols(); ++j) {
    const MatX& V = eigen_.eigenvectors();
    tmp_.noalias() = V.transpose() * B.col(j);
    tmp_.array() *= inverse_eigenvalues_.array();
    B.col(j).noalias() = V * tmp_;
  }
}

void SymmetricSolver::inverse_quadratic_forms(const Eigen::Ref<const MatX>& G, Eigen::Ref<VecX> out,
                                              MatX& scratch) {
  if (cholesky_) {
    // g^T (L L^T)^-1 g = |L^-1 g|^2 with the kept L^-1, column by column over its lower triangle.
    if (fixed_) {
      squared_norms_12(L_inv_fixed_, G, out);
      return;
    }
  }
  const Eigen::Index m = G.cols();
  if (scratch.rows() != G.rows() || scratch.cols() < m) scratch.resize(G.rows(), 2 * m);
  auto Y = scratch.leftCols(m);
  if (cholesky_) {
    // Other sizes: one dense product with L^-1 (its upper triangle zero).
    Y.noalias() = work_ * G;
    out.noalias() = Y.colwise().squaredNorm().transpose();
    return;
  }
  Y.noalias() = eigen_.eigenvectors().transpose() * G;
  out.noalias() = Y.cwiseAbs2().transpose() * inverse_eigenvalues_;
}

void SymmetricSolver::pseudo_inverse(MatX& out) {
  if (cholesky_ && fixed_) {
    out.noalias() = L_inv_fixed_.transpose() * L_inv_fixed_;  // A^-1 = L^-T L^-1
    return;
  }
  if (cholesky_) {
    out.noalias() = work_.transpose() * work_;
    return;
  }
  const MatX& V = eigen_.eigenvectors();
  work_.noalias() = V * inverse_eigenvalues_.asDiagonal();
  out.noalias() = work_ * V.transpose();
}

}  // namespace pbm
