#include "liquid/liquid_state.h"

#include <algorithm>
#include <cmath>

#include "core/bits.h"
#include "liquid/cell_labels.h"
#include "liquid/surface_chains.h"

namespace pbm {

namespace {

bool inside(const LiquidBoxDef& box, const Vec3& x) {
  return (x.array() >= box.min.array()).all() && (x.array() <= box.max.array()).all();
}

// Markers on a regular lattice of markers_per_axis per cell edge, in every free cell whose
// lattice points lie in a fluid region (16.3.1); the thin axis's at its middle.
void seed_markers(const LiquidModel& m, std::vector<Vec3>& markers) {
  const MacGrid& g = m.grid;
  const int k_axis = m.def.markers_per_axis;
  Eigen::Vector3i per = Eigen::Vector3i::Constant(k_axis);
  if (m.thin_axis >= 0) per[m.thin_axis] = 1;
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        if (m.fixed[static_cast<std::size_t>(g.index(i, j, k))] != CellFlag::empty) continue;
        const Vec3 corner =
            g.origin + Vec3((i - 1) * g.h.x(), (j - 1) * g.h.y(), (k - 1) * g.h.z());
        for (int c = 0; c < per.z(); ++c) {
          for (int b = 0; b < per.y(); ++b) {
            for (int a = 0; a < per.x(); ++a) {
              const Vec3 x =
                  corner + Vec3((a + 0.5) / per.x() * g.h.x(), (b + 0.5) / per.y() * g.h.y(),
                                (c + 0.5) / per.z() * g.h.z());
              for (const FluidRegionDef& region : m.def.fluid) {
                if (inside(region.box, x)) {
                  markers.push_back(x);
                  break;
                }
              }
            }
          }
        }
      }
    }
  }
}

void seed_height(const LiquidModel& m, std::vector<Real>& height) {
  const MacGrid& g = m.grid;
  const ColumnAxes axes = column_axes(m);
  const Real bottom = g.origin[axes.v];
  const Real top = bottom + g.n[axes.v] * g.h[axes.v];
  height.assign(static_cast<std::size_t>(column_count(m)), bottom);
  for (int i1 = 1; i1 <= g.n[axes.h1]; ++i1) {
    for (int i0 = 1; i0 <= g.n[axes.h0]; ++i0) {
      Vec3 x = g.centre(1, 1, 1);
      x[axes.h0] = g.origin[axes.h0] + (i0 - 0.5) * g.h[axes.h0];
      x[axes.h1] = g.origin[axes.h1] + (i1 - 0.5) * g.h[axes.h1];
      Real& h = height[static_cast<std::size_t>((i0 - 1) + g.n[axes.h0] * (i1 - 1))];
      for (const FluidRegionDef& region : m.def.fluid) {
        x[axes.v] = region.box.min[axes.v];
        if (!inside(region.box, x)) continue;
        h = std::max(h, std::clamp(region.box.max[axes.v], bottom, top));
      }
    }
  }
}

// Each face takes the velocity of the last fluid region its centre lies in.
void seed_velocity(const LiquidModel& m, MacField& field) {
  const MacGrid& g = m.grid;
  field.resize(g.size);
  for (int a = 0; a < 3; ++a) {
    for (int k = 0; k <= g.n.z() + 1; ++k) {
      for (int j = 0; j <= g.n.y() + 1; ++j) {
        for (int i = 0; i <= g.n.x() + 1; ++i) {
          Vec3 x = g.centre(i, j, k);
          x[a] += 0.5 * g.h[a];
          for (const FluidRegionDef& region : m.def.fluid) {
            if (inside(region.box, x))
              field.u[a][static_cast<std::size_t>(g.index(i, j, k))] = region.velocity[a];
          }
        }
      }
    }
  }
}

// The pressure of still liquid (16.5, step 2): the weight of the liquid above each cell down
// its column, a start the first solve refines.
void seed_pressure(const LiquidModel& m, const Vec3& gravity, LiquidState& s) {
  const MacGrid& g = m.grid;
  std::vector<CellFlag> flags(static_cast<std::size_t>(g.size));
  std::vector<Real> fill(static_cast<std::size_t>(g.size));
  std::vector<int> count(static_cast<std::size_t>(g.size));
  label_cells(m, s, flags, fill, count);
  const ColumnAxes axes = column_axes(m);
  const Real applied = m.def.surface_pressure / m.def.density;
  s.pressure.assign(static_cast<std::size_t>(g.size), applied);
  const Real gv = std::abs(gravity[axes.v]);
  const bool up = gravity[axes.v] <= 0;  // the top of a column is its last cell
  const Real hv = g.h[axes.v];
  for (int i1 = 1; i1 <= g.n[axes.h1]; ++i1) {
    for (int i0 = 1; i0 <= g.n[axes.h0]; ++i0) {
      constexpr Real kAbove = -1e300;
      Real depth = kAbove;  // of the cell's centre below the surface [m]
      for (int step = 0; step < g.n[axes.v]; ++step) {
        int ijk[3];
        ijk[axes.h0] = i0;
        ijk[axes.h1] = i1;
        ijk[axes.v] = up ? g.n[axes.v] - step : step + 1;
        const auto c = static_cast<std::size_t>(g.index(ijk[0], ijk[1], ijk[2]));
        if (!is_liquid(flags[c])) {
          depth = kAbove;
          continue;
        }
        // The surface cell's centre lies (fill - 1/2) h below the surface (the ghost-fluid
        // boundary of liquid/pressure_system.h); its own pressure is the applied one.
        depth = depth == kAbove ? (fill[c] - 0.5) * hv : depth + hv;
        s.pressure[c] = applied + gv * std::max(0.0, depth);
      }
    }
  }
}

}  // namespace

LiquidState initial_liquid_state(const LiquidModel& model, const Vec3& gravity) {
  LiquidState s;
  seed_velocity(model, s.velocity);
  if (model.def.surface == SurfaceMethod::height_field) {
    seed_height(model, s.height);
  } else if (model.def.surface == SurfaceMethod::chains) {
    seed_chains(model, s.chain, s.chain_next);
    // The seeded loops renumbered and their long links split as every substep leaves them.
    ChainScratch scratch;
    (void)remesh_chains(model, s.chain, s.chain_next, scratch);
    s.chain_area = chains_area(model, s.chain, s.chain_next);
  } else {
    seed_markers(model, s.markers);
    // Room for the inflows' markers up to twice a full grid's: releasing allocates nothing.
    s.markers.reserve(
        std::max(s.markers.size(), static_cast<std::size_t>(model.grid.interior_cells()) *
                                       static_cast<std::size_t>(model.markers_per_cell)));
    if (model.def.advection == LiquidAdvection::flip) {
      // The grid's starting velocity where each marker is.
      s.marker_velocity.reserve(s.markers.capacity());
      for (const Vec3& x : s.markers) {
        s.marker_velocity.push_back(interpolate_velocity(model.grid, s.velocity.u, x));
      }
    }
  }
  seed_pressure(model, gravity, s);
  s.released.assign(model.inflows.size(), 0.0);
  return s;
}

void hash_liquid_state(const LiquidState& s, std::uint64_t& h) {
  auto mix = [&h](const void* data, std::size_t n) { fnv1a_mix(h, data, n); };
  mix(&s.time, sizeof s.time);
  for (const auto& c : s.velocity.u) mix(c.data(), sizeof(Real) * c.size());
  mix(s.pressure.data(), sizeof(Real) * s.pressure.size());
  mix(s.markers.data(), sizeof(Vec3) * s.markers.size());
  mix(s.marker_velocity.data(), sizeof(Vec3) * s.marker_velocity.size());
  mix(s.chain.data(), sizeof(Vec3) * s.chain.size());
  mix(s.chain_next.data(), sizeof(int) * s.chain_next.size());
  mix(&s.chain_area, sizeof s.chain_area);
  mix(s.spray.data(), sizeof(Vec3) * s.spray.size());
  mix(s.spray_velocity.data(), sizeof(Vec3) * s.spray_velocity.size());
  mix(s.foam.data(), sizeof(Vec3) * s.foam.size());
  mix(s.foam_age.data(), sizeof(Real) * s.foam_age.size());
  mix(&s.spray_total, sizeof s.spray_total);
  mix(&s.spray_owed, sizeof s.spray_owed);
  mix(s.height.data(), sizeof(Real) * s.height.size());
  mix(s.released.data(), sizeof(Real) * s.released.size());
  mix(&s.released_total, sizeof s.released_total);
  mix(&s.next_step, sizeof s.next_step);
  mix(&s.overrun, sizeof s.overrun);
}

std::size_t liquid_state_bytes(const LiquidState& s) {
  std::size_t bytes = sizeof s;
  for (const auto& c : s.velocity.u) bytes += sizeof(Real) * c.size();
  return bytes + sizeof(Real) * (s.pressure.size() + s.height.size() + s.released.size()) +
         sizeof(Vec3) * (s.markers.size() + s.marker_velocity.size() + s.spray.size() +
                         s.spray_velocity.size() + s.foam.size()) +
         sizeof(Real) * s.foam_age.size() + sizeof(Vec3) * s.chain.size() +
         sizeof(int) * s.chain_next.size();
}

}  // namespace pbm
