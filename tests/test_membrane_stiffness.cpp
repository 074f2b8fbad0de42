// Membrane stiffness K_dd (sec. 4.5.1): element matrices against the book's closed forms (4.55),
// (4.56) and hand-derived ones, and the assembled matrix's properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <Eigen/SparseCore>

#include "deform/membrane_stiffness.h"
#include "deform/shape_functions.h"
#include "deform/tessellation.h"

namespace pbm {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

// (4.55): bilinear rectangle, nodes 1..4 at (xi, eta) = (-1,-1), (1,-1), (1,1), (-1,1).
Eigen::Matrix4d quad_closed_form(Real a, Real b, Real w0, Real w1) {
  const Real diag = a * b * (w1 / (3 * a * a) + w1 / (3 * b * b) + w0 / 9);
  const Real along_u = a * b / 4 * (-4 * w1 / (3 * a * a) + 2 * w1 / (3 * b * b) + 2 * w0 / 9);
  const Real along_v = a * b / 4 * (2 * w1 / (3 * a * a) - 4 * w1 / (3 * b * b) + 2 * w0 / 9);
  const Real diagonal = a * b / 4 * (-2 * w1 / (3 * a * a) - 2 * w1 / (3 * b * b) + w0 / 9);
  Eigen::Matrix4d K;
  K << diag, along_u, diagonal, along_v,  //
      along_u, diag, along_v, diagonal,   // K23 = K14, K24 = K13
      diagonal, along_v, diag, along_u,   // K34 = K12
      along_v, diagonal, along_u, diag;
  return K;
}

// (4.56): south pole triangle, nodes at (0,0), (1,0), (1,1), N = (1 - xi, xi - eta, eta).
Eigen::Matrix4d south_closed_form(Real a, Real b, Real w0, Real w1) {
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  K(0, 0) = a * b / 2 * (w1 / (a * a) + w0 / 6);
  K(0, 1) = K(1, 0) = a * b / 2 * (-w1 / (a * a) + w0 / 12);
  K(0, 2) = K(2, 0) = a * b / 24 * w0;
  K(1, 1) = a * b / 2 * (w1 / (b * b) + w1 / (a * a) + w0 / 6);
  K(1, 2) = K(2, 1) = a * b / 2 * (-w1 / (b * b) + w0 / 12);
  K(2, 2) = a * b / 2 * (w1 / (b * b) + w0 / 6);
  return K;
}

// North pole triangle (4.10)-(4.17), derived by hand. The element is the right triangle of area
// A = ab/2 and its N_i are its barycentric coordinates, so the w0 part is the linear triangle's
// "mass" integral: int N_i N_j = A/6 (i = j), A/12 (i != j), i.e. ab/12 and ab/24. The gradients
// are constant: grad N_1 = (-1/a, -1/b), grad N_2 = (1/a, 0), grad N_3 = (0, 1/b) (4.15)-(4.16),
// so the w1 part is A w1 grad N_i . grad N_j:
//   K11 = ab/2 w1 (1/a^2 + 1/b^2) + ab/12 w0     K12 = -ab/2 w1/a^2 + ab/24 w0
//   K13 = -ab/2 w1/b^2 + ab/24 w0                K22 = ab/2 w1/a^2 + ab/12 w0
//   K23 = ab/24 w0                               K33 = ab/2 w1/b^2 + ab/12 w0
Eigen::Matrix4d north_closed_form(Real a, Real b, Real w0, Real w1) {
  const Real A = a * b / 2;
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  K(0, 0) = A * w1 * (1 / (a * a) + 1 / (b * b)) + a * b / 12 * w0;
  K(0, 1) = K(1, 0) = -A * w1 / (a * a) + a * b / 24 * w0;
  K(0, 2) = K(2, 0) = -A * w1 / (b * b) + a * b / 24 * w0;
  K(1, 1) = A * w1 / (a * a) + a * b / 12 * w0;
  K(1, 2) = K(2, 1) = a * b / 24 * w0;
  K(2, 2) = A * w1 / (b * b) + a * b / 12 * w0;
  return K;
}

// Mid-region triangle (4.26)-(4.33), same reasoning: area ab/2, barycentric N_i, gradients
// grad N_1 = (0, -1/b), grad N_2 = (1/a, 1/b), grad N_3 = (-1/a, 0) (4.31)-(4.32):
//   K11 = ab/2 w1/b^2 + ab/12 w0                 K12 = -ab/2 w1/b^2 + ab/24 w0
//   K13 = ab/24 w0                               K22 = ab/2 w1 (1/a^2 + 1/b^2) + ab/12 w0
//   K23 = -ab/2 w1/a^2 + ab/24 w0                K33 = ab/2 w1/a^2 + ab/12 w0
Eigen::Matrix4d mid_closed_form(Real a, Real b, Real w0, Real w1) {
  const Real A = a * b / 2;
  Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
  K(0, 0) = A * w1 / (b * b) + a * b / 12 * w0;
  K(0, 1) = K(1, 0) = -A * w1 / (b * b) + a * b / 24 * w0;
  K(0, 2) = K(2, 0) = a * b / 24 * w0;
  K(1, 1) = A * w1 * (1 / (a * a) + 1 / (b * b)) + a * b / 12 * w0;
  K(1, 2) = K(2, 1) = -A * w1 / (a * a) + a * b / 24 * w0;
  K(2, 2) = A * w1 / (a * a) + a * b / 12 * w0;
  return K;
}

Element element_of(ElementKind kind, Real a, Real b) {
  return Element{kind, {0, 1, 2, kind == ElementKind::quad ? 3 : -1}, a, b, 0.1, -0.2};
}

// Max-entry relative difference.
Real relative_difference(const Eigen::Matrix4d& K, const Eigen::Matrix4d& expected) {
  return (K - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

TEST(ElementMembraneStiffness, MatchesClosedFormsForEveryElementKind) {
  int checked = 0;
  for (Real a : {0.1, 0.3, 1.0}) {
    for (Real b : {0.2, 0.5, 2.0}) {
      for (Real w0 : {0.0, 1.1, 20.0}) {
        for (Real w1 : {0.5, 15.0, 85.0}) {
          const auto check = [&](ElementKind kind, const Eigen::Matrix4d& expected) {
            const Eigen::Matrix4d K = element_membrane_stiffness(element_of(kind, a, b), w0, w1);
            EXPECT_LT(relative_difference(K, expected), 1e-12)
                << "kind " << static_cast<int>(kind) << " a=" << a << " b=" << b << " w0=" << w0
                << " w1=" << w1 << "\n"
                << K << "\nexpected\n"
                << expected;
            ++checked;
          };
          check(ElementKind::quad, quad_closed_form(a, b, w0, w1));    // (4.55)
          check(ElementKind::south, south_closed_form(a, b, w0, w1));  // (4.56)
          check(ElementKind::north, north_closed_form(a, b, w0, w1));
          check(ElementKind::mid, mid_closed_form(a, b, w0, w1));
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 81);
}

// The book's south element with its printed N_2 = xi would give K22's w0 part int xi^2 =
// ab/4 instead of (4.56)'s ab/12: (4.56) itself confirms the corrected N_2 = xi - eta.
TEST(ElementMembraneStiffness, SouthW0PartIsTheCorrectedShapeFunctionsMass) {
  const Eigen::Matrix4d K = element_membrane_stiffness(element_of(ElementKind::south, 1, 1), 1, 0);
  EXPECT_NEAR(K(1, 1), 1.0 / 12, 1e-15);
}

// An independent, higher-order quadrature (4x4 Gauss-Legendre on quads, the 7-point Radau rule on
// triangles) gives the same matrix: the degree-2 rules used are exact.
TEST(ElementMembraneStiffness, AgreesWithHigherOrderQuadrature) {
  for (ElementKind kind :
       {ElementKind::quad, ElementKind::north, ElementKind::south, ElementKind::mid}) {
    const Element e = element_of(kind, 0.27, 0.81);
    const Real w0 = 3.3, w1 = 7.7;
    const ElementRule rule =
        element_quadrature_rule(kind, e.a, e.b, kind == ElementKind::quad ? 7 : 3);
    Eigen::Matrix4d K = Eigen::Matrix4d::Zero();
    for (int q = 0; q < rule.n; ++q) {
      const ShapeFunctions s = evaluate_shape_functions(e, rule.xi_eta[q].x(), rule.xi_eta[q].y());
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          K(i, j) += rule.weight[q] * (w1 * (s.dN_du[i] * s.dN_du[j] + s.dN_dv[i] * s.dN_dv[j]) +
                                       w0 * s.N[i] * s.N[j]);
        }
      }
    }
    EXPECT_LT(relative_difference(element_membrane_stiffness(e, w0, w1), K), 1e-13);
  }
}

// ---------------------------------------------------------------- assembled K_dd

struct Case {
  TessellationKind kind;
  int rings, segments;
};
constexpr Case kCases[] = {{TessellationKind::quads, 5, 7}, {TessellationKind::triangles, 6, 5}};

VecX random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> U(-1, 1);
  VecX x(n);
  for (int i = 0; i < n; ++i) x[i] = U(rng);
  return x;
}

// Smallest pivot of a plain Cholesky factorization A = L L^T, relative to the largest diagonal
// entry: positive iff A is positive definite. Written out here (instead of an Eigen solver) so the
// test is independent of the code it checks.
Real smallest_relative_cholesky_pivot(Eigen::MatrixXd A) {
  const Eigen::Index n = A.rows();
  const Real scale = A.diagonal().maxCoeff();
  Real smallest = 1e300;
  for (Eigen::Index j = 0; j < n; ++j) {
    Real pivot = A(j, j);
    for (Eigen::Index k = 0; k < j; ++k) pivot -= A(j, k) * A(j, k);
    smallest = std::min(smallest, pivot / scale);
    if (pivot <= 0) return smallest;
    A(j, j) = std::sqrt(pivot);
    for (Eigen::Index i = j + 1; i < n; ++i) {
      Real x = A(i, j);
      for (Eigen::Index k = 0; k < j; ++k) x -= A(i, k) * A(j, k);
      A(i, j) = x / A(j, j);
    }
  }
  return smallest;
}

// K_dd = K_c (x) I_3 (4.52): the components do not couple and share one n x n matrix K_c, which
// is symmetric, positive definite for w0 > 0, and for w0 = 0 positive semidefinite with only the
// constants in its null space (K_c + 1 1^T is then positive definite, and K_c 1 = 0 is checked
// below).
TEST(MembraneStiffness, AssembledMatrixIsSymmetricPositiveSemidefinite) {
  for (const Case& c : kCases) {
    const Tessellation t = tessellate({.kind = c.kind, .rings = c.rings, .segments = c.segments});
    const int n = t.node_count();
    for (Real w0 : {0.0, 20.0}) {
      const Eigen::MatrixXd K =
          Eigen::MatrixXd(assemble_membrane_stiffness(t, build_membrane_stiffness(t, w0, 15.0)));
      ASSERT_EQ(K.rows(), 3 * n);
      EXPECT_EQ((K - K.transpose()).cwiseAbs().maxCoeff(), 0.0);
      Eigen::MatrixXd K_c(n, n);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          K_c(i, j) = K(3 * i, 3 * j);
          for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
              EXPECT_EQ(K(3 * i + a, 3 * j + b), a == b ? K_c(i, j) : 0.0);
            }
          }
        }
      }
      if (w0 == 0) {
        EXPECT_LT((K_c * VecX::Ones(n)).cwiseAbs().maxCoeff(), 1e-12 * K_c.diagonal().maxCoeff());
        // Without the 1 1^T term the factorization breaks down: the null space is there.
        EXPECT_LT(smallest_relative_cholesky_pivot(K_c), 1e-10);
        const Real scale = K_c.diagonal().maxCoeff() / n;
        K_c += scale * Eigen::MatrixXd::Ones(n, n);
      }
      EXPECT_GT(smallest_relative_cholesky_pivot(K_c), 1e-8) << "w0=" << w0;
    }
  }
}

// K q for q = constant c in every component: the w1 part vanishes (gradients of a partition of
// unity sum to 0) and the w0 part gives w0 c int N_i = w0 c times the row sums of the mass-like
// matrix int N_i N_j. Per element int N_i = ab/4 on quads (4.9) and (ab/2)/3 = ab/6 on triangles.
TEST(MembraneStiffness, ConstantDisplacementGivesW0TimesNodalAreas) {
  for (const Case& c : kCases) {
    const Tessellation t = tessellate({.kind = c.kind, .rings = c.rings, .segments = c.segments});
    VecX nodal_area = VecX::Zero(t.node_count());
    for (const Element& e : t.elements) {
      const int n = element_node_count(e.kind);
      const Real share = e.kind == ElementKind::quad ? e.a * e.b / 4 : e.a * e.b / 6;
      for (int i = 0; i < n; ++i) nodal_area[e.nodes[i]] += share;
    }
    const Vec3 d(0.3, -1.2, 2.0);
    VecX q(3 * t.node_count());
    for (int i = 0; i < t.node_count(); ++i) q.segment<3>(3 * i) = d;
    for (Real w0 : {0.0, 1.1, 20.0}) {
      const MembraneStiffness k = build_membrane_stiffness(t, w0, 85.0);
      VecX f = VecX::Zero(q.size());
      add_membrane_forces(t, k, q, f);
      for (int i = 0; i < t.node_count(); ++i) {
        const Vec3 expected = w0 * nodal_area[i] * d;
        EXPECT_LT((f.segment<3>(3 * i) - expected).norm(), 1e-12 * (1 + expected.norm()))
            << "node " << i << " w0=" << w0;
      }
    }
  }
}

TEST(MembraneStiffness, RowPassEqualsTheAssembled3nMatrixAndEnergy) {
  for (const Case& c : kCases) {
    const Tessellation t = tessellate({.kind = c.kind, .rings = c.rings, .segments = c.segments});
    const MembraneStiffness k = build_membrane_stiffness(t, 1.1, 5.0);
    const Eigen::SparseMatrix<double> K = assemble_membrane_stiffness(t, k);
    const VecX q = random_vector(3 * t.node_count(), 7);
    const VecX f0 = random_vector(3 * t.node_count(), 11);
    VecX f = f0;
    add_membrane_forces(t, k, q, f);  // accumulates onto f
    const VecX expected = f0 + K * q;
    EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
    const Real E = membrane_energy(t, k, q);
    const Real expected_E = 0.5 * q.dot(K * q);
    EXPECT_NEAR(E, expected_E, 1e-12 * std::abs(expected_E));
    EXPECT_GT(E, 0.0);
  }
}

TEST(MembraneStiffness, DiagonalIsTheAssembledDiagonal) {
  for (const Case& c : kCases) {
    const Tessellation t = tessellate({.kind = c.kind, .rings = c.rings, .segments = c.segments});
    const MembraneStiffness k = build_membrane_stiffness(t, 1.1, 5.0);
    const VecX K_diag = VecX(assemble_membrane_stiffness(t, k).diagonal());
    const VecX diagonal = membrane_stiffness_diagonal(t, k);
    ASSERT_EQ(diagonal.size(), t.node_count());
    for (int i = 0; i < t.node_count(); ++i) {
      for (int comp = 0; comp < 3; ++comp) {
        EXPECT_NEAR(diagonal[i], K_diag[3 * i + comp], 1e-12 * K_diag.maxCoeff());
      }
    }
  }
}

// For a displacement linear in u (d_1 = u at every node, d_2 = d_3 = 0) both element families
// interpolate exactly, so q^T K_dd q is the membrane functional (4.42) itself:
// the integral of w1 * 1 + w0 u^2 over the area the elements cover. At latitude u that area is a
// full 2 pi wide in the middle bands, 2 pi s wide in the south strip (triangle eta <= xi,
// s = (u + pi/2)/a) and 2 pi (1 - s) wide in the north strip (xi + eta <= 1, s = (u - u_R)/a).
// Every integrand is a cubic in u, so one Simpson panel per region is exact.
TEST(MembraneStiffness, LinearFieldEnergyIsTheMembraneFunctional) {
  for (const Case& c : kCases) {
    const Tessellation t = tessellate({.kind = c.kind, .rings = c.rings, .segments = c.segments});
    const Real w0 = 2.5, w1 = 7.0;
    const MembraneStiffness k = build_membrane_stiffness(t, w0, w1);
    VecX q = VecX::Zero(3 * t.node_count());
    for (int i = 0; i < t.node_count(); ++i) q[3 * i] = t.uv[i].x();

    const Real a = kPi / (c.rings + 1);
    const Real u_first = -kPi / 2 + a, u_last = kPi / 2 - a;
    const auto simpson = [](auto f, Real x0, Real x1) {
      return (x1 - x0) / 6 * (f(x0) + 4 * f((x0 + x1) / 2) + f(x1));
    };
    const auto density = [&](Real u) { return w1 + w0 * u * u; };
    const Real middle = simpson([&](Real u) { return 2 * kPi * density(u); }, u_first, u_last);
    const Real south = simpson([&](Real u) { return 2 * kPi * (u + kPi / 2) / a * density(u); },
                               -kPi / 2, u_first);
    const Real north = simpson(
        [&](Real u) { return 2 * kPi * (1 - (u - u_last) / a) * density(u); }, u_last, kPi / 2);
    const Real functional = middle + south + north;
    EXPECT_NEAR(2 * membrane_energy(t, k, q), functional, 1e-12 * functional);
  }
}

}  // namespace
}  // namespace pbm
