#include "deform/tessellation.h"

#include <algorithm>

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace pbm {

namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;

// Node index of ring k (0 = southmost), segment j; j == segments wraps across the seam.
int ring_node(int k, int j, int segments) {
  return 1 + k * segments + (j % segments);
}

// Surface triangle of a triangular element. Every kind lists its reference nodes clockwise in
// the (v, u) plane, and d x/dv x d x/du points outward on the sphere, so (1, 3, 2) faces out.
std::array<int, 3> outward_triangle(int n1, int n2, int n3) {
  return {n1, n3, n2};
}

}  // namespace

Tessellation tessellate(const TessellationDef& def) {
  if (def.rings < 2) throw Error("", "tessellation.rings", "must be >= 2");
  if (def.segments < 3) throw Error("", "tessellation.segments", "must be >= 3");

  Tessellation t;
  t.kind = def.kind;
  t.rings = def.rings;
  t.segments = def.segments;
  const int R = def.rings, S = def.segments;
  const Real a = kPi / (R + 1);  // u extent of every cell
  const Real b = 2 * kPi / S;    // v extent of every cell

  t.uv.reserve(2 + R * S);
  t.south_pole = 0;
  t.uv.emplace_back(-kPi / 2, 0);
  for (int k = 0; k < R; ++k) {
    for (int j = 0; j < S; ++j) t.uv.emplace_back(-kPi / 2 + (k + 1) * a, -kPi + j * b);
  }
  t.north_pole = static_cast<int>(t.uv.size());
  t.uv.emplace_back(kPi / 2, 0);

  const bool quads = def.kind == TessellationKind::quads;
  t.elements.reserve(quads ? (R + 1) * S : 2 * R * S);
  t.triangles.reserve(2 * R * S);
  auto add_triangle = [&t](ElementKind kind, int n1, int n2, int n3, Real u0, Real v0, Real a_,
                           Real b_) {
    t.elements.push_back({kind, {n1, n2, n3, -1}, a_, b_, u0, v0});
    t.triangles.push_back(outward_triangle(n1, n2, n3));
  };

  // South pole strip, fig. 4.5: node 1 is the pole (at v = v_j), nodes 2 and 3 on ring 0.
  for (int j = 0; j < S; ++j) {
    add_triangle(ElementKind::south, t.south_pole, ring_node(0, j, S), ring_node(0, j + 1, S),
                 -kPi / 2, -kPi + j * b, a, b);
  }
  // Middle bands between ring k and ring k + 1.
  for (int k = 0; k + 1 < R; ++k) {
    const Real u_k = -kPi / 2 + (k + 1) * a;
    for (int j = 0; j < S; ++j) {
      const Real v_j = -kPi + j * b;
      const int c00 = ring_node(k, j, S);          // (u_k,     v_j)
      const int c10 = ring_node(k + 1, j, S);      // (u_k + a, v_j)
      const int c11 = ring_node(k + 1, j + 1, S);  // (u_k + a, v_j + b)
      const int c01 = ring_node(k, j + 1, S);      // (u_k,     v_j + b)
      if (quads) {
        // Fig. 4.3 numbering (xi, eta) = (-1,-1), (1,-1), (1,1), (-1,1); origin at the centre
        // (4.6).
        t.elements.push_back(
            {ElementKind::quad, {c00, c10, c11, c01}, a, b, u_k + a / 2, v_j + b / 2});
        t.triangles.push_back(outward_triangle(c00, c10, c01));
        t.triangles.push_back(outward_triangle(c10, c11, c01));
      } else {
        add_triangle(ElementKind::north, c00, c10, c01, u_k, v_j, a, b);  // (4.10)-(4.12)
        add_triangle(ElementKind::mid, c10, c11, c01, u_k, v_j, a, b);    // (4.26)-(4.28)
      }
    }
  }
  // North pole strip, fig. 4.4: node 2 is the pole (at v = v_j), nodes 1 and 3 on the last ring.
  const Real u_last = -kPi / 2 + R * a;
  for (int j = 0; j < S; ++j) {
    add_triangle(ElementKind::north, ring_node(R - 1, j, S), t.north_pole,
                 ring_node(R - 1, j + 1, S), u_last, -kPi + j * b, a, b);
  }
  for (const Element& e : t.elements) {
    const int count = element_node_count(e.kind);
    for (int k = 0; k < count; ++k) {
      const int from = e.nodes[k], to = e.nodes[(k + 1) % count];
      t.edges.push_back({std::min(from, to), std::max(from, to)});
    }
  }
  std::sort(t.edges.begin(), t.edges.end());
  t.edges.erase(std::unique(t.edges.begin(), t.edges.end()), t.edges.end());
  return t;
}

int nearest_node(const Tessellation& t, const Vec2& uv) {
  int best = 0;
  Real best_d = 1e300;
  for (int i = 0; i < t.node_count(); ++i) {
    Real du = t.uv[i].x() - uv.x();
    Real dv = std::remainder(t.uv[i].y() - uv.y(), 2 * std::numbers::pi);
    // At the poles v is arbitrary (fig. 4.1): only u counts there.
    if (i == t.south_pole || i == t.north_pole) dv = 0;
    const Real d = du * du + dv * dv * std::cos(uv.x()) * std::cos(uv.x());
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return best;
}

}  // namespace pbm
