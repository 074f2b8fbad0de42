#include "liquid/liquid_model.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace pbm {

namespace {

bool inside(const LiquidBoxDef& box, const Vec3& x) {
  return (x.array() >= box.min.array()).all() && (x.array() <= box.max.array()).all();
}

// Labels the interior cells whose centre lies in `box`; returns how many.
int mark_cells(const MacGrid& grid, const LiquidBoxDef& box, CellFlag flag,
               std::vector<CellFlag>& fixed, std::vector<int>* cells) {
  int marked = 0;
  for (int k = 1; k <= grid.n.z(); ++k) {
    for (int j = 1; j <= grid.n.y(); ++j) {
      for (int i = 1; i <= grid.n.x(); ++i) {
        if (!inside(box, grid.centre(i, j, k))) continue;
        const int c = grid.index(i, j, k);
        fixed[static_cast<std::size_t>(c)] = flag;
        if (cells) cells->push_back(c);
        ++marked;
      }
    }
  }
  return marked;
}

// The solid-solid faces a liquid face's stencil reads across a wall (16.2.2).
void find_mirror_faces(LiquidModel& m) {
  const MacGrid& g = m.grid;
  auto solid = [&](int c) { return m.fixed[static_cast<std::size_t>(c)] == CellFlag::solid; };
  for (int a = 0; a < 3; ++a) {
    const int ea = g.stride(a);
    Eigen::Vector3i last = g.n + Eigen::Vector3i::Ones();
    last[a] = g.n[a];  // faces 0..n along a
    for (int k = 0; k <= last.z(); ++k) {
      for (int j = 0; j <= last.y(); ++j) {
        for (int i = 0; i <= last.x(); ++i) {
          const int f = g.index(i, j, k);
          if (!solid(f) || !solid(f + ea)) continue;
          LiquidModel::MirrorFace mirror{.face = f};
          int found = 0;
          const int ijk[3] = {i, j, k};
          for (int b = 0; b < 3; ++b) {
            if (b == a) continue;
            for (int side = -1; side <= 1; side += 2) {
              const int at = ijk[b] + side;
              if (at < 0 || at > g.n[b] + 1) continue;
              const int nb = f + side * g.stride(b);
              if (!solid(nb) || !solid(nb + ea)) mirror.neighbours[found++] = nb;
            }
          }
          if (found > 0) m.mirror_faces[a].push_back(mirror);
        }
      }
    }
  }
}

// The liquid's mean depth at the start: its regions' volume inside the domain over the domain's
// floor (across `vertical`).
Real initial_depth(const LiquidDef& def, int vertical) {
  const Vec3 extent = def.domain.max - def.domain.min;
  Real volume = 0;
  for (const FluidRegionDef& region : def.fluid) {
    const Vec3 lo = region.box.min.cwiseMax(def.domain.min);
    const Vec3 hi = region.box.max.cwiseMin(def.domain.max);
    volume += (hi - lo).cwiseMax(0.0).prod();
  }
  return volume * extent[vertical] / extent.prod();
}

// Resonant forcing: a pressure B cos(k s - omega t) travelling at the wave's own phase speed
// grows the linear wave's amplitude as B omega t / (2 rho g) (from eta'' + omega^2 eta =
// -k tanh(k D) p / rho at the surface), so B / rho = 2 g a / (omega T) reaches a at t = T.
void compile_surface_waves(LiquidModel& m, const Vec3& gravity, const std::string& file,
                           const std::string& path) {
  const Real g = gravity.norm();
  for (std::size_t w = 0; w < m.def.surface_waves.size(); ++w) {
    const SurfaceWaveDef& def = m.def.surface_waves[w];
    const std::string at = path + ".surface_waves[" + std::to_string(w) + "]";
    if (g <= 0) throw Error(file, at, "a surface wave needs gravity to restore it");
    Vec3 n = def.direction - def.direction.dot(gravity) / (g * g) * gravity;
    if (m.thin_axis >= 0) n[m.thin_axis] = 0;  // a 2D liquid's waves run in its plane
    if (!(n.norm() > 1e-9 * std::max(1.0, def.direction.norm()))) {
      throw Error(file, at + ".direction", "must have a part across gravity in the liquid's plane");
    }
    const Real depth = def.depth > 0 ? def.depth : initial_depth(m.def, m.vertical_axis);
    if (!(depth > 0)) throw Error(file, at + ".depth", "the liquid starts with no depth");
    const Real k = 2 * M_PI / def.wavelength;  // C = pi / L of (16.19), 2L the wavelength
    const Real omega = std::sqrt(g * k * std::tanh(k * depth));
    m.surface_waves.push_back({.wave_vector = k * n.normalized(),
                               .omega = omega,
                               .pressure = 2 * g * def.amplitude / (omega * def.duration),
                               .start = def.start,
                               .end = def.start + def.duration});
  }
}

// Chains (16.3.2) are closed loops in a plane, one around each fluid region, moved by the flow:
// what would add or take liquid anywhere else, or a third dimension, they cannot follow.
void check_chains(const LiquidDef& def, const std::string& file, const std::string& path) {
  int thin = -1, thin_axes = 0;
  for (int a = 0; a < 3; ++a) {
    if (def.resolution[a] == 1) {
      thin = a;
      ++thin_axes;
    }
  }
  if (thin_axes != 1) {
    throw Error(file, path + ".surface",
                "chains: the book's free-surface chains are 2D, a resolution of 1 along exactly "
                "one axis; a 3D liquid takes \"markers\"");
  }
  if (!def.inflows.empty()) {
    throw Error(file, path + ".inflows",
                "chains cannot grow a loop from an inflow; surface \"markers\" releases liquid");
  }
  if (!def.outflows.empty()) {
    throw Error(file, path + ".outflows",
                "chains cannot open a loop at an outflow; surface \"markers\" drains liquid");
  }
  if (def.spray_speed > 0) {
    throw Error(file, path + ".spray_speed", "spray leaves marker particles (surface \"markers\")");
  }
  const int a0 = thin == 0 ? 1 : 0, a1 = thin == 2 ? 1 : 2;
  for (std::size_t t = 1; t < def.fluid.size(); ++t) {
    for (std::size_t s = 0; s < t; ++s) {
      const LiquidBoxDef& p = def.fluid[s].box;
      const LiquidBoxDef& q = def.fluid[t].box;
      const bool overlap = std::min(p.max[a0], q.max[a0]) > std::max(p.min[a0], q.min[a0]) &&
                           std::min(p.max[a1], q.max[a1]) > std::max(p.min[a1], q.min[a1]);
      if (overlap) {
        throw Error(file, path + ".fluid[" + std::to_string(t) + "]",
                    "overlaps fluid[" + std::to_string(s) +
                        "]: chains trace each region's boundary, so regions may touch but not "
                        "overlap");
      }
    }
  }
}

}  // namespace

Real surface_wave_pressure(const LiquidModel& model, const Vec3& x, Real t) {
  Real p = 0;
  for (const SurfaceWaveModel& wave : model.surface_waves) {
    if (t < wave.start || t >= wave.end) continue;
    p += wave.pressure * std::cos(wave.wave_vector.dot(x) - wave.omega * (t - wave.start));
  }
  return p;
}

LiquidModel build_liquid_model(const LiquidDef& def, const Vec3& gravity, const std::string& file,
                               int index) {
  const std::string path = "liquids[" + std::to_string(index) + "]";
  const long cells =
      static_cast<long>(def.resolution.x()) * def.resolution.y() * def.resolution.z();
  if ((def.resolution.array() < 1).any() || cells > kMaxLiquidCells) {
    throw Error(file, path + ".resolution",
                "a grid of " + std::to_string(cells) + " cells: must have 1 to " +
                    std::to_string(kMaxLiquidCells) + " cells, at least 1 per axis");
  }
  if (def.advection == LiquidAdvection::flip && def.surface != SurfaceMethod::markers) {
    throw Error(file, path + ".advection",
                "flip: the markers carry the velocity, and a height field has none (surface "
                "\"markers\")");
  }
  if (def.surface == SurfaceMethod::chains) check_chains(def, file, path);
  LiquidModel m;
  m.def = def;
  const Vec3 extent = def.domain.max - def.domain.min;
  m.grid.resize(def.resolution, extent.cwiseQuotient(def.resolution.cast<Real>()), def.domain.min);
  m.fixed.assign(static_cast<std::size_t>(m.grid.size), CellFlag::solid);
  for (int k = 1; k <= m.grid.n.z(); ++k) {
    for (int j = 1; j <= m.grid.n.y(); ++j) {
      for (int i = 1; i <= m.grid.n.x(); ++i) {
        m.fixed[static_cast<std::size_t>(m.grid.index(i, j, k))] = CellFlag::empty;
      }
    }
  }
  for (std::size_t s = 0; s < def.solids.size(); ++s) {
    mark_cells(m.grid, def.solids[s], CellFlag::solid, m.fixed, nullptr);
  }
  m.inflow_of.assign(static_cast<std::size_t>(m.grid.size), -1);
  for (std::size_t s = 0; s < def.inflows.size(); ++s) {
    InflowModel inflow{.cells = {},
                       .velocity = def.inflows[s].velocity,
                       .markers_per_second = def.inflows[s].markers_per_second,
                       .box = def.inflows[s].box};
    if (mark_cells(m.grid, inflow.box, CellFlag::inflow, m.fixed, &inflow.cells) == 0) {
      throw Error(file, path + ".inflows[" + std::to_string(s) + "]",
                  "covers no cell's centre of the grid");
    }
    m.inflows.push_back(std::move(inflow));
  }
  for (std::size_t s = 0; s < def.outflows.size(); ++s) {
    if (mark_cells(m.grid, def.outflows[s], CellFlag::outflow, m.fixed, nullptr) == 0) {
      throw Error(file, path + ".outflows[" + std::to_string(s) + "]",
                  "covers no cell's centre of the grid");
    }
  }
  // A later box wins a cell; the inflows' lists keep only the cells still theirs.
  for (std::size_t s = 0; s < m.inflows.size(); ++s) {
    auto& list = m.inflows[s].cells;
    std::erase_if(list, [&](int c) {
      return m.fixed[static_cast<std::size_t>(c)] != CellFlag::inflow ||
             m.inflow_of[static_cast<std::size_t>(c)] >= 0;
    });
    for (int c : list) m.inflow_of[static_cast<std::size_t>(c)] = static_cast<int>(s);
    if (list.empty()) {
      throw Error(file, path + ".inflows[" + std::to_string(s) + "]",
                  "every cell of it is another inflow's or an outflow's");
    }
    // Markers are released over the cells it holds.
    LiquidBoxDef bounds{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
    for (int c : list) {
      const int i = c % m.grid.sy, j = (c / m.grid.sy) % (m.grid.n.y() + 2), k = c / m.grid.sz;
      const Vec3 lo = m.grid.centre(i, j, k) - 0.5 * m.grid.h;
      bounds.min = bounds.min.cwiseMin(lo);
      bounds.max = bounds.max.cwiseMax(lo + m.grid.h);
    }
    m.inflows[s].box = bounds;
  }
  // Inflow boxes released into the domain only; the thin axis's markers at its middle.
  m.thin_axis = -1;
  for (int a = 0; a < 3; ++a) {
    if (m.grid.n[a] == 1 && m.thin_axis < 0) m.thin_axis = a;
  }
  m.markers_per_cell = 1;
  for (int a = 0; a < 3; ++a) m.markers_per_cell *= a == m.thin_axis ? 1 : def.markers_per_axis;
  // Chains are one surface each, like a height field's: a body cannot push them (coupled one
  // way).
  m.two_way = def.coupling == LiquidCoupling::two_way && def.surface == SurfaceMethod::markers;
  m.vertical_axis = 2;
  if (gravity.squaredNorm() > 0) gravity.cwiseAbs().maxCoeff(&m.vertical_axis);
  find_mirror_faces(m);
  compile_surface_waves(m, gravity, file, path);
  return m;
}

}  // namespace pbm
