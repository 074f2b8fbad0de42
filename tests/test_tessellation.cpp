// Tessellation of (u, v) (sec. 4.2), C0 shape functions (sec. 4.3) and the quadrature rules of
// appendix A.2.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "core/error.h"
#include "deform/quadrature.h"
#include "deform/shape_functions.h"
#include "deform/tessellation.h"

namespace pbm {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;
constexpr ElementKind kAllKinds[] = {ElementKind::quad, ElementKind::north, ElementKind::south,
                                     ElementKind::mid};

// ---------------------------------------------------------------- quadrature (appendix A.2)

// Integral of xi^p over [-1, 1].
Real monomial_integral_1d(int p) {
  return p % 2 == 1 ? 0.0 : 2.0 / (p + 1);
}

TEST(Quadrature, GaussLegendreIsExactUpToDegree2nMinus1) {
  for (int n = 1; n <= 4; ++n) {
    const GaussLegendreRule& g = gauss_legendre_rule(n);
    ASSERT_EQ(g.n, n);
    ASSERT_EQ(g.degree, 2 * n - 1);
    for (int p = 0; p <= 2 * n; ++p) {
      Real I = 0;
      for (int i = 0; i < n; ++i) I += g.W[i] * std::pow(g.xi[i], p);
      if (p <= 2 * n - 1) {
        EXPECT_NEAR(I, monomial_integral_1d(p), 1e-15) << "n=" << n << " p=" << p;
      } else {
        // Degree 2n is not integrated exactly: the rule really has the degree it claims.
        EXPECT_GT(std::abs(I - monomial_integral_1d(p)), 1e-3) << "n=" << n << " p=" << p;
      }
    }
  }
  // Table A.1 to its printed 6 digits (its 0.577530 is a typo for 1/sqrt(3) = 0.577350).
  EXPECT_NEAR(gauss_legendre_rule(2).xi[1], 0.577350, 5e-7);
  EXPECT_NEAR(gauss_legendre_rule(3).xi[2], 0.774597, 5e-7);
  EXPECT_NEAR(gauss_legendre_rule(4).xi[3], 0.861136, 5e-7);
  EXPECT_NEAR(gauss_legendre_rule(4).W[3], 0.347855, 5e-7);
  EXPECT_NEAR(gauss_legendre_rule(4).xi[2], 0.339981, 5e-7);
  EXPECT_NEAR(gauss_legendre_rule(4).W[2], 0.652145, 5e-7);
}

// Integral of xi^p eta^q over the triangle (0,0), (1,0), (0,1): p! q! / (p + q + 2)!.
Real monomial_integral_triangle(int p, int q) {
  return std::tgamma(p + 1) * std::tgamma(q + 1) / std::tgamma(p + q + 3);
}

TEST(Quadrature, RadauTriangleRulesAreExactUpToTheirDegree) {
  for (int n : {1, 3, 7}) {
    const TriangleRule& r = radau_triangle_rule(n);
    ASSERT_EQ(r.n, n);
    bool some_higher_degree_fails = false;
    for (int p = 0; p <= r.degree + 1; ++p) {
      for (int q = 0; p + q <= r.degree + 1; ++q) {
        Real I = 0;
        for (int i = 0; i < n; ++i) I += r.W[i] * std::pow(r.xi[i], p) * std::pow(r.eta[i], q);
        const Real exact = monomial_integral_triangle(p, q);
        if (p + q <= r.degree) {
          EXPECT_NEAR(I, exact, 1e-15) << "n=" << n << " p=" << p << " q=" << q;
        } else if (std::abs(I - exact) > 1e-4) {
          some_higher_degree_fails = true;
        }
      }
    }
    EXPECT_TRUE(some_higher_degree_fails) << "rule " << n << " is exact beyond its degree";
  }
  EXPECT_EQ(radau_triangle_rule(1).degree, 1);
  EXPECT_EQ(radau_triangle_rule(3).degree, 2);
  EXPECT_EQ(radau_triangle_rule(7).degree, 3);
}

// Element rules integrate polynomials in (u, v) exactly over the element's material domain.
TEST(Quadrature, ElementRulesIntegrateOverTheElementDomain) {
  const Real a = 0.3, b = 0.7;
  // Integral of xi^p eta^q over each reference domain, and the du dv Jacobian.
  // quad: [-1,1]^2, du dv = ab/4 dxi deta. north: xi + eta <= 1. south: eta <= xi (swap roles:
  // integral_0^1 xi^p xi^(q+1)/(q+1) dxi = 1/((q+1)(p+q+2))). mid: substitute xi' = 1 - xi,
  // eta' = 1 - eta, which maps it onto the north triangle.
  for (int p = 0; p <= 2; ++p) {
    for (int q = 0; q + p <= 2; ++q) {
      const ElementRule quad = element_quadrature_rule(ElementKind::quad, a, b, 2);
      Real I = 0;
      for (int i = 0; i < quad.n; ++i) {
        I += quad.weight[i] * std::pow(quad.xi_eta[i].x(), p) * std::pow(quad.xi_eta[i].y(), q);
      }
      EXPECT_NEAR(I, a * b / 4 * monomial_integral_1d(p) * monomial_integral_1d(q), 1e-15);

      const ElementRule north = element_quadrature_rule(ElementKind::north, a, b, 2);
      I = 0;
      for (int i = 0; i < north.n; ++i) {
        I += north.weight[i] * std::pow(north.xi_eta[i].x(), p) * std::pow(north.xi_eta[i].y(), q);
      }
      EXPECT_NEAR(I, a * b * monomial_integral_triangle(p, q), 1e-15);

      const ElementRule south = element_quadrature_rule(ElementKind::south, a, b, 2);
      I = 0;
      for (int i = 0; i < south.n; ++i) {
        I += south.weight[i] * std::pow(south.xi_eta[i].x(), p) * std::pow(south.xi_eta[i].y(), q);
      }
      EXPECT_NEAR(I, a * b / ((q + 1.0) * (p + q + 2.0)), 1e-15);

      // mid, f = (1 - xi')^p ... is awkward; test f = xi'^p eta'^q = (1 - xi)^p (1 - eta)^q.
      const ElementRule mid = element_quadrature_rule(ElementKind::mid, a, b, 2);
      I = 0;
      for (int i = 0; i < mid.n; ++i) {
        I +=
            mid.weight[i] * std::pow(1 - mid.xi_eta[i].x(), p) * std::pow(1 - mid.xi_eta[i].y(), q);
      }
      EXPECT_NEAR(I, a * b * monomial_integral_triangle(p, q), 1e-15);
    }
  }
  // Points lie in the element domains.
  for (ElementKind kind : {ElementKind::north, ElementKind::south, ElementKind::mid}) {
    const ElementRule r = element_quadrature_rule(kind, a, b, 3);
    for (int i = 0; i < r.n; ++i) {
      const Real xi = r.xi_eta[i].x(), eta = r.xi_eta[i].y();
      const ShapeFunctions s = evaluate_shape_functions(kind, a, b, xi, eta);
      for (int k = 0; k < 3; ++k) EXPECT_GE(s.N[k], -1e-15);  // barycentric >= 0 inside
    }
  }
}

// ---------------------------------------------------------------- shape functions (sec. 4.3)

TEST(ShapeFunctions, KroneckerDeltaAtNodesAndPartitionOfUnity) {
  for (ElementKind kind : kAllKinds) {
    const int n = element_node_count(kind);
    for (int i = 0; i < n; ++i) {
      const Vec2 x = reference_node(kind, i);
      const ShapeFunctions s = evaluate_shape_functions(kind, 0.4, 0.9, x.x(), x.y());
      for (int j = 0; j < n; ++j) EXPECT_DOUBLE_EQ(s.N[j], i == j ? 1.0 : 0.0);
    }
    for (Real xi : {-0.7, 0.1, 0.3, 0.8}) {
      for (Real eta : {-0.4, 0.2, 0.55}) {
        const ShapeFunctions s = evaluate_shape_functions(kind, 0.4, 0.9, xi, eta);
        EXPECT_NEAR(s.N.sum(), 1.0, 1e-15);
        EXPECT_NEAR(s.dN_du.sum(), 0.0, 1e-14);
        EXPECT_NEAR(s.dN_dv.sum(), 0.0, 1e-14);
        if (n == 3) {
          EXPECT_EQ(s.N[3], 0.0);
        }
      }
    }
  }
}

// The printed south N_2 = xi (4.19) is 1 at node 3 (1, 1); the consistent xi - eta is 0 there and
// has the printed derivatives (4.24).
TEST(ShapeFunctions, SouthPoleN2IsTheConsistentXiMinusEta) {
  const ShapeFunctions s = evaluate_shape_functions(ElementKind::south, 0.5, 0.25, 1.0, 1.0);
  EXPECT_EQ(s.N[1], 0.0);
  EXPECT_EQ(s.dN_dv[1], -1 / 0.25);  // (4.24)
  const ShapeFunctions s2 = evaluate_shape_functions(ElementKind::south, 0.5, 0.25, 0.6, 0.2);
  EXPECT_DOUBLE_EQ(s2.N[1], 0.6 - 0.2);
}

TEST(ShapeFunctions, MaterialDerivativesMatchFiniteDifferences) {
  const Real h = 1e-6;
  for (ElementKind kind : kAllKinds) {
    const Element e{kind, {0, 1, 2, kind == ElementKind::quad ? 3 : -1}, 0.37, 0.61, 0.2, -1.1};
    for (Real xi : {0.15, 0.3, 0.7}) {
      for (Real eta : {0.1, 0.25, 0.6}) {
        const Vec2 uv = reference_to_material(e, Vec2(xi, eta));
        auto N_at = [&e](const Vec2& p) {
          const Vec2 x = material_to_reference(e, p);
          return evaluate_shape_functions(e, x.x(), x.y()).N;
        };
        const Vec4 dN_du = (N_at(uv + Vec2(h, 0)) - N_at(uv - Vec2(h, 0))) / (2 * h);
        const Vec4 dN_dv = (N_at(uv + Vec2(0, h)) - N_at(uv - Vec2(0, h))) / (2 * h);
        const ShapeFunctions s = evaluate_shape_functions(e, xi, eta);
        EXPECT_LT((s.dN_du - dN_du).norm(), 1e-8) << static_cast<int>(kind);
        EXPECT_LT((s.dN_dv - dN_dv).norm(), 1e-8) << static_cast<int>(kind);
      }
    }
  }
}

TEST(ShapeFunctions, ReferenceMapsAreInverse) {
  for (ElementKind kind : kAllKinds) {
    const Element e{kind, {0, 1, 2, -1}, 0.37, 0.61, 0.2, -1.1};
    const Vec2 x(0.3, -0.45);
    EXPECT_LT((material_to_reference(e, reference_to_material(e, x)) - x).norm(), 1e-15);
  }
  // (4.6): the quad's centre is xi = eta = 0 and its corners are a/2, b/2 away.
  const Element q{ElementKind::quad, {0, 1, 2, 3}, 0.4, 0.8, 1.0, 2.0};
  EXPECT_LT((reference_to_material(q, Vec2(1, -1)) - Vec2(1.2, 1.6)).norm(), 1e-15);
}

// ---------------------------------------------------------------- tessellation (sec. 4.2)

Vec3 on_unit_sphere(const Vec2& uv) {
  return {std::cos(uv.x()) * std::cos(uv.y()), std::cos(uv.x()) * std::sin(uv.y()),
          std::sin(uv.x())};
}

TEST(Tessellation, NodeAndElementCounts) {
  const int expected_nodes[] = {66, 258, 1026, 4098, 16386};
  int i = 0;
  for (int n : {8, 16, 32, 64, 128}) {
    for (TessellationKind kind : {TessellationKind::quads, TessellationKind::triangles}) {
      const Tessellation t = tessellate({.kind = kind, .rings = n, .segments = n});
      EXPECT_EQ(t.node_count(), expected_nodes[i]);
      EXPECT_EQ(t.south_pole, 0);
      EXPECT_EQ(t.north_pole, t.node_count() - 1);
      // Fig. 4.1: (rings - 1) bands of quads + 2 pole strips; fig. 4.2: every quad split in two.
      const size_t elements =
          kind == TessellationKind::quads ? size_t(n + 1) * n : size_t(2) * n * n;
      EXPECT_EQ(t.elements.size(), elements);
      EXPECT_EQ(t.triangles.size(), size_t(2) * n * n);
      // The element edges close a sphere: Euler's V - E + F = 2, each edge once.
      EXPECT_EQ(static_cast<long>(t.node_count()) - static_cast<long>(t.edges.size()) +
                    static_cast<long>(t.elements.size()),
                2);
      for (const auto& e : t.edges) EXPECT_LT(e[0], e[1]);
    }
    ++i;
  }
  const Tessellation t = tessellate({.kind = TessellationKind::quads, .rings = 3, .segments = 5});
  EXPECT_EQ(t.node_count(), 17);
  EXPECT_EQ(t.elements.size(), 20u);
  EXPECT_THROW(tessellate({.rings = 1, .segments = 8}), Error);
  EXPECT_THROW(tessellate({.rings = 4, .segments = 2}), Error);
}

TEST(Tessellation, NodeCoordinatesFollowTheConvention) {
  const Tessellation t = tessellate({.rings = 5, .segments = 7});
  EXPECT_DOUBLE_EQ(t.uv[0].x(), -kPi / 2);
  EXPECT_DOUBLE_EQ(t.uv[36].x(), kPi / 2);
  // Node 1 + k S + j: ring k at u = -pi/2 + (k+1) pi/(R+1), v = -pi + j 2pi/S.
  EXPECT_NEAR(t.uv[1 + 2 * 7 + 3].x(), -kPi / 2 + 3 * kPi / 6, 1e-15);
  EXPECT_NEAR(t.uv[1 + 2 * 7 + 3].y(), -kPi + 3 * 2 * kPi / 7, 1e-15);
}

// Each element's nodes sit where its shape functions put them: reference_node mapped through
// (4.6)/(4.13)/(4.21)/(4.29), with the pole's v arbitrary and v taken modulo 2 pi at the seam.
TEST(Tessellation, ElementNodesMatchTheirReferencePositions) {
  for (TessellationKind kind : {TessellationKind::quads, TessellationKind::triangles}) {
    const Tessellation t = tessellate({.kind = kind, .rings = 4, .segments = 6});
    for (const Element& e : t.elements) {
      EXPECT_NEAR(e.a, kPi / 5, 1e-15);
      EXPECT_NEAR(e.b, 2 * kPi / 6, 1e-15);
      EXPECT_EQ(e.nodes[3] >= 0, e.kind == ElementKind::quad);
      for (int i = 0; i < element_node_count(e.kind); ++i) {
        const Vec2 uv = reference_to_material(e, reference_node(e.kind, i));
        const Vec2& node = t.uv[static_cast<size_t>(e.nodes[i])];
        EXPECT_NEAR(uv.x(), node.x(), 1e-14);
        if (e.nodes[i] == t.south_pole || e.nodes[i] == t.north_pole) continue;
        EXPECT_NEAR(std::remainder(uv.y() - node.y(), 2 * kPi), 0.0, 1e-14);
      }
    }
    // Kinds by position: fig. 4.1 quads in the middle, fig. 4.2 north + mid pairs.
    EXPECT_EQ(t.elements.front().kind, ElementKind::south);
    EXPECT_EQ(t.elements.back().kind, ElementKind::north);
    EXPECT_EQ(t.elements[6].kind,
              kind == TessellationKind::quads ? ElementKind::quad : ElementKind::north);
    if (kind == TessellationKind::triangles) {
      EXPECT_EQ(t.elements[7].kind, ElementKind::mid);
    }
  }
}

// The elements tile the (u, v) rectangle [-pi/2, pi/2] x [-pi, pi) except the degenerate half of
// each pole cell (two of its corners are the pole): area 2 pi^2 - 2 * (a * 2 pi) / 2 with
// a = pi / (rings + 1). Element areas: ab for quads (4.9), ab/2 for triangles (4.17).
TEST(Tessellation, MaterialAreaCoversTheRectangleExceptDegeneratePoleHalves) {
  for (TessellationKind kind : {TessellationKind::quads, TessellationKind::triangles}) {
    for (int n : {4, 9, 16}) {
      const Tessellation t = tessellate({.kind = kind, .rings = n, .segments = n + 3});
      Real area = 0;
      for (const Element& e : t.elements) {
        const ElementRule r = element_quadrature_rule(e.kind, e.a, e.b, 0);
        for (int q = 0; q < r.n; ++q) area += r.weight[q];
      }
      const Real a = kPi / (n + 1);
      EXPECT_NEAR(area + 2 * kPi * a, 2 * kPi * kPi, 1e-12);
    }
  }
}

TEST(Tessellation, TrianglesAreOutwardAndWatertightOnTheSphere) {
  for (TessellationKind kind : {TessellationKind::quads, TessellationKind::triangles}) {
    for (int n : {3, 8, 32, 128}) {
      const Tessellation t = tessellate({.kind = kind, .rings = n, .segments = n + 1});
      std::map<std::pair<int, int>, int> directed;  // directed edge -> count
      std::set<std::pair<int, int>> undirected;
      for (const auto& tri : t.triangles) {
        const Vec3 p0 = on_unit_sphere(t.uv[tri[0]]);
        const Vec3 p1 = on_unit_sphere(t.uv[tri[1]]);
        const Vec3 p2 = on_unit_sphere(t.uv[tri[2]]);
        const Vec3 normal = (p1 - p0).cross(p2 - p0);
        EXPECT_GT(normal.norm(), 1e-6);                  // not degenerate
        EXPECT_GT(normal.dot((p0 + p1 + p2) / 3), 0.0);  // faces outward
        for (int k = 0; k < 3; ++k) {
          const int i = tri[k], j = tri[(k + 1) % 3];
          ASSERT_NE(i, j);
          ++directed[{i, j}];
          undirected.insert({std::min(i, j), std::max(i, j)});
        }
      }
      // Watertight and consistently oriented: each edge appears once in each direction.
      for (const auto& [edge, count] : directed) {
        EXPECT_EQ(count, 1);
        EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
      }
      const int V = t.node_count(), E = static_cast<int>(undirected.size());
      const int F = static_cast<int>(t.triangles.size());
      EXPECT_EQ(V - E + F, 2);  // Euler characteristic of the sphere
      // Every node is used.
      std::set<int> used;
      for (const auto& tri : t.triangles) used.insert(tri.begin(), tri.end());
      EXPECT_EQ(static_cast<int>(used.size()), V);
    }
  }
}

// ---------------------------------------------------------------- locating material points

TEST(LocateMaterialPoint, MidBandPointsMapBackExactly) {
  for (TessellationKind kind : {TessellationKind::quads, TessellationKind::triangles}) {
    const Tessellation t = tessellate({.kind = kind, .rings = 6, .segments = 9});
    const Real a = kPi / 7;
    for (Real u : {-kPi / 2 + 1.3 * a, -0.1, 0.33, kPi / 2 - 1.2 * a}) {
      for (Real v : {-3.1, -1.0, 0.0, 2.5, 3.14}) {
        const MaterialPoint p = locate_material_point(t, Vec2(u, v));
        ASSERT_GE(p.element, 0);
        const Element& e = t.elements[p.element];
        ASSERT_NE(e.kind, ElementKind::south);
        const ShapeFunctions s = evaluate_shape_functions(e, p.xi_eta.x(), p.xi_eta.y());
        for (int i = 0; i < element_node_count(e.kind); ++i) EXPECT_GE(s.N[i], -1e-12);
        // Interpolating the node coordinates with N reproduces the point (affine elements).
        Vec2 uv = Vec2::Zero();
        for (int i = 0; i < element_node_count(e.kind); ++i) {
          uv += s.N[i] * reference_to_material(e, reference_node(e.kind, i));
        }
        EXPECT_NEAR(uv.x(), u, 1e-12);
        EXPECT_NEAR(std::remainder(uv.y() - v, 2 * kPi), 0.0, 1e-12);
      }
    }
    // Wrapping: v and v + 2 pi are the same point.
    const MaterialPoint p1 = locate_material_point(t, Vec2(0.2, 1.0));
    const MaterialPoint p2 = locate_material_point(t, Vec2(0.2, 1.0 + 2 * kPi));
    EXPECT_EQ(p1.element, p2.element);
    EXPECT_LT((p1.xi_eta - p2.xi_eta).norm(), 1e-12);
  }
}

TEST(LocateMaterialPoint, PoleStripsCollapseOntoThePoleTriangle) {
  const Tessellation t =
      tessellate({.kind = TessellationKind::triangles, .rings = 6, .segments = 9});
  const Real a = kPi / 7, b = 2 * kPi / 9;
  // The pole itself, at any v: all weight on the pole node.
  for (Real v : {-2.0, 0.4, 3.0}) {
    const MaterialPoint s = locate_material_point(t, Vec2(-kPi / 2, v));
    const Element& es = t.elements[s.element];
    EXPECT_EQ(es.kind, ElementKind::south);
    const ShapeFunctions Ns = evaluate_shape_functions(es, s.xi_eta.x(), s.xi_eta.y());
    EXPECT_NEAR(Ns.N[0], 1.0, 1e-12);  // node 1 = south pole
    const MaterialPoint n = locate_material_point(t, Vec2(kPi / 2, v));
    const Element& en = t.elements[n.element];
    EXPECT_EQ(en.kind, ElementKind::north);
    const ShapeFunctions Nn = evaluate_shape_functions(en, n.xi_eta.x(), n.xi_eta.y());
    EXPECT_NEAR(Nn.N[1], 1.0, 1e-12);  // node 2 = north pole
    EXPECT_EQ(en.nodes[1], t.north_pole);
  }
  // Halfway from ring 0 to the south pole, a quarter into segment 2: weights
  // pole 1/2, ring nodes (1/2)(3/4) and (1/2)(1/4).
  const MaterialPoint p = locate_material_point(t, Vec2(-kPi / 2 + a / 2, -kPi + 2.25 * b));
  EXPECT_EQ(p.element, 2);
  const ShapeFunctions N = evaluate_shape_functions(t.elements[2], p.xi_eta.x(), p.xi_eta.y());
  EXPECT_NEAR(N.N[0], 0.5, 1e-12);
  EXPECT_NEAR(N.N[1], 0.375, 1e-12);
  EXPECT_NEAR(N.N[2], 0.125, 1e-12);
}

}  // namespace
}  // namespace pbm
