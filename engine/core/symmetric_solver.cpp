#include "core/symmetric_solver.h"

namespace pbm {

void SymmetricSolver::reserve(Eigen::Index n) {
  llt_ = Eigen::LLT<MatX>(n);
  eigen_.reserve(n);
  inverse_eigenvalues_.setZero(n);
  tmp_.setZero(n);
  work_.setZero(n, n);
  cholesky_ = false;
}

void SymmetricSolver::compute(const MatX& A) {
  llt_.compute(A);
  cholesky_ = llt_.info() == Eigen::Success;
  if (cholesky_ && A.rows() > 0) {
    const auto pivots = llt_.matrixLLT().diagonal();
    const Real smallest = pivots.minCoeff(), largest = pivots.maxCoeff();
    cholesky_ = smallest * smallest > kPivotRatio * largest * largest;
  }
  if (cholesky_) {
    work_.setIdentity(A.rows(), A.cols());
    llt_.matrixL().solveInPlace(work_);
    return;
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
  const Eigen::Index m = G.cols();
  if (scratch.rows() != G.rows() || scratch.cols() < m) scratch.resize(G.rows(), 2 * m);
  auto Y = scratch.leftCols(m);
  if (cholesky_) {
    // g^T (L L^T)^-1 g = |L^-1 g|^2: one dense product with the kept L^-1 (its upper triangle
    // zero), as fast as the eigen-vectors' product it replaced; Eigen's blocked triangular solve
    // of the 12 x m block of a contact patch cost 1.25x as many instructions.
    Y.noalias() = work_ * G;
    out.noalias() = Y.colwise().squaredNorm().transpose();
    return;
  }
  Y.noalias() = eigen_.eigenvectors().transpose() * G;
  out.noalias() = Y.cwiseAbs2().transpose() * inverse_eigenvalues_;
}

void SymmetricSolver::pseudo_inverse(MatX& out) {
  if (cholesky_) {
    out.noalias() = work_.transpose() * work_;  // A^-1 = L^-T L^-1
    return;
  }
  const MatX& V = eigen_.eigenvectors();
  work_.noalias() = V * inverse_eigenvalues_.asDiagonal();
  out.noalias() = work_ * V.transpose();
}

}  // namespace pbm
