// The staggered grid of fig. 16.1: pressure at the cells' centres, u, v, w at the centres of
// their faces. Every array has one layer of ghost cells around the domain (the walls of 16.2.2,
// whose velocities and pressures are set like any boundary cell's), so the update of (16.2) reads
// its neighbours without a test. Index (i, j, k) in 0..n+1 per axis; the interior is 1..n.
// u(i, j, k) is the face between cells i and i+1 along x (u_{i+1/2,j,k}), v and w likewise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace pbm {

// What a cell holds (16.2.1); Inflow and Outflow are the boundary cells of 16.2.2.
enum class CellFlag : std::uint8_t { solid, full, surface, empty, inflow, outflow };

inline bool is_liquid(CellFlag f) {
  return f == CellFlag::full || f == CellFlag::surface;
}
// A face whose velocity the walls or a source fix (no momentum update, no pressure correction).
inline bool fixes_velocity(CellFlag f) {
  return f == CellFlag::solid || f == CellFlag::inflow;
}

struct MacGrid {
  Eigen::Vector3i n{1, 1, 1};  // interior cells per axis
  Vec3 h{1, 1, 1};             // cell sizes delta x, y, z [m]
  Vec3 origin = Vec3::Zero();  // the domain's min corner (the interior's first cell) [m]
  int sx = 1, sy = 1, sz = 1;  // strides of the arrays (with the ghost layer)
  int size = 0;                // cells with the ghost layer

  void resize(const Eigen::Vector3i& cells, const Vec3& cell_size, const Vec3& min_corner) {
    n = cells;
    h = cell_size;
    origin = min_corner;
    sx = 1;
    sy = n.x() + 2;
    sz = (n.x() + 2) * (n.y() + 2);
    size = sz * (n.z() + 2);
  }
  int index(int i, int j, int k) const { return i * sx + j * sy + k * sz; }
  int stride(int axis) const { return axis == 0 ? sx : axis == 1 ? sy : sz; }
  bool interior(int i, int j, int k) const {
    return i >= 1 && j >= 1 && k >= 1 && i <= n.x() && j <= n.y() && k <= n.z();
  }
  Real cell_volume() const { return h.x() * h.y() * h.z(); }
  int interior_cells() const { return n.x() * n.y() * n.z(); }
  // The cell containing a world point (possibly a ghost or outside: clamp before indexing).
  Eigen::Vector3i cell_of(const Vec3& x) const {
    const Vec3 c = (x - origin).cwiseQuotient(h);
    return {static_cast<int>(std::floor(c.x())) + 1, static_cast<int>(std::floor(c.y())) + 1,
            static_cast<int>(std::floor(c.z())) + 1};
  }
  // The centre of cell (i, j, k) [m].
  Vec3 centre(int i, int j, int k) const {
    return origin + Vec3((i - 0.5) * h.x(), (j - 0.5) * h.y(), (k - 0.5) * h.z());
  }
  // The centre of the cell at array index c.
  Vec3 centre(int c) const { return centre(c % sy, (c / sy) % (n.y() + 2), c / sz); }
};

// Velocity components on the faces and pressure at the centres, each grid.size long.
struct MacField {
  std::vector<Real> u[3];
  void resize(int size) {
    for (auto& c : u) c.assign(static_cast<std::size_t>(size), 0.0);
  }
};

// The sample index and fraction along axis a of a point g cells from the origin (already offset
// so the component's samples sit at integers), clamped to the samples there are.
inline void stencil_axis(const MacGrid& grid, int a, bool own_axis, Real g, int& base, Real& frac) {
  // Faces 0..n along the axis, cells 0..n+1 across it (the ghosts carry the walls' values).
  const int last = own_axis ? grid.n[a] : grid.n[a] + 1;
  // A NaN position (a state the guard will reject) reads the first sample, not past the array.
  g = g >= 0 ? std::min(g, static_cast<Real>(last)) : 0.0;
  int b = static_cast<int>(g);
  if (b >= last) b = last - 1;
  if (last == 0) b = 0;
  base = b;
  frac = last == 0 ? 0.0 : g - b;
}

// The 8 samples of component `axis` around world point x: from index base (per axis) to base + 1
// at fractions frac (clamped to the grid; a 2D grid's thin axis has fraction 0). Inline, with the
// blend below: the advection's and the markers' inner loop (40% of a 32^3 dam break's time when
// they were calls into mac_grid.cpp, `perf record pbm simulate`).
inline void component_stencil(const MacGrid& grid, int axis, const Vec3& x, int (&base)[3],
                              Real (&frac)[3]) {
  // Grid coordinates in which the component's samples sit at integers: the faces of axis `axis`
  // at i * h (index i), the other axes' samples at the cells' centres (index j, centre j - 1/2).
  for (int a = 0; a < 3; ++a) {
    const Real g = (x[a] - grid.origin[a]) / grid.h[a] + (a == axis ? 0.0 : 0.5);
    stencil_axis(grid, a, a == axis, g, base[a], frac[a]);
  }
}

// The trilinear blend of `values` over the 8 samples from index base (per axis) to base + 1 at
// fractions frac. Every sample is read, a zero weight's too (a 2D grid's thin axis: its ghost
// layer), so a NaN anywhere in the stencil reads as NaN (the guard then refuses the state).
inline Real blend_trilinear(const MacGrid& grid, const std::vector<Real>& values,
                            const int (&base)[3], const Real (&frac)[3]) {
  // Along x, then y, then z, without a branch on the weights: 22% off a 32^3 dam break's time
  // against the 8-term sum that skipped zero weights (`time pbm simulate`, 3.6-3.9 s -> 2.9 s).
  const Real* v = values.data() + grid.index(base[0], base[1], base[2]);
  const int sx = grid.sx, sy = grid.sy, sz = grid.sz;
  const Real fx = frac[0], fy = frac[1], fz = frac[2];
  const Real c00 = v[0] + fx * (v[sx] - v[0]);
  const Real c10 = v[sy] + fx * (v[sy + sx] - v[sy]);
  const Real c01 = v[sz] + fx * (v[sz + sx] - v[sz]);
  const Real c11 = v[sz + sy] + fx * (v[sz + sy + sx] - v[sz + sy]);
  const Real c0 = c00 + fy * (c10 - c00);
  const Real c1 = c01 + fy * (c11 - c01);
  return c0 + fz * (c1 - c0);
}

// One component (axis) at a world point.
inline Real interpolate_component(const MacGrid& grid, const std::vector<Real>& u, int axis,
                                  const Vec3& x) {
  int base[3];
  Real frac[3];
  component_stencil(grid, axis, x, base, frac);
  return blend_trilinear(grid, u, base, frac);
}

// The velocity at a world point: each component interpolated trilinearly from the faces that
// carry it (the area weighting of fig. 16.3, volume weighting in 3D). Points outside the domain
// are clamped to it. The component along `skip` (a 2D grid's thin axis, which carries none; -1:
// every component) is left at 0. The point's grid coordinates are divided out once for the
// three components (the same values component_stencil computes: a third of its divisions).
inline Vec3 interpolate_velocity(const MacGrid& grid, const std::vector<Real> (&u)[3],
                                 const Vec3& x, int skip = -1) {
  Real cells[3];
  for (int a = 0; a < 3; ++a) cells[a] = (x[a] - grid.origin[a]) / grid.h[a];
  Vec3 v = Vec3::Zero();
  for (int c = 0; c < 3; ++c) {
    if (c == skip) continue;
    int base[3];
    Real frac[3];
    for (int a = 0; a < 3; ++a) {
      stencil_axis(grid, a, a == c, cells[a] + (a == c ? 0.0 : 0.5), base[a], frac[a]);
    }
    v[c] = blend_trilinear(grid, u[c], base, frac);
  }
  return v;
}

}  // namespace pbm
