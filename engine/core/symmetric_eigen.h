// The symmetric eigen-decomposition A = V diag(lambda) V^T of Eigen's SelfAdjointEigenSolver,
// step by step with its scratch kept between calls. Eigen's compute() builds a workspace vector
// for the Householder reflections' accumulation on every call, a heap allocation inside the step
// (docs/architecture.md: a step allocates nothing); these are the same steps, the same internal
// routines in the same order (Eigen 3.4: SelfAdjointEigenSolver::compute and
// tridiagonalization_inplace_selector::run), so the results are bit-identical to the solver's.
#pragma once

#include <Eigen/Eigenvalues>

#include "core/types.h"

namespace pbm {

class SymmetricEigenSolver {
 public:
  // Sizes the scratch for n x n matrices, so that compute() of one allocates nothing.
  void reserve(Eigen::Index n) {
    vectors_.setZero(n, n);
    values_.setZero(n);
    subdiagonal_.setZero(n > 0 ? n - 1 : 0);
    householder_.setZero(n > 0 ? n - 1 : 0);
    workspace_.setZero(n);
  }
  // Eigenvalues ascending, eigenvectors as columns; reads the lower triangle of A only.
  void compute(const MatX& A) {
    const Eigen::Index n = A.cols();
    values_.resize(n);
    if (n == 1) {
      vectors_ = A;
      values_[0] = vectors_(0, 0);
      vectors_.setOnes(1, 1);
      return;
    }
    // Map the coefficients to [-1, 1] against over- and underflow.
    vectors_ = A.triangularView<Eigen::Lower>();
    Real scale = vectors_.cwiseAbs().maxCoeff();
    if (scale == Real(0)) scale = Real(1);
    vectors_.triangularView<Eigen::Lower>() /= scale;
    subdiagonal_.resize(n - 1);
    householder_.resize(n - 1);
    Eigen::internal::tridiagonalization_inplace(vectors_, householder_);
    values_ = vectors_.diagonal();
    subdiagonal_ = vectors_.diagonal<-1>();
    Eigen::Tridiagonalization<MatX>::HouseholderSequenceType(vectors_, householder_)
        .setLength(n - 1)
        .setShift(1)
        .evalTo(vectors_, workspace_);
    converged_ = Eigen::internal::computeFromTridiagonal_impl(values_, subdiagonal_, kMaxIterations,
                                                              true, vectors_) == Eigen::Success;
    values_ *= scale;
  }
  const VecX& eigenvalues() const { return values_; }
  const MatX& eigenvectors() const { return vectors_; }
  bool converged() const { return converged_; }

 private:
  static constexpr Eigen::Index kMaxIterations = 30;  // SelfAdjointEigenSolver::m_maxIterations
  MatX vectors_;
  VecX values_, subdiagonal_, householder_, workspace_;
  bool converged_ = false;
};

}  // namespace pbm
