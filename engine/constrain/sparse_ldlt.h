// Eigen's SimplicialLDLT (AMD ordering) with the permuted copy of the matrix and the solve's
// vectors kept between calls. SimplicialLDLT::factorize builds the permuted copy P N P^T anew and
// solve() evaluates its right-hand side and applies P^-1 in place through temporaries: heap
// allocations inside the step (docs/architecture.md: a step allocates nothing). These are the
// same steps in the same order (Eigen 3.4, SimplicialCholeskyBase::factorize and _solve_impl):
// the permuted copy's values are taken from the matrix where Eigen's copy takes them (found once
// by permuting a matrix of value indices), so factors and solutions are bit-identical.
#pragma once

#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/types.h"

namespace pbm {

class SparseLDLT : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<Real>> {
 public:
  using Matrix = Eigen::SparseMatrix<Real>;

  // The ordering and the symbolic factorization of n's pattern (compressed), and where each
  // value of P n P^T comes from.
  void analyze(const Matrix& n) {
    analyzePattern(n);
    Matrix indices = n;
    for (Eigen::Index k = 0; k < indices.nonZeros(); ++k) {
      indices.valuePtr()[k] = static_cast<Real>(k);
    }
    permuted_.resize(n.rows(), n.cols());
    permuted_.selfadjointView<Eigen::Upper>() =
        indices.selfadjointView<Eigen::Lower>().twistedBy(m_P);
    source_.resize(static_cast<std::size_t>(permuted_.nonZeros()));
    for (Eigen::Index k = 0; k < permuted_.nonZeros(); ++k) {
      source_[static_cast<std::size_t>(k)] = static_cast<Eigen::Index>(permuted_.valuePtr()[k]);
    }
    rhs_.setZero(n.rows());
    solution_.setZero(n.rows());
  }

  // factorize(n) for n with the analyzed pattern.
  void factorize_values(const Matrix& n) {
    for (std::size_t k = 0; k < source_.size(); ++k) {
      permuted_.valuePtr()[k] = n.valuePtr()[source_[k]];
    }
    factorize_preordered<true>(permuted_);
  }

  // x = n^-1 (-b): solve(-b) of the factorization.
  void solve_negated(const VecX& b, VecX& x) {
    if (m_info != Eigen::Success) return;
    rhs_ = -b;
    x = m_P * rhs_;
    if (m_matrix.nonZeros() > 0) matrixL().solveInPlace(x);
    if (m_diag.size() > 0) x = m_diag.asDiagonal().inverse() * x;
    if (m_matrix.nonZeros() > 0) matrixU().solveInPlace(x);
    solution_ = m_Pinv * x;
    x = solution_;
  }

 private:
  CholMatrixType permuted_;
  std::vector<Eigen::Index> source_;
  VecX rhs_, solution_;
};

}  // namespace pbm
