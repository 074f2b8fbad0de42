#include "liquid/liquid_probe.h"

#include <algorithm>
#include <cmath>

#include "liquid/cell_labels.h"

namespace pbm {

namespace {

constexpr std::uint8_t kUnknown = 0, kKnown = 1;
constexpr Real kNoSurface = -1e300;

// Cell c's index along axis a (0..n + 1).
int index_along(const MacGrid& g, int a, int c) {
  return (c / g.stride(a)) % (g.n[a] + 2);
}

// ws.probe_eta of every liquid cell: where the free surface over it lies along the vertical axis
// [m]. Down each column along gravity, a Surface cell puts the surface at its fill and the
// liquid below it keeps that surface; an Empty cell (air, also a pocket under liquid) or a solid
// interrupts it: the liquid under a body or a ledge takes its horizontal neighbours' surface,
// spreading inwards pass by pass, so that a hump of liquid riding on a body presses it down
// without also pressing it up.
void set_free_surface_heights(const LiquidModel& model, const Vec3& gravity, LiquidWorkspace& ws) {
  const MacGrid& g = model.grid;
  const ColumnAxes axes = column_axes(model);
  const int v = axes.v;
  const bool up_is_plus = gravity[v] <= 0;  // the surface lies towards +v over the liquid
  const int down = up_is_plus ? -g.stride(v) : g.stride(v);
  const Real hv = g.h[v];
  std::vector<Real>& eta = ws.probe_eta;
  eta.assign(static_cast<std::size_t>(g.size), kNoSurface);
  int ijk[3];
  for (int i1 = 1; i1 <= g.n[axes.h1]; ++i1) {
    for (int i0 = 1; i0 <= g.n[axes.h0]; ++i0) {
      ijk[axes.h0] = i0;
      ijk[axes.h1] = i1;
      ijk[v] = up_is_plus ? g.n[v] : 1;
      Real surface = kNoSurface;
      int c = g.index(ijk[0], ijk[1], ijk[2]);
      for (int t = 0; t < g.n[v]; ++t, c += down) {
        const auto k = static_cast<std::size_t>(c);
        const CellFlag f = ws.flags[k];
        if (f == CellFlag::empty || f == CellFlag::solid) {
          surface = kNoSurface;
        } else if (f == CellFlag::surface) {
          const int iv = index_along(g, v, c);
          // The cell's face towards gravity, and the fill above it.
          const Real floor = g.origin[v] + (up_is_plus ? iv - 1 : iv) * hv;
          surface = floor + (up_is_plus ? 1 : -1) * ws.fill[k] * hv;
          eta[k] = surface;
        } else if (f == CellFlag::full) {
          eta[k] = surface;
        }
      }
    }
  }
  // Under solids: from the neighbours across the column axes, a pass at a time (each reads only
  // the last pass's values: the same result in any order), over the cells still without one.
  std::vector<int>& pending = ws.probe_order;
  std::vector<Real>& next = ws.probe_next_eta;
  pending.clear();
  for (int c = 0; c < g.size; ++c) {
    const auto k = static_cast<std::size_t>(c);
    if (ws.flags[k] == CellFlag::full && eta[k] == kNoSurface) pending.push_back(c);
  }
  const int horizontal[2] = {axes.h0, axes.h1};
  while (!pending.empty()) {
    next.assign(pending.size(), kNoSurface);
    for (std::size_t m = 0; m < pending.size(); ++m) {
      const int c = pending[m];
      Real sum = 0;
      int n = 0;
      for (int a : horizontal) {
        if (a == model.thin_axis) continue;
        for (int side = -1; side <= 1; side += 2) {
          const auto nb = static_cast<std::size_t>(c + side * g.stride(a));
          if (is_liquid(ws.flags[nb]) && eta[nb] != kNoSurface) {
            sum += eta[nb];
            ++n;
          }
        }
      }
      if (n > 0) next[m] = sum / n;
    }
    std::size_t kept = 0;
    for (std::size_t m = 0; m < pending.size(); ++m) {
      if (next[m] != kNoSurface) {
        eta[static_cast<std::size_t>(pending[m])] = next[m];
      } else {
        pending[kept++] = pending[m];
      }
    }
    if (kept == pending.size()) break;  // nothing reachable is left (a full tank)
    pending.resize(kept);
  }
}

}  // namespace

void build_liquid_probe(const LiquidModel& model, const LiquidState& state, const Vec3& gravity,
                        LiquidWorkspace& ws) {
  const MacGrid& g = model.grid;
  label_cells(model, state, ws.flags, ws.fill, ws.count, &ws.moving);
  std::vector<Real>& p = ws.probe_pressure;
  std::vector<std::uint8_t>& known = ws.probe_known;
  p.assign(static_cast<std::size_t>(g.size), 0.0);
  known.assign(static_cast<std::size_t>(g.size), kUnknown);
  const int v = model.vertical_axis;
  // Gravity's component along the vertical axis and the stride one cell down (along gravity).
  const Real gv = std::abs(gravity[v]);
  const int down = gravity[v] <= 0 ? -g.stride(v) : g.stride(v);
  const Real hv = g.h[v];
  const Real applied = model.def.surface_pressure / model.def.density;
  // Full cells: the solve's pressure. Surface cells: zero (plus the applied pressure) at the
  // surface, which the fill puts (fill - 1/2) h above the centre of a cell filled from below.
  // The surface waves' pressure where they force the surface (16.17), felt through the column.
  auto wave_at = [&](int c) {
    return model.surface_waves.empty() ? 0.0
                                       : surface_wave_pressure(model, g.centre(c), state.time);
  };
  const bool two_way = model.two_way;
  if (two_way) set_free_surface_heights(model, gravity, ws);
  for (int c = 0; c < g.size; ++c) {
    const auto k = static_cast<std::size_t>(c);
    if (ws.flags[k] == CellFlag::full) {
      // Two-way: the hydrostatic pressure below the free surface over the cell (see the header);
      // the solve's where no surface is over it (a full tank).
      const Real eta = two_way ? ws.probe_eta[k] : kNoSurface;
      if (eta != kNoSurface) {
        const Real z = g.origin[v] + (index_along(g, v, c) - 0.5) * hv;
        p[k] = applied + wave_at(c) + gv * (gravity[v] <= 0 ? eta - z : z - eta);
      } else {
        p[k] = state.pressure[k];
      }
      known[k] = kKnown;
    } else if (ws.flags[k] == CellFlag::surface) {
      p[k] = applied + wave_at(c) + gv * (ws.fill[k] - 0.5) * hv;
      known[k] = kKnown;
    }
  }
  // Empty (and Inflow, Outflow) cells: continued upwards from the cell below, layer by layer
  // against gravity so each reads a cell already set (no sort, nothing allocated); with nothing
  // below, a cell's depth below the surface is negative: one cell's worth of negative pressure,
  // clamped to 0 when read.
  const int layers = g.n[v] + 2;
  const int a1 = (v + 1) % 3, a2 = (v + 2) % 3;
  for (int t = 0; t < layers; ++t) {
    int idx[3];
    idx[v] = down < 0 ? t : layers - 1 - t;
    for (idx[a2] = 0; idx[a2] < g.n[a2] + 2; ++idx[a2]) {
      for (idx[a1] = 0; idx[a1] < g.n[a1] + 2; ++idx[a1]) {
        const int c = g.index(idx[0], idx[1], idx[2]);
        const auto k = static_cast<std::size_t>(c);
        if (known[k] || ws.flags[k] == CellFlag::solid) continue;
        const int below = c + down;
        if (below >= 0 && below < g.size && known[static_cast<std::size_t>(below)]) {
          p[k] = p[static_cast<std::size_t>(below)] - gv * hv;
        } else {
          p[k] = -gv * hv;
        }
        known[k] = kKnown;
      }
    }
  }
  std::vector<int>& order = ws.probe_order;
  // Solid cells (walls, boxes, the ghost layer): the mean of their set neighbours' values
  // continued to their centre, so the pressure a body feels beside a wall or on a floor is the
  // liquid's, not the solid's zero. A second pass reaches the cells with only solid neighbours
  // (the ghost layer's edges) from the first pass's.
  for (int pass = 0; pass < 2; ++pass) {
    order.clear();
    for (int c = 0; c < g.size; ++c) {
      const auto k = static_cast<std::size_t>(c);
      if (known[k]) continue;
      Real sum = 0;
      int count = 0;
      for (int a = 0; a < 3; ++a) {
        for (int side = -1; side <= 1; side += 2) {
          const int nb = c + side * g.stride(a);
          if (nb < 0 || nb >= g.size || !known[static_cast<std::size_t>(nb)]) continue;
          // p grows along gravity: the neighbour's value plus g . (x_c - x_nb).
          sum += p[static_cast<std::size_t>(nb)] - gravity[a] * side * g.h[a];
          ++count;
        }
      }
      p[k] = count > 0 ? sum / count : -gv * hv;
      if (count > 0 || pass == 1) order.push_back(c);
    }
    for (int c : order) known[static_cast<std::size_t>(c)] = kKnown;
  }
  for (int a = 0; a < 3; ++a) ws.probe_velocity.u[a] = state.velocity.u[a];
}

bool in_liquid_domain(const LiquidModel& model, const Vec3& x) {
  for (int a = 0; a < 3; ++a) {
    if (a == model.thin_axis) continue;
    if (!(x[a] >= model.def.domain.min[a] && x[a] <= model.def.domain.max[a])) return false;
  }
  return true;
}

Real probe_pressure(const LiquidModel& model, const LiquidWorkspace& ws, const Vec3& x) {
  if (!in_liquid_domain(model, x)) return 0;
  const MacGrid& g = model.grid;
  int base[3];
  Real frac[3];
  for (int a = 0; a < 3; ++a) {
    if (a == model.thin_axis) {
      base[a] = 1;
      frac[a] = 0;
      continue;
    }
    // Centres at integers (centre of cell i at i - 1/2 cells from the origin); 0 and n + 1 are
    // the ghosts', which the continuation above has set.
    Real s = (x[a] - g.origin[a]) / g.h[a] + 0.5;
    s = std::clamp(s, 0.0, static_cast<Real>(g.n[a] + 1));
    int b = std::min(static_cast<int>(s), g.n[a]);
    base[a] = b;
    frac[a] = s - b;
  }
  const Real value = blend_trilinear(g, ws.probe_pressure, base, frac);
  return std::max(0.0, value);
}

Vec3 probe_velocity(const LiquidModel& model, const LiquidWorkspace& ws, const Vec3& x) {
  Vec3 y = x;
  if (model.thin_axis >= 0) {
    y[model.thin_axis] =
        0.5 * (model.def.domain.min[model.thin_axis] + model.def.domain.max[model.thin_axis]);
  }
  return interpolate_velocity(model.grid, ws.probe_velocity.u, y);
}

}  // namespace pbm
