#include "liquid/surface_chains.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pbm {

namespace {

// How far inside a wall a marker is held, as a fraction of the cell: enough that its cell is the
// interior one, too little to show in any area.
constexpr Real kWallInset = 1e-7;
// Markers two surfaces' joins skip along one chain: a chain's own neighbours face each other
// only across a bend sharper than the spacing can resolve.
constexpr int kJoinSeparation = 3;
// A cell a link crosses holding less of the liquid than this fraction is left Empty (the link
// runs along its edge).
constexpr Real kTinyFill = 1e-6;

struct Plane {
  int a0, a1, thin;
  Real x0, y0, hx, hy;  // the plane's origin and cells along a0, a1
  int nx, ny;
  Real lo_x, hi_x, lo_y, hi_y;  // where markers are held, a hair inside the walls
};

Plane plane_of(const LiquidModel& model) {
  const ChainPlane p = chain_plane(model);
  const MacGrid& g = model.grid;
  Plane out{.a0 = p.a0,
            .a1 = p.a1,
            .thin = p.thin,
            .x0 = g.origin[p.a0],
            .y0 = g.origin[p.a1],
            .hx = g.h[p.a0],
            .hy = g.h[p.a1],
            .nx = g.n[p.a0],
            .ny = g.n[p.a1],
            .lo_x = 0,
            .hi_x = 0,
            .lo_y = 0,
            .hi_y = 0};
  out.lo_x = out.x0 + kWallInset * out.hx;
  out.hi_x = out.x0 + out.nx * out.hx - kWallInset * out.hx;
  out.lo_y = out.y0 + kWallInset * out.hy;
  out.hi_y = out.y0 + out.ny * out.hy - kWallInset * out.hy;
  return out;
}

// The grid index of plane cell (i, j), 1-based.
int cell_index(const MacGrid& g, const Plane& p, int i, int j) {
  int ijk[3];
  ijk[p.a0] = i;
  ijk[p.a1] = j;
  ijk[p.thin] = 1;
  return g.index(ijk[0], ijk[1], ijk[2]);
}

int column_of(const Plane& p, Real x) {
  return static_cast<int>(std::floor((x - p.x0) / p.hx)) + 1;
}
int row_of(const Plane& p, Real y) {
  return static_cast<int>(std::floor((y - p.y0) / p.hy)) + 1;
}

// The antiderivative of clamp(y, r0, r1) - r0.
Real clamped_integral(Real y, Real r0, Real r1) {
  if (y <= r0) return 0;
  if (y < r1) return 0.5 * (y - r0) * (y - r0);
  return 0.5 * (r1 - r0) * (r1 - r0) + (r1 - r0) * (y - r1);
}

// Marks every cell the segment from a to b passes through (a supercover: both cells at a corner
// it crosses exactly), so that the marked cells wall the chains' inside from their outside.
void mark_link_cells(const MacGrid& g, const Plane& p, const Vec3& a, const Vec3& b,
                     std::vector<int>& marks) {
  const Real xa = a[p.a0], ya = a[p.a1], xb = b[p.a0], yb = b[p.a1];
  int i = column_of(p, xa), j = row_of(p, ya);
  const int ie = column_of(p, xb), je = row_of(p, yb);
  auto mark = [&](int ci, int cj) {
    if (ci >= 1 && cj >= 1 && ci <= p.nx && cj <= p.ny) {
      marks[static_cast<std::size_t>(cell_index(g, p, ci, cj))] = 1;
    }
  };
  const Real dx = xb - xa, dy = yb - ya;
  const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
  constexpr Real kNever = std::numeric_limits<Real>::infinity();
  const Real delta_x = dx != 0 ? p.hx / std::abs(dx) : kNever;
  const Real delta_y = dy != 0 ? p.hy / std::abs(dy) : kNever;
  Real t_x = dx > 0   ? (p.x0 + i * p.hx - xa) / dx
             : dx < 0 ? (p.x0 + (i - 1) * p.hx - xa) / dx
                      : kNever;
  Real t_y = dy > 0   ? (p.y0 + j * p.hy - ya) / dy
             : dy < 0 ? (p.y0 + (j - 1) * p.hy - ya) / dy
                      : kNever;
  const int steps = std::abs(ie - i) + std::abs(je - j) + 1;
  for (int s = 0; s <= steps; ++s) {
    mark(i, j);
    if (i == ie && j == je) break;
    if (t_x < t_y) {
      i += step_x;
      t_x += delta_x;
    } else if (t_y < t_x) {
      j += step_y;
      t_y += delta_y;
    } else {
      mark(i + step_x, j);
      mark(i, j + step_y);
      i += step_x;
      j += step_y;
      t_x += delta_x;
      t_y += delta_y;
    }
  }
}

bool within_links(const std::vector<int>& next, const std::vector<int>& prev, int a, int b,
                  int links) {
  int f = a, r = a;
  for (int k = 0; k < links; ++k) {
    f = next[static_cast<std::size_t>(f)];
    r = prev[static_cast<std::size_t>(r)];
    if (f == b || r == b) return true;
  }
  return false;
}

}  // namespace

ChainPlane chain_plane(const LiquidModel& model) {
  ChainPlane p;
  p.thin = model.thin_axis >= 0 ? model.thin_axis : 2;
  p.a0 = p.thin == 0 ? 1 : 0;
  p.a1 = p.thin == 2 ? 1 : 2;
  return p;
}

Real chain_spacing(const LiquidModel& model) {
  const ChainPlane p = chain_plane(model);
  return std::min(model.grid.h[p.a0], model.grid.h[p.a1]) / model.def.markers_per_axis;
}

std::size_t chain_capacity(const LiquidModel& model) {
  const ChainPlane p = chain_plane(model);
  return 8 * static_cast<std::size_t>(model.def.markers_per_axis) *
         static_cast<std::size_t>(model.grid.n[p.a0]) *
         static_cast<std::size_t>(model.grid.n[p.a1]);
}

void seed_chains(const LiquidModel& model, std::vector<Vec3>& points, std::vector<int>& next) {
  const Plane p = plane_of(model);
  const MacGrid& g = model.grid;
  const Real s = chain_spacing(model);
  points.clear();
  next.clear();
  for (const FluidRegionDef& region : model.def.fluid) {
    const Real x0 = std::max(region.box.min[p.a0], p.lo_x);
    const Real x1 = std::min(region.box.max[p.a0], p.hi_x);
    const Real y0 = std::max(region.box.min[p.a1], p.lo_y);
    const Real y1 = std::min(region.box.max[p.a1], p.hi_y);
    if (!(x1 > x0 && y1 > y0)) continue;
    const Real corner[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    const int first = static_cast<int>(points.size());
    for (int e = 0; e < 4; ++e) {
      const Real* a = corner[e];
      const Real* b = corner[(e + 1) % 4];
      const Real length = std::hypot(b[0] - a[0], b[1] - a[1]);
      const int n = std::max(1, static_cast<int>(std::ceil(length / s - 1e-9)));
      for (int k = 0; k < n; ++k) {
        const Real t = static_cast<Real>(k) / n;
        Vec3 x;
        x[p.a0] = a[0] + t * (b[0] - a[0]);
        x[p.a1] = a[1] + t * (b[1] - a[1]);
        x[p.thin] = g.origin[p.thin] + 0.5 * g.h[p.thin];
        points.push_back(x);
        next.push_back(static_cast<int>(points.size()));
      }
    }
    next.back() = first;
  }
}

void advect_chains(const LiquidModel& model, const MacField& field, Real dt,
                   std::vector<Vec3>& points) {
  const Plane p = plane_of(model);
  const MacGrid& g = model.grid;
  for (Vec3& x : points) {
    const Vec3 v1 = interpolate_velocity(g, field.u, x);
    const Vec3 v2 = interpolate_velocity(g, field.u, x + 0.5 * dt * v1);
    Vec3 moved = x + dt * v2;
    moved[p.thin] = x[p.thin];
    if (!moved.allFinite()) {
      x = moved;  // the guard refuses the state
      continue;
    }
    moved[p.a0] = std::clamp(moved[p.a0], p.lo_x, p.hi_x);
    moved[p.a1] = std::clamp(moved[p.a1], p.lo_y, p.hi_y);
    const Eigen::Vector3i c = g.cell_of(moved);
    if (model.fixed[static_cast<std::size_t>(g.index(c.x(), c.y(), c.z()))] == CellFlag::solid) {
      continue;
    }
    x = moved;
  }
}

ChainRemeshStats remesh_chains(const LiquidModel& model, std::vector<Vec3>& points,
                               std::vector<int>& next, ChainScratch& w) {
  ChainRemeshStats stats;
  const MacGrid& g = model.grid;
  const Plane p = plane_of(model);
  const Real s = chain_spacing(model);
  const Real merge = kChainMergeFraction * s, join = kChainJoinFraction * s;
  const std::size_t n = points.size();
  w.prev.assign(n, 0);
  for (std::size_t m = 0; m < n; ++m)
    w.prev[static_cast<std::size_t>(next[m])] = static_cast<int>(m);
  w.alive.assign(n, 1);
  auto at = [&](int m) -> const Vec3& { return points[static_cast<std::size_t>(m)]; };
  auto distance = [&](int a, int b) { return (at(a) - at(b)).norm(); };
  auto unlink = [&](int m) { w.alive[static_cast<std::size_t>(m)] = 0; };
  auto link = [&](int a, int b) {
    next[static_cast<std::size_t>(a)] = b;
    w.prev[static_cast<std::size_t>(b)] = a;
  };

  // 1. Linked markers too close: both deleted, their neighbours linked (16.3.2).
  for (std::size_t m = 0; m < n; ++m) {
    const int a = static_cast<int>(m);
    if (!w.alive[m]) continue;
    const int b = next[m];
    if (b == a || !w.alive[static_cast<std::size_t>(b)] || !(distance(a, b) < merge)) continue;
    const int before = w.prev[m], after = next[static_cast<std::size_t>(b)];
    unlink(a);
    unlink(b);
    stats.deleted += 2;
    if (before != b) link(before, after);  // else the loop held only a and b
  }

  // 2. Unlinked markers facing each other: the chains cross over (a join), found in buckets of
  // the grid's cells (the join distance is under a cell).
  w.bucket_head.assign(static_cast<std::size_t>(g.size), -1);
  w.bucket_next.assign(n, -1);
  auto bucket_of = [&](const Vec3& x) {
    const int i = std::clamp(column_of(p, x[p.a0]), 1, p.nx);
    const int j = std::clamp(row_of(p, x[p.a1]), 1, p.ny);
    return cell_index(g, p, i, j);
  };
  for (std::size_t m = n; m-- > 0;) {
    if (!w.alive[m] || !points[m].allFinite()) continue;
    const auto b = static_cast<std::size_t>(bucket_of(points[m]));
    w.bucket_next[m] = w.bucket_head[b];
    w.bucket_head[b] = static_cast<int>(m);
  }
  for (std::size_t m = 0; m < n; ++m) {
    const int a = static_cast<int>(m);
    if (!w.alive[m] || !points[m].allFinite()) continue;
    const int i = std::clamp(column_of(p, at(a)[p.a0]), 1, p.nx);
    const int j = std::clamp(row_of(p, at(a)[p.a1]), 1, p.ny);
    const Vec3 tangent_a = at(next[m]) - at(w.prev[m]);
    int best = -1;
    Real best_distance = join;
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        if (i + di < 1 || j + dj < 1 || i + di > p.nx || j + dj > p.ny) continue;
        for (int b = w.bucket_head[static_cast<std::size_t>(cell_index(g, p, i + di, j + dj))];
             b >= 0; b = w.bucket_next[static_cast<std::size_t>(b)]) {
          if (b == a || !w.alive[static_cast<std::size_t>(b)]) continue;
          const Real d = distance(a, b);
          if (!(d < best_distance) && !(d == best_distance && best >= 0 && b < best)) continue;
          const auto bs = static_cast<std::size_t>(b);
          const Vec3 tangent_b = at(next[bs]) - at(w.prev[bs]);
          if (!(tangent_a.dot(tangent_b) < 0)) continue;
          if (within_links(next, w.prev, a, b, kJoinSeparation)) continue;
          best = b;
          best_distance = d;
        }
      }
    }
    if (best < 0) continue;
    const auto bs = static_cast<std::size_t>(best);
    const int pa = w.prev[m], na = next[m], pb = w.prev[bs], nb = next[bs];
    unlink(a);
    unlink(best);
    link(pa, nb);
    link(pb, na);
    stats.joined += 1;
    // The join zips on along both bridges while they are shorter than the join distance: two
    // surfaces that close meet along the whole of it, not at points trapping slivers of air.
    for (int bridge : {pa, pb}) {
      int from = bridge;
      while (w.alive[static_cast<std::size_t>(from)]) {
        const int to = next[static_cast<std::size_t>(from)];
        if (to == from || !(distance(from, to) < join)) break;
        const int before = w.prev[static_cast<std::size_t>(from)];
        const int after = next[static_cast<std::size_t>(to)];
        if (before == to || after == from || before == after) break;  // the loop is that small
        unlink(from);
        unlink(to);
        stats.deleted += 2;
        link(before, after);
        from = before;
      }
    }
  }

  // 3. Long links split evenly (16.3.2), up to the capacity.
  const std::size_t capacity = chain_capacity(model);
  std::size_t live = 0;
  for (std::size_t m = 0; m < n; ++m) live += w.alive[m];
  for (std::size_t m = 0; m < n; ++m) {
    if (!w.alive[m]) continue;
    const int a = static_cast<int>(m), b = next[m];
    const Real length = distance(a, b);
    if (!(length > s)) continue;  // a NaN length too: the guard refuses that state
    const Real pieces = std::ceil(length / s);
    const std::size_t extra = static_cast<std::size_t>(pieces) - 1;
    if (live + extra > capacity) {
      stats.full = true;
      continue;
    }
    const Vec3 xa = at(a), xb = at(b);
    int last = a;
    for (std::size_t k = 1; k <= extra; ++k) {
      points.push_back(xa + (xb - xa) * (static_cast<Real>(k) / pieces));
      next.push_back(-1);
      w.prev.push_back(-1);
      w.alive.push_back(1);
      const int added = static_cast<int>(points.size()) - 1;
      link(last, added);
      last = added;
    }
    link(last, b);
    live += extra;
    stats.inserted += static_cast<int>(extra);
  }

  // 4. The loops renumbered in the order of their first marker; those of fewer than three
  // markers dropped.
  const std::size_t total = points.size();
  w.visited.assign(total, 0);
  w.points.clear();
  w.next.clear();
  for (std::size_t start = 0; start < total; ++start) {
    if (!w.alive[start] || w.visited[start]) continue;
    w.order.clear();
    int m = static_cast<int>(start);
    while (m >= 0 && w.alive[static_cast<std::size_t>(m)] &&
           !w.visited[static_cast<std::size_t>(m)] && w.order.size() < total) {
      w.visited[static_cast<std::size_t>(m)] = 1;
      w.order.push_back(m);
      m = next[static_cast<std::size_t>(m)];
    }
    if (w.order.size() < 3) {
      stats.loops_dropped += 1;
      continue;
    }
    const int first = static_cast<int>(w.points.size());
    for (int k : w.order) {
      w.points.push_back(points[static_cast<std::size_t>(k)]);
      w.next.push_back(static_cast<int>(w.points.size()));
    }
    w.next.back() = first;
  }
  points.swap(w.points);
  next.swap(w.next);
  return stats;
}

void chain_cell_fractions(const LiquidModel& model, const std::vector<Vec3>& points,
                          const std::vector<int>& next, std::vector<Real>& fraction) {
  const MacGrid& g = model.grid;
  const Plane p = plane_of(model);
  fraction.assign(static_cast<std::size_t>(g.size), 0.0);
  // A cell's area inside the loops is -oint (clamp(y, r0, r1) - r0) dx over the loops' pieces in
  // its column (counter-clockwise: -oint y dx is the area), r0, r1 its row's bottom and top.
  // Markers held at a wall are taken on it: the hair they are held inside would otherwise take
  // its sliver off the cells along the wall (still water accelerated at 4e-7 m/s^2 by it).
  const Real x_end = p.x0 + p.nx * p.hx, y_end = p.y0 + p.ny * p.hy;
  auto on_x = [&](Real x) { return x <= p.lo_x ? p.x0 : x >= p.hi_x ? x_end : x; };
  auto on_y = [&](Real y) { return y <= p.lo_y ? p.y0 : y >= p.hi_y ? y_end : y; };
  for (std::size_t m = 0; m < points.size(); ++m) {
    const Vec3& a = points[m];
    const Vec3& b = points[static_cast<std::size_t>(next[m])];
    const Real xa = on_x(a[p.a0]), ya = on_y(a[p.a1]), xb = on_x(b[p.a0]), yb = on_y(b[p.a1]);
    if (!(xa != xb) || !std::isfinite(xa + ya + xb + yb)) continue;
    const Real x_min = std::min(xa, xb), x_max = std::max(xa, xb);
    const int i_lo = std::max(1, column_of(p, x_min)), i_hi = std::min(p.nx, column_of(p, x_max));
    const Real slope = (yb - ya) / (xb - xa);
    for (int i = i_lo; i <= i_hi; ++i) {
      const Real c0 = std::max(x_min, p.x0 + (i - 1) * p.hx);
      const Real c1 = std::min(x_max, p.x0 + i * p.hx);
      if (!(c1 > c0)) continue;
      // The piece in the link's direction.
      const Real xs = xb > xa ? c0 : c1, xe = xb > xa ? c1 : c0;
      const Real ys = ya + (xs - xa) * slope, ye = ya + (xe - xa) * slope;
      const Real dx = xe - xs, dy = ye - ys;
      const Real y_lo = std::min(ys, ye), y_hi = std::max(ys, ye);
      const int j_hi = std::min(p.ny, row_of(p, y_hi));
      for (int j = 1; j <= j_hi; ++j) {
        const Real r0 = p.y0 + (j - 1) * p.hy, r1 = r0 + p.hy;
        Real mean;  // of clamp(y, r0, r1) - r0 along the piece
        if (r1 <= y_lo) {
          mean = p.hy;
        } else if (std::abs(dy) < 1e-6 * p.hy) {
          mean = std::clamp(0.5 * (ys + ye), r0, r1) - r0;
        } else {
          mean = (clamped_integral(ye, r0, r1) - clamped_integral(ys, r0, r1)) / dy;
        }
        fraction[static_cast<std::size_t>(cell_index(g, p, i, j))] -= dx * mean;
      }
    }
  }
  const Real area = p.hx * p.hy;
  for (Real& f : fraction) f /= area;
}

void label_from_chains(const LiquidModel& model, const std::vector<Vec3>& points,
                       const std::vector<int>& next, std::vector<CellFlag>& flags,
                       std::vector<Real>& fill, std::vector<int>& marks) {
  const MacGrid& g = model.grid;
  const Plane p = plane_of(model);
  chain_cell_fractions(model, points, next, fill);
  std::fill(marks.begin(), marks.end(), 0);
  for (std::size_t m = 0; m < points.size(); ++m) {
    const Vec3& a = points[m];
    const Vec3& b = points[static_cast<std::size_t>(next[m])];
    if (a.allFinite() && b.allFinite()) mark_link_cells(g, p, a, b, marks);
  }
  // Region growing (fig. 16.5) over the cells no link crosses, 4-connected in the plane; a
  // region is liquid when the chains enclose most of it (each of its cells wholly in or out,
  // but for rounding and for chains tangled within a substep).
  constexpr int kGrown = 2;
  std::vector<int> region;
  for (int j = 1; j <= p.ny; ++j) {
    for (int i = 1; i <= p.nx; ++i) {
      const auto start = static_cast<std::size_t>(cell_index(g, p, i, j));
      if (flags[start] != CellFlag::empty || marks[start] != 0) continue;
      region.clear();
      region.push_back(static_cast<int>(start));
      marks[start] = kGrown;
      Real enclosed = 0;
      for (std::size_t k = 0; k < region.size(); ++k) {
        const int c = region[k];
        enclosed += fill[static_cast<std::size_t>(c)];
        for (int e : {g.stride(p.a0), g.stride(p.a1)}) {
          for (int nb : {c - e, c + e}) {
            const auto ns = static_cast<std::size_t>(nb);
            if (flags[ns] != CellFlag::empty || marks[ns] != 0) continue;  // walls are Solid
            marks[ns] = kGrown;
            region.push_back(nb);
          }
        }
      }
      const bool liquid = enclosed > 0.5 * static_cast<Real>(region.size());
      for (int c : region) {
        const auto cs = static_cast<std::size_t>(c);
        fill[cs] = liquid ? 1.0 : 0.0;
        if (liquid) flags[cs] = CellFlag::full;
      }
    }
  }
  // The cells the chains cross hold what they enclose there: liquid cells (the book's Surface
  // cells of fig. 16.5c where next to an Empty cell, as every method labels them; a wall's and a
  // bubble's corner Full), their fill kept exact.
  for (int c = 0; c < g.size; ++c) {
    const auto cs = static_cast<std::size_t>(c);
    if (marks[cs] == 1 && flags[cs] == CellFlag::empty) {
      const Real f = std::clamp(fill[cs], 0.0, 1.0);
      fill[cs] = f > kTinyFill ? f : 0.0;
      if (f > kTinyFill) flags[cs] = CellFlag::full;
    } else if (marks[cs] != kGrown) {
      fill[cs] = 0;  // walls, solids
    }
  }
}

Real chains_area(const LiquidModel& model, const std::vector<Vec3>& points,
                 const std::vector<int>& next, Vec3* centroid) {
  const Plane p = plane_of(model);
  Real twice = 0, cx = 0, cy = 0;
  for (std::size_t m = 0; m < points.size(); ++m) {
    const Vec3& a = points[m];
    const Vec3& b = points[static_cast<std::size_t>(next[m])];
    // About the plane's origin, so that the products keep their digits.
    const Real xa = a[p.a0] - p.x0, ya = a[p.a1] - p.y0, xb = b[p.a0] - p.x0, yb = b[p.a1] - p.y0;
    const Real cross = xa * yb - xb * ya;
    twice += cross;
    cx += (xa + xb) * cross;
    cy += (ya + yb) * cross;
  }
  const Real area = 0.5 * twice;
  if (centroid) {
    const MacGrid& g = model.grid;
    Vec3 c;
    c[p.thin] = g.origin[p.thin] + 0.5 * g.h[p.thin];
    c[p.a0] = area != 0 ? p.x0 + cx / (6 * area) : p.x0;
    c[p.a1] = area != 0 ? p.y0 + cy / (6 * area) : p.y0;
    *centroid = c;
  }
  return area;
}

int chain_loops(const std::vector<int>& next) {
  std::vector<std::uint8_t> seen(next.size(), 0);
  int loops = 0;
  for (std::size_t start = 0; start < next.size(); ++start) {
    if (seen[start]) continue;
    ++loops;
    for (auto m = start; !seen[m]; m = static_cast<std::size_t>(next[m])) seen[m] = 1;
  }
  return loops;
}

}  // namespace pbm
