#include "liquid/moving_solids.h"

#include <algorithm>
#include <cmath>

#include "liquid/cell_labels.h"

namespace pbm {

namespace {

// Whether a column's centre p lies in the projected triangle (a, b, c), counter-clockwise, with
// the top-left rule on its edges: a point on an edge two triangles share belongs to exactly one
// of them, so a scan line through a vertex or an edge crosses the surface once, not twice or
// never.
bool covers(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p, Real (&w)[3]) {
  const Vec2* v[3] = {&a, &b, &c};
  Real area = 0;
  for (int e = 0; e < 3; ++e) {
    const Vec2& p0 = *v[(e + 1) % 3];
    const Vec2& p1 = *v[(e + 2) % 3];
    const Vec2 d = p1 - p0;
    const Real f = d.x() * (p.y() - p0.y()) - d.y() * (p.x() - p0.x());
    const bool top_left = d.y() < 0 || (d.y() == 0 && d.x() > 0);
    if (f < 0 || (f == 0 && !top_left)) return false;
    w[e] = f;  // twice the area opposite vertex e
    area += f;
  }
  if (area <= 0) return false;
  for (Real& x : w) x /= area;
  return true;
}

}  // namespace

void size_moving_solids(const LiquidModel& model, MovingSolids& solids) {
  const auto n = static_cast<std::size_t>(model.grid.size);
  solids.inside.assign(n, 0);
  solids.velocity.assign(n, Vec3::Zero());
  solids.cells.clear();
}

void clear_moving_solids(MovingSolids& solids) {
  for (int c : solids.cells) {
    solids.inside[static_cast<std::size_t>(c)] = 0;
    solids.velocity[static_cast<std::size_t>(c)].setZero();
  }
  solids.cells.clear();
}

void mark_solid_cell(const LiquidModel& model, int c, const Vec3& velocity, MovingSolids& solids) {
  const auto k = static_cast<std::size_t>(c);
  if (model.fixed[k] != CellFlag::empty || solids.inside[k]) return;
  solids.inside[k] = 1;
  solids.velocity[k] = velocity;
  solids.cells.push_back(c);
}

void voxelize_surface(const LiquidModel& model, const SolidSurface& surface, Real dt,
                      MovingSolids& solids) {
  const MacGrid& g = model.grid;
  const ColumnAxes axes = column_axes(model);
  const int n0 = g.n[axes.h0], n1 = g.n[axes.h1], nv = g.n[axes.v];
  // A column's centre along axis a, index i (0-based): a 2D grid's slab has one, its middle.
  auto centre = [&](int a, int i) { return g.origin[a] + (i + 0.5) * g.h[a]; };
  solids.crossings.clear();
  for (const std::array<int, 3>& t : surface.triangles) {
    Vec3 y[3], v[3];
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(t[k]);
      v[k] = surface.x_dot[i];
      y[k] = surface.x[i] + dt * v[k];
    }
    // Along the scan axis the outward normal points down where the line enters the solid.
    const Real normal_v = (y[1] - y[0]).cross(y[2] - y[0])[axes.v];
    if (normal_v == 0) continue;  // edge-on: the line misses it or runs in its plane
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) p[k] = Vec2(y[k][axes.h0], y[k][axes.h1]);
    // Counter-clockwise in the (h0, h1) plane for the edge test.
    const Real turn = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x();
    int order[3] = {0, 1, 2};
    if (turn < 0) std::swap(order[1], order[2]);
    const Vec2 lo = p[0].cwiseMin(p[1]).cwiseMin(p[2]);
    const Vec2 hi = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
    const int i0_lo =
        std::max(0, static_cast<int>(std::ceil((lo.x() - g.origin[axes.h0]) / g.h[axes.h0] - 0.5)));
    const int i0_hi = std::min(
        n0 - 1, static_cast<int>(std::floor((hi.x() - g.origin[axes.h0]) / g.h[axes.h0] - 0.5)));
    const int i1_lo =
        std::max(0, static_cast<int>(std::ceil((lo.y() - g.origin[axes.h1]) / g.h[axes.h1] - 0.5)));
    const int i1_hi = std::min(
        n1 - 1, static_cast<int>(std::floor((hi.y() - g.origin[axes.h1]) / g.h[axes.h1] - 0.5)));
    for (int i1 = i1_lo; i1 <= i1_hi; ++i1) {
      for (int i0 = i0_lo; i0 <= i0_hi; ++i0) {
        const Vec2 q(centre(axes.h0, i0), centre(axes.h1, i1));
        Real w[3];
        if (!covers(p[order[0]], p[order[1]], p[order[2]], q, w)) continue;
        Real at = 0;
        Vec3 velocity = Vec3::Zero();
        for (int k = 0; k < 3; ++k) {
          at += w[k] * y[order[k]][axes.v];
          velocity += w[k] * v[order[k]];
        }
        solids.crossings.push_back({.column = i0 + n0 * i1,
                                    .at = at,
                                    .step = normal_v < 0 ? 1 : -1,
                                    .velocity = velocity});
      }
    }
  }
  // Each column's crossings in order along the line: inside wherever the winding is positive.
  std::sort(solids.crossings.begin(), solids.crossings.end());
  const Real bottom = g.origin[axes.v], hv = g.h[axes.v];
  const std::vector<MovingSolids::Crossing>& x = solids.crossings;
  int winding = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    winding += x[k].step;
    const bool last_of_column = k + 1 == x.size() || x[k + 1].column != x[k].column;
    if (last_of_column) {
      winding = 0;
      continue;
    }
    if (winding <= 0) continue;
    const MovingSolids::Crossing& a = x[k];
    const MovingSolids::Crossing& b = x[k + 1];
    // Cells whose centres lie strictly between the two crossings.
    const int first = std::max(1, static_cast<int>(std::floor((a.at - bottom) / hv + 0.5)) + 1);
    const int last = std::min(nv, static_cast<int>(std::ceil((b.at - bottom) / hv + 0.5)) - 1);
    int ijk[3];
    ijk[axes.h0] = a.column % n0 + 1;
    ijk[axes.h1] = a.column / n0 + 1;
    for (int iv = first; iv <= last; ++iv) {
      const Real z = bottom + (iv - 0.5) * hv;
      if (!(z > a.at && z < b.at)) continue;
      const Real s = b.at > a.at ? (z - a.at) / (b.at - a.at) : 0.5;
      ijk[axes.v] = iv;
      mark_solid_cell(model, g.index(ijk[0], ijk[1], ijk[2]), (1 - s) * a.velocity + s * b.velocity,
                      solids);
    }
  }
}

int push_markers_out(const LiquidModel& model, const MovingSolids& solids,
                     std::vector<Vec3>& markers) {
  if (solids.cells.empty()) return 0;
  const MacGrid& g = model.grid;
  const int vertical = column_axes(model).v;
  auto free = [&](int c) {
    const auto k = static_cast<std::size_t>(c);
    return !solids.inside[k] && model.fixed[k] == CellFlag::empty;
  };
  // The first free cell from c along axis a in direction dir (+-1), at most `reach` cells away:
  // how many cells away, or 0.
  auto first_free = [&](int c, int i, int a, int dir, int reach) {
    for (int step = 1; step <= reach; ++step) {
      const int j = i + dir * step;
      if (j < 1 || j > g.n[a]) return 0;
      if (free(c + dir * step * g.stride(a))) return step;
    }
    return 0;
  };
  int moved = 0;
  for (Vec3& x : markers) {
    const Eigen::Vector3i ijk = g.cell_of(x);
    if (!g.interior(ijk.x(), ijk.y(), ijk.z())) continue;
    const int c = g.index(ijk.x(), ijk.y(), ijk.z());
    const auto k = static_cast<std::size_t>(c);
    if (!solids.inside[k]) continue;
    // Ahead of the solid, along the main axis of its motion there (the liquid it sweeps); for a
    // solid at rest, to the nearer free cell up or down the column (up on a tie).
    Vec3 velocity = solids.velocity[k];
    if (model.thin_axis >= 0) velocity[model.thin_axis] = 0;
    int axis = vertical, dir = 0, steps = 0;
    if (velocity.squaredNorm() > 0) {
      velocity.cwiseAbs().maxCoeff(&axis);
      dir = velocity[axis] > 0 ? 1 : -1;
      steps = first_free(c, ijk[axis], axis, dir, g.n[axis]);
    }
    if (steps == 0) {
      axis = vertical;
      const int up = first_free(c, ijk[axis], axis, 1, g.n[axis]);
      const int down = first_free(c, ijk[axis], axis, -1, g.n[axis]);
      if (up == 0 && down == 0) continue;  // the whole column is solid: nowhere to go
      const bool go_up = down == 0 || (up != 0 && up <= down);
      dir = go_up ? 1 : -1;
      steps = go_up ? up : down;
    }
    // Just inside the free cell, a tenth of a cell past the face it is entered by.
    const int target = ijk[axis] + dir * steps;
    const Real face = g.origin[axis] + (dir > 0 ? target - 1 : target) * g.h[axis];
    x[axis] = face + dir * 0.1 * g.h[axis];
    ++moved;
  }
  return moved;
}

}  // namespace pbm
