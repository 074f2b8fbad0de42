// Numerical integration rules of appendix A.2: Gauss-Legendre rules on [-1, 1] (Table A.1, (A.8),
// tensor product (A.9) for quadrilaterals) and Radau rules on the reference triangle (Table A.2,
// (A.10)). Rules are fixed-size constant tables; nothing allocates.
//
// Table A.1 prints rounded values (and the typo 0.577530 for 1/sqrt(3) = 0.577350); the tables
// here hold the same rules to full double precision. Table A.2 is complete as printed: the
// 1-point centroid rule (exact to degree 1), the 3-point edge-midpoint rule (degree 2) and the
// 7-point vertex/midpoint/centroid rule (degree 3), all on the triangle (0,0), (1,0), (0,1) with
// weights summing to its area 1/2.
#pragma once

#include <array>

#include "core/types.h"

namespace pbm {

struct GaussLegendreRule {
  int n = 0;                 // number of points, 1..4
  int degree = 0;            // polynomials of degree <= 2n - 1 are integrated exactly
  std::array<Real, 4> xi{};  // sampling positions in [-1, 1] (first n used)
  std::array<Real, 4> W{};   // weights, sum 2
};

struct TriangleRule {
  int n = 0;                 // number of points: 1, 3 or 7
  int degree = 0;            // polynomials of total degree <= degree are integrated exactly
  std::array<Real, 7> xi{};  // sampling positions on the triangle (0,0), (1,0), (0,1)
  std::array<Real, 7> eta{};
  std::array<Real, 7> W{};  // weights, sum 1/2
};

// n-point Gauss-Legendre rule of Table A.1, n in 1..4.
const GaussLegendreRule& gauss_legendre_rule(int n);

// n-point Radau triangle rule of Table A.2, n in {1, 3, 7}.
const TriangleRule& radau_triangle_rule(int n);

// Smallest Table A.2 rule exact for polynomials of total degree <= degree (degree <= 3).
const TriangleRule& radau_triangle_rule_for_degree(int degree);

}  // namespace pbm
