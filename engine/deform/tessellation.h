// Tessellation of the material coordinates (u, v) of a closed superquadric shell into C0 finite
// elements (sec. 4.2, figs. 4.1 and 4.2).
//
// Material coordinates: u in [-pi/2, pi/2] (latitude), v in [-pi, pi) (longitude), as in (2.7).
// Nodes: 2 + rings * segments.
//   node 0                      south pole, u = -pi/2 (its v is arbitrary, stored as 0)
//   node 1 + k * segments + j   ring k (0 = southmost) at u = -pi/2 + (k + 1) pi / (rings + 1),
//                               segment j at v = -pi + j 2 pi / segments
//   node 1 + rings * segments   north pole, u = +pi/2 (v stored as 0)
// Nodes are shared at the poles and across the seam v = pi == -pi: the cell after the last
// segment wraps to j = 0 but keeps its extent b = 2 pi / segments and its v0 near +pi.
//
// Every element covers part of one grid cell [u_k, u_k + a] x [v_j, v_j + b] (a = pi/(rings+1),
// b = 2 pi/segments); (xi, eta) runs along (u, v):
//   quad  (4.5)-(4.9)   the whole cell; xi, eta in [-1, 1]; nodes 1..4 at (xi, eta) =
//                       (-1,-1), (1,-1), (1,1), (-1,1) (this numbering reproduces (4.55));
//                       (u0, v0) = cell centre (u_c, v_c) of (4.6).
//   north (4.10)-(4.17) lower-left half xi + eta <= 1; nodes 1..3 at (0,0), (1,0), (0,1);
//                       (u0, v0) = node 1 = (u_1, v_1) of (4.13)-(4.14).
//   south (4.18)-(4.25) lower-right half eta <= xi; nodes 1..3 at (0,0), (1,0), (1,1);
//                       (u0, v0) = node 1 = (u_1, v_1) of (4.21)-(4.22).
//   mid   (4.26)-(4.33) upper-right half xi + eta >= 1; nodes 1..3 at (1,0), (1,1), (0,1);
//                       (u0, v0) = (u_3, v_1) of (4.29)-(4.30), the cell corner where xi = eta = 0.
// So for every kind (u0, v0) is the material point where xi = eta = 0.
//
// Pole strips (between a pole and its nearest ring) hold one triangle per segment: a south
// element (pole, ring 0 at v_j, ring 0 at v_j+1) with the pole at (xi, eta) = (0, 0), and a north
// element (ring at v_j, pole, ring at v_j+1) with the pole at (1, 0). The other half of each pole
// cell has two corners on the pole, so it is a degenerate (zero-area) triangle on the surface and
// carries no element: the elements cover the (u, v) rectangle minus half of each pole strip.
//
// Element order (used by locate_material_point): the `segments` south elements, then the middle
// bands from south to north (quads: one element per cell; triangles: per cell the north-type
// lower-left triangle then the mid upper-right triangle, which is how fig. 4.2 splits a quad into
// the book's north- and mid-region shape functions), then the `segments` north elements.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "deform/body_def.h"

namespace pbm {

// Element families by their shape functions in the book: quad (4.5)-(4.9), north (4.10)-(4.17),
// south (4.18)-(4.25), mid (4.26)-(4.33).
enum class ElementKind { quad, north, south, mid };

struct Element {
  ElementKind kind = ElementKind::quad;
  std::array<int, 4> nodes{-1, -1, -1, -1};  // book's local numbering (node 1 first); [3] = -1 for
                                             // triangles
  Real a = 0, b = 0;    // extents in u and v [rad], as in (4.6) and (4.13)-(4.14)
  Real u0 = 0, v0 = 0;  // material point where (xi, eta) = (0, 0) (see the header comment)
};

struct Tessellation {
  TessellationKind kind = TessellationKind::triangles;
  int rings = 0, segments = 0;
  std::vector<Vec2> uv;           // (u, v) of each node [rad]; size node_count()
  std::vector<Element> elements;  // quads: (rings + 1) segments; triangles: 2 rings segments
  // Surface triangles for rendering, collision and export: counter-clockwise seen from outside
  // (outward normal for a sphere x = (cos u cos v, cos u sin v, sin u)); quads split in two along
  // the same diagonal fig. 4.2 uses. Always 2 rings segments triangles.
  std::vector<std::array<int, 3>> triangles;
  // Sides of the finite elements (a quad's four, a triangle's three), each once, (low, high)
  // node order, sorted: the wireframe of fig. 4.1 / 4.2.
  std::vector<std::array<int, 2>> edges;
  int south_pole = 0, north_pole = 0;  // node indices
  int node_count() const { return static_cast<int>(uv.size()); }
};

// Builds the tessellation; throws pbm::Error naming the field if rings < 2 or segments < 3.
Tessellation tessellate(const TessellationDef& def);

// The node nearest to material coordinates (u, v) (v wraps at the seam; at the poles only u
// counts): where springs and constraints given by a material point act.
int nearest_node(const Tessellation& t, const Vec2& uv);

// Number of nodes of an element of this kind: 4 for quads, 3 for triangles.
inline int element_node_count(ElementKind kind) {
  return kind == ElementKind::quad ? 4 : 3;
}

}  // namespace pbm
