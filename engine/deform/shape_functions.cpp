#include "deform/shape_functions.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "deform/quadrature.h"

namespace pbm {

namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

// Reference node positions, fig. 4.3-4.6 (0-based rows).
constexpr Real kQuadNodes[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
constexpr Real kNorthNodes[3][2] = {{0, 0}, {1, 0}, {0, 1}};
constexpr Real kSouthNodes[3][2] = {{0, 0}, {1, 0}, {1, 1}};
constexpr Real kMidNodes[3][2] = {{1, 0}, {1, 1}, {0, 1}};

// Maps a point of the reference triangle (0,0), (1,0), (0,1) of Table A.2 onto the element's
// reference domain with a unit-determinant affine map, so the rule's weights carry over.
Vec2 triangle_domain_point(ElementKind kind, Real xi_r, Real eta_r) {
  switch (kind) {
    case ElementKind::south:  // domain 0 <= eta <= xi <= 1 (4.25)
      return {xi_r + eta_r, eta_r};
    case ElementKind::mid:  // domain 1 - xi <= eta <= 1 (4.33)
      return {1 - xi_r, 1 - eta_r};
    case ElementKind::north:  // domain xi + eta <= 1 (4.17)
    case ElementKind::quad:
      break;
  }
  return {xi_r, eta_r};
}

}  // namespace

ShapeFunctions evaluate_shape_functions(ElementKind kind, Real a, Real b, Real xi, Real eta) {
  ShapeFunctions s;
  switch (kind) {
    case ElementKind::quad:
      for (int i = 0; i < 4; ++i) {
        const Real xi_i = kQuadNodes[i][0], eta_i = kQuadNodes[i][1];
        s.N[i] = 0.25 * (1 + xi * xi_i) * (1 + eta * eta_i);  // (4.5)
        s.dN_du[i] = xi_i * (1 + eta * eta_i) / (2 * a);      // (4.7)
        s.dN_dv[i] = (1 + xi * xi_i) * eta_i / (2 * b);       // (4.8)
      }
      break;
    case ElementKind::north:
      s.N << 1 - xi - eta, xi, eta, 0;  // (4.10)-(4.12)
      s.dN_du << -1 / a, 1 / a, 0, 0;   // (4.15)
      s.dN_dv << -1 / b, 0, 1 / b, 0;   // (4.16)
      break;
    case ElementKind::south:
      s.N << 1 - xi, xi - eta, eta, 0;  // (4.18), N_2 corrected (see header), (4.20)
      s.dN_du << -1 / a, 1 / a, 0, 0;   // (4.23)
      s.dN_dv << 0, -1 / b, 1 / b, 0;   // (4.24)
      break;
    case ElementKind::mid:
      s.N << 1 - eta, xi + eta - 1, 1 - xi, 0;  // (4.26)-(4.28)
      s.dN_du << 0, 1 / a, -1 / a, 0;           // (4.31)
      s.dN_dv << -1 / b, 1 / b, 0, 0;           // (4.32)
      break;
  }
  return s;
}

Vec2 reference_node(ElementKind kind, int i) {
  assert(i >= 0 && i < element_node_count(kind));
  switch (kind) {
    case ElementKind::quad:
      return {kQuadNodes[i][0], kQuadNodes[i][1]};
    case ElementKind::north:
      return {kNorthNodes[i][0], kNorthNodes[i][1]};
    case ElementKind::south:
      return {kSouthNodes[i][0], kSouthNodes[i][1]};
    case ElementKind::mid:
      return {kMidNodes[i][0], kMidNodes[i][1]};
  }
  return Vec2::Zero();
}

Vec2 reference_to_material(const Element& e, const Vec2& xi_eta) {
  // Quads measure from the centre in half-extents (4.6); triangles from (u0, v0) in full extents.
  const Real scale = e.kind == ElementKind::quad ? 0.5 : 1.0;
  return {e.u0 + scale * e.a * xi_eta.x(), e.v0 + scale * e.b * xi_eta.y()};
}

Vec2 material_to_reference(const Element& e, const Vec2& uv) {
  const Real scale = e.kind == ElementKind::quad ? 2.0 : 1.0;
  return {scale * (uv.x() - e.u0) / e.a, scale * (uv.y() - e.v0) / e.b};
}

ElementRule element_quadrature_rule(ElementKind kind, Real a, Real b, int degree) {
  ElementRule rule;
  if (kind == ElementKind::quad) {
    // (A.9) with the Jacobian ab/4 of (4.9); an n-point rule is exact to degree 2n - 1.
    const GaussLegendreRule& g = gauss_legendre_rule(std::max(1, (degree + 2) / 2));
    for (int i = 0; i < g.n; ++i) {
      for (int j = 0; j < g.n; ++j) {
        rule.xi_eta[static_cast<size_t>(rule.n)] = Vec2(g.xi[i], g.xi[j]);
        rule.weight[static_cast<size_t>(rule.n)] = g.W[i] * g.W[j] * a * b / 4;
        ++rule.n;
      }
    }
    return rule;
  }
  // (A.10) with the Jacobian ab of (4.17), (4.25), (4.33).
  const TriangleRule& r = radau_triangle_rule_for_degree(std::max(0, degree));
  for (int q = 0; q < r.n; ++q) {
    rule.xi_eta[static_cast<size_t>(q)] = triangle_domain_point(kind, r.xi[q], r.eta[q]);
    rule.weight[static_cast<size_t>(q)] = r.W[q] * a * b;
  }
  rule.n = r.n;
  return rule;
}

MaterialPoint locate_material_point(const Tessellation& t, const Vec2& uv) {
  const int R = t.rings, S = t.segments;
  assert(R >= 2 && S >= 3 && !t.elements.empty());
  const Real a = kPi / (R + 1), b = 2 * kPi / S;
  const Real u = std::clamp(uv.x(), -kPi / 2, kPi / 2);
  const Real v = uv.y() - 2 * kPi * std::floor((uv.y() + kPi) / (2 * kPi));  // in [-pi, pi)
  const int band = std::clamp(static_cast<int>(std::floor((u + kPi / 2) / a)), 0, R);
  const int j = std::clamp(static_cast<int>(std::floor((v + kPi) / b)), 0, S - 1);
  const int per_cell = t.kind == TessellationKind::quads ? 1 : 2;

  MaterialPoint p;
  if (band == 0 || band == R) {
    p.element = band == 0 ? j : S + (R - 1) * S * per_cell + j;
    const Element& e = t.elements[static_cast<size_t>(p.element)];
    const Real s = std::clamp((u - e.u0) / e.a, 0.0, 1.0);
    const Real r = std::clamp((v - e.v0) / e.b, 0.0, 1.0);
    // Collapse the cell's pole edge onto the pole node (see header).
    p.xi_eta = e.kind == ElementKind::south ? Vec2(s, s * r) : Vec2(s, (1 - s) * r);
    return p;
  }
  const int cell = (band - 1) * S + j;
  p.element = S + cell * per_cell;
  if (per_cell == 2) {
    const Element& lower_left = t.elements[static_cast<size_t>(p.element)];
    const Vec2 x = material_to_reference(lower_left, Vec2(u, v));
    if (x.x() + x.y() > 1) ++p.element;  // upper-right half: the mid element, same origin
  }
  p.xi_eta = material_to_reference(t.elements[static_cast<size_t>(p.element)], Vec2(u, v));
  return p;
}

}  // namespace pbm
