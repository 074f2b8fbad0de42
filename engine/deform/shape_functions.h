// C0 element shape functions of sec. 4.3 with the book's node numbering (see tessellation.h for
// where each node sits), the map between material (u, v) and reference (xi, eta) coordinates,
// element quadrature in reference coordinates, and the lookup of the element holding a material
// point (to attach springs, data forces (4.3) or collisions at material points).
//
//   quad  (4.5)  N_i = (1 + xi xi_i)(1 + eta eta_i) / 4,   xi = 2 (u - u_c) / a   (4.6)
//   north (4.10)-(4.12) N = (1 - xi - eta, xi, eta),       xi = (u - u_1) / a      (4.13)
//   south (4.18)-(4.20) N = (1 - xi, xi - eta, eta),       xi = (u - u_1) / a      (4.21)
//   mid   (4.26)-(4.28) N = (1 - eta, xi + eta - 1, 1 - xi), xi = (u - u_3) / a    (4.29)
// The book prints the south element's N_2 = xi (4.19), which is not 0 at node 3 (xi, eta) = (1, 1)
// and contradicts its own derivatives (4.24) (dN_2/dv = -1/b) and stiffness (4.56); we use the
// consistent N_2 = xi - eta, which reproduces (4.24) and (4.56).
#pragma once

#include <array>

#include "core/types.h"
#include "deform/tessellation.h"

namespace pbm {

// Shape function values and their material derivatives at one point; entries past
// element_node_count(kind) are 0.
struct ShapeFunctions {
  Vec4 N = Vec4::Zero();      // N_i
  Vec4 dN_du = Vec4::Zero();  // dN_i/du (4.7), (4.15), (4.23), (4.31)
  Vec4 dN_dv = Vec4::Zero();  // dN_i/dv (4.8), (4.16), (4.24), (4.32)
};

// Shape functions of an element of the given kind and extents (a, b) at (xi, eta).
ShapeFunctions evaluate_shape_functions(ElementKind kind, Real a, Real b, Real xi, Real eta);
inline ShapeFunctions evaluate_shape_functions(const Element& e, Real xi, Real eta) {
  return evaluate_shape_functions(e.kind, e.a, e.b, xi, eta);
}

// Reference coordinates (xi, eta) of local node i (0-based: i = 0 is the book's node 1).
Vec2 reference_node(ElementKind kind, int i);

// Affine maps (4.6), (4.13)-(4.14), (4.21)-(4.22), (4.29)-(4.30) between (xi, eta) and (u, v).
Vec2 reference_to_material(const Element& e, const Vec2& xi_eta);
Vec2 material_to_reference(const Element& e, const Vec2& uv);

// Quadrature points of an element in its reference domain; weight includes the Jacobian of the
// material area, ab/4 for quads (4.9) and ab for triangles (4.17), (4.25), (4.33), so that
// sum_q weight_q f(xi_eta_q) approximates the integral of f over the element in du dv.
struct ElementRule {
  int n = 0;
  std::array<Vec2, 16> xi_eta;
  std::array<Real, 16> weight{};
};
// Exact for integrands that are polynomials of degree <= degree in each of xi and eta (quads:
// tensor Gauss-Legendre of Table A.1, degree <= 7) or of total degree <= degree (triangles:
// Radau rules of Table A.2 mapped onto the element's half-cell, degree <= 3).
ElementRule element_quadrature_rule(ElementKind kind, Real a, Real b, int degree);

// The element holding a material point and the point's reference coordinates in it.
struct MaterialPoint {
  int element = -1;
  Vec2 xi_eta = Vec2::Zero();
};
// u is clamped to [-pi/2, pi/2] and v wrapped to [-pi, pi). In the middle bands xi_eta is the
// inverse of the affine map. A pole strip cell [u_k, u_k + a] x [v_j, v_j + b] is covered on the
// surface by its one triangle (the cell's pole edge is a single point), so the whole cell is mapped
// onto that triangle by collapsing the pole edge: with s = (u - u0)/a and r = (v - v0)/b,
// (xi, eta) = (s, (1 - s) r) for north and (s, s r) for south pole elements.
// This agrees with the affine map on the ring edge, on the edge v = v_j and at the pole.
MaterialPoint locate_material_point(const Tessellation& t, const Vec2& uv);

}  // namespace pbm
