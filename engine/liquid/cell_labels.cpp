#include "liquid/cell_labels.h"

#include <algorithm>

#include "liquid/moving_solids.h"
#include "liquid/surface_chains.h"

namespace pbm {

ColumnAxes column_axes(const LiquidModel& model) {
  ColumnAxes axes;
  axes.v = model.vertical_axis;
  axes.h0 = axes.v == 0 ? 1 : 0;
  axes.h1 = axes.v == 2 ? 1 : 2;
  return axes;
}

int column_count(const LiquidModel& model) {
  const ColumnAxes axes = column_axes(model);
  return model.grid.n[axes.h0] * model.grid.n[axes.h1];
}

namespace {

// The height field's labels: a cell is liquid where the surface is above its bottom; the fill
// is the part of the cell below the surface.
void label_from_height(const LiquidModel& model, const LiquidState& state,
                       std::vector<CellFlag>& flags, std::vector<Real>& fill) {
  const MacGrid& g = model.grid;
  const ColumnAxes axes = column_axes(model);
  const Real hv = g.h[axes.v];
  for (int i1 = 1; i1 <= g.n[axes.h1]; ++i1) {
    for (int i0 = 1; i0 <= g.n[axes.h0]; ++i0) {
      const Real height =
          state.height[static_cast<std::size_t>((i0 - 1) + g.n[axes.h0] * (i1 - 1))];
      for (int iv = 1; iv <= g.n[axes.v]; ++iv) {
        int ijk[3];
        ijk[axes.h0] = i0;
        ijk[axes.h1] = i1;
        ijk[axes.v] = iv;
        const auto c = static_cast<std::size_t>(g.index(ijk[0], ijk[1], ijk[2]));
        if (flags[c] != CellFlag::empty) continue;
        const Real bottom = g.origin[axes.v] + (iv - 1) * hv;
        if (height > bottom) {
          flags[c] = CellFlag::full;
          fill[c] = std::min(1.0, (height - bottom) / hv);
        }
      }
    }
  }
}

}  // namespace

void label_cells(const LiquidModel& model, const LiquidState& state, std::vector<CellFlag>& flags,
                 std::vector<Real>& fill, std::vector<int>& count, const MovingSolids* moving) {
  const MacGrid& g = model.grid;
  flags = model.fixed;  // same size: no allocation
  if (moving) {
    for (int c : moving->cells) flags[static_cast<std::size_t>(c)] = CellFlag::solid;
  }
  std::fill(fill.begin(), fill.end(), 0.0);
  std::fill(count.begin(), count.end(), 0);
  if (model.def.surface == SurfaceMethod::height_field) {
    label_from_height(model, state, flags, fill);
  } else if (model.def.surface == SurfaceMethod::chains) {
    label_from_chains(model, state.chain, state.chain_next, flags, fill, count);
  } else {
    for (const Vec3& x : state.markers) {
      const Eigen::Vector3i c = g.cell_of(x);
      if (!g.interior(c.x(), c.y(), c.z())) continue;
      ++count[static_cast<std::size_t>(g.index(c.x(), c.y(), c.z()))];
    }
    const Real per_cell = model.markers_per_cell;
    for (int c = 0; c < g.size; ++c) {
      const auto s = static_cast<std::size_t>(c);
      if (flags[s] != CellFlag::empty || count[s] == 0) continue;
      flags[s] = CellFlag::full;
      fill[s] = std::min(1.0, count[s] / per_cell);
    }
  }
  // A liquid cell next to an Empty one is a Surface cell; the others are Full and whole.
  const int strides[3] = {g.sx, g.sy, g.sz};
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        const auto s = static_cast<std::size_t>(c);
        if (flags[s] != CellFlag::full) continue;
        bool open = false;
        for (int stride : strides) {
          open = open || flags[static_cast<std::size_t>(c - stride)] == CellFlag::empty ||
                 flags[static_cast<std::size_t>(c + stride)] == CellFlag::empty;
        }
        if (open) {
          flags[s] = CellFlag::surface;
        } else if (model.def.surface != SurfaceMethod::chains) {
          fill[s] = 1;  // chains' cells keep the exact part of them the liquid fills
        }
      }
    }
  }
}

Real liquid_volume(const LiquidModel& model, const std::vector<CellFlag>& flags,
                   const std::vector<Real>& fill) {
  Real cells = 0;
  for (std::size_t c = 0; c < flags.size(); ++c) {
    if (is_liquid(flags[c])) cells += fill[c];
  }
  return cells * model.grid.cell_volume();
}

}  // namespace pbm
