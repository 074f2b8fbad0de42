// SymmetricSolver (core/symmetric_solver.h) against Eigen's own dense solvers: its Cholesky path
// (with the 12 x 12 superquadric block's fixed-size quadratic forms), its run-time-sized path,
// and its pseudo-inverse fallback on a semi-definite matrix.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <random>

#include "core/symmetric_solver.h"

namespace pbm {
namespace {

MatX random_matrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::uniform_real_distribution<Real> u(-1.0, 1.0);
  MatX M(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) M(i, j) = u(rng);
  return M;
}

// A = B B^T + shift I: symmetric, of rank `rank` when shift is 0. The first rows are scaled up
// as a body's mass rows are (kilograms against a shape parameter's inertia).
MatX spd(Eigen::Index n, Eigen::Index rank, Real shift, std::mt19937& rng) {
  MatX B = random_matrix(n, rank, rng);
  B.topRows(3) *= 30.0;
  return B * B.transpose() + shift * MatX::Identity(n, n);
}

// g^T A^+ g by Eigen's eigen-decomposition, cut at 1e-10 of the largest eigenvalue.
VecX reference_forms(const MatX& A, const MatX& G) {
  Eigen::SelfAdjointEigenSolver<MatX> eig(A);
  const VecX& lambda = eig.eigenvalues();
  VecX inverse = VecX::Zero(lambda.size());
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
    if (lambda[k] > 1e-10 * lambda.cwiseAbs().maxCoeff()) inverse[k] = 1.0 / lambda[k];
  const MatX A_pinv = eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
  return (G.transpose() * A_pinv * G).diagonal();
}

void expect_forms_match(const MatX& A, bool expect_cholesky, std::mt19937& rng) {
  const Eigen::Index n = A.rows(), m = 37;
  SymmetricSolver solver;
  solver.reserve(n);
  solver.compute(A);
  EXPECT_EQ(solver.cholesky(), expect_cholesky) << "n = " << n;
  const MatX G = random_matrix(n, m, rng);
  VecX out(m);
  MatX scratch;
  solver.inverse_quadratic_forms(G, out, scratch);
  const VecX expected = reference_forms(A, G);
  for (Eigen::Index j = 0; j < m; ++j) {
    EXPECT_NEAR(out[j], expected[j], 1e-10 * std::abs(expected[j])) << "n = " << n << ", j = " << j;
  }
  // The same numbers through the solve: g^T (A^+ g).
  MatX AG = G;
  solver.solve_in_place(AG);
  for (Eigen::Index j = 0; j < m; ++j) {
    EXPECT_NEAR(G.col(j).dot(AG.col(j)), expected[j], 1e-10 * std::abs(expected[j]));
  }
}

TEST(SymmetricSolver, InverseQuadraticFormsOfTheSuperquadricBlockAreGTransposeAInverseG) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) expect_forms_match(spd(12, 12, 1e-3, rng), true, rng);
}

TEST(SymmetricSolver, InverseQuadraticFormsOfOtherSizesAreGTransposeAInverseG) {
  std::mt19937 rng(11);
  for (Eigen::Index n : {6, 9, 16}) expect_forms_match(spd(n, n, 1e-3, rng), true, rng);
}

TEST(SymmetricSolver, ASemiDefiniteBlockFallsBackToThePseudoInverse) {
  std::mt19937 rng(13);
  // Rank 10 of 12: Cholesky fails or leaves a pivot below the cut; A^+ acts on A's range only.
  expect_forms_match(spd(12, 10, 0.0, rng), false, rng);
}

TEST(SymmetricSolver, SolveIsTheInverseOnADefiniteBlock) {
  std::mt19937 rng(17);
  const MatX A = spd(12, 12, 1e-2, rng);
  SymmetricSolver solver;
  solver.reserve(12);
  solver.compute(A);
  const VecX y = random_matrix(12, 1, rng);
  VecX x(12);
  solver.solve(y, x);
  const VecX expected = A.partialPivLu().solve(y);
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
}

}  // namespace
}  // namespace pbm
