#include "deform/quadrature.h"

#include <cassert>

namespace pbm {

namespace {

// Table A.1 at full precision: roots of the Legendre polynomials P_n and their weights.
constexpr std::array<GaussLegendreRule, 4> kGaussLegendre{{
    {1, 1, {0.0}, {2.0}},
    {2, 3, {-0.57735026918962576451, 0.57735026918962576451}, {1.0, 1.0}},
    {3, 5, {-0.77459666924148337704, 0.0, 0.77459666924148337704}, {5.0 / 9, 8.0 / 9, 5.0 / 9}},
    {4,
     7,
     {-0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480,
      0.86113631159405257522},
     {0.34785484513745385737, 0.65214515486254614263, 0.65214515486254614263,
      0.34785484513745385737}},
}};

// Table A.2, in its printed order.
constexpr TriangleRule kRadau1{1, 1, {1.0 / 3}, {1.0 / 3}, {1.0 / 2}};
constexpr TriangleRule kRadau3{
    3, 2, {1.0 / 2, 1.0 / 2, 0.0}, {0.0, 1.0 / 2, 1.0 / 2}, {1.0 / 6, 1.0 / 6, 1.0 / 6}};
constexpr TriangleRule kRadau7{
    7,
    3,
    {0.0, 1.0 / 2, 1.0, 1.0 / 2, 0.0, 0.0, 1.0 / 3},
    {0.0, 0.0, 0.0, 1.0 / 2, 1.0, 1.0 / 2, 1.0 / 3},
    {1.0 / 40, 1.0 / 15, 1.0 / 40, 1.0 / 15, 1.0 / 40, 1.0 / 15, 9.0 / 40}};

}  // namespace

const GaussLegendreRule& gauss_legendre_rule(int n) {
  assert(n >= 1 && n <= 4);
  return kGaussLegendre[static_cast<size_t>(n - 1)];
}

const TriangleRule& radau_triangle_rule(int n) {
  assert(n == 1 || n == 3 || n == 7);
  if (n == 1) return kRadau1;
  if (n == 3) return kRadau3;
  return kRadau7;
}

const TriangleRule& radau_triangle_rule_for_degree(int degree) {
  assert(degree >= 0 && degree <= 3);
  if (degree <= 1) return kRadau1;
  if (degree == 2) return kRadau3;
  return kRadau7;
}

}  // namespace pbm
