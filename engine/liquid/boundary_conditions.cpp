#include "liquid/boundary_conditions.h"

#include <algorithm>

namespace pbm {

namespace {

// Calls visit(face index, cell below, cell above) for every face of axis a with both cells in
// the arrays.
template <typename Visit>
void for_each_face(const MacGrid& g, int a, Visit&& visit) {
  const int ea = g.stride(a);
  Eigen::Vector3i last = g.n + Eigen::Vector3i::Ones();
  last[a] = g.n[a];
  for (int k = 0; k <= last.z(); ++k) {
    for (int j = 0; j <= last.y(); ++j) {
      int f = g.index(0, j, k);
      for (int i = 0; i <= last.x(); ++i, ++f) visit(f, f, f + ea);
    }
  }
}

}  // namespace

void set_wall_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                         const std::vector<Vec3>& inflow_velocity, const MovingSolids& moving,
                         MacField& field) {
  const bool any_moving = !moving.cells.empty();
  const MacGrid& g = model.grid;
  for (int a = 0; a < 3; ++a) {
    std::vector<Real>& u = field.u[a];
    for_each_face(g, a, [&](int f, int lo, int hi) {
      const CellFlag fl = flags[static_cast<std::size_t>(lo)];
      const CellFlag fh = flags[static_cast<std::size_t>(hi)];
      if (fl == CellFlag::solid || fh == CellFlag::solid) {
        Real value = 0;
        if (any_moving) {
          const bool ml = moving.inside[static_cast<std::size_t>(lo)] != 0;
          const bool mh = moving.inside[static_cast<std::size_t>(hi)] != 0;
          if (ml && mh) {
            value = 0.5 * (moving.velocity[static_cast<std::size_t>(lo)][a] +
                           moving.velocity[static_cast<std::size_t>(hi)][a]);
          } else if (ml || mh) {
            value = moving.velocity[static_cast<std::size_t>(ml ? lo : hi)][a];
          }
        }
        u[static_cast<std::size_t>(f)] = value;
      } else if (fl == CellFlag::inflow || fh == CellFlag::inflow) {
        const int c = fl == CellFlag::inflow ? lo : hi;
        const int inflow = model.inflow_of[static_cast<std::size_t>(c)];
        u[static_cast<std::size_t>(f)] = inflow_velocity[static_cast<std::size_t>(inflow)][a];
      }
    });
    const Real sign = model.def.walls == WallKind::no_slip ? -1.0 : 1.0;
    for (const LiquidModel::MirrorFace& m : model.mirror_faces[a]) {
      Real sum = 0;
      int n = 0;
      for (int nb : m.neighbours) {
        if (nb < 0) break;
        sum += u[static_cast<std::size_t>(nb)];
        ++n;
      }
      u[static_cast<std::size_t>(m.face)] = sign * sum / n;
    }
  }
}

void set_surface_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                            MacField& field) {
  const MacGrid& g = model.grid;
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (flags[static_cast<std::size_t>(c)] != CellFlag::surface) continue;
        // The open faces whose opposite is closed: (face index, axis, +1 for the + face).
        int open_face[3], open_axis[3], open_sign[3];
        int n_open = 0;
        for (int a = 0; a < 3; ++a) {
          const int e = g.stride(a);
          const bool minus = flags[static_cast<std::size_t>(c - e)] == CellFlag::empty;
          const bool plus = flags[static_cast<std::size_t>(c + e)] == CellFlag::empty;
          if (minus == plus) continue;  // both closed, or both open (the body force's)
          std::vector<Real>& u = field.u[a];
          const auto fp = static_cast<std::size_t>(c), fm = static_cast<std::size_t>(c - e);
          if (plus) {
            u[fp] = u[fm];
          } else {
            u[fm] = u[fp];
          }
          open_face[n_open] = plus ? c : c - e;
          open_axis[n_open] = a;
          open_sign[n_open] = plus ? 1 : -1;
          ++n_open;
        }
        if (n_open == 0) continue;
        // What the other axes leave is shared: face a+ moves by -div h_a / n, a- by +div h_a / n.
        const Real div = cell_divergence(g, field, c);
        for (int o = 0; o < n_open; ++o) {
          field.u[open_axis[o]][static_cast<std::size_t>(open_face[o])] -=
              open_sign[o] * div * g.h[open_axis[o]] / n_open;
        }
      }
    }
  }
}

void extrapolate_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                            int layers, ExtrapolationWork& work, MacField& field) {
  const MacGrid& g = model.grid;
  // known: 0 unknown, 1 known before this layer (the only faces a layer reads, so the order in
  // which a layer visits its faces cannot change a value), 2 set in this layer.
  std::vector<std::uint8_t>& known = work.known;
  constexpr std::uint8_t kKnown = 1, kThisLayer = 2;
  const int stride[3] = {g.sx, g.sy, g.sz};
  // The average of a face's known neighbours along every axis (it has one: it is reached from
  // one, or the first layer's scan found one).
  auto fill = [&](std::vector<Real>& u, int f) {
    Real sum = 0;
    int n = 0;
    for (int b = 0; b < 3; ++b) {
      for (int side = -1; side <= 1; side += 2) {
        const auto nb = static_cast<std::size_t>(f + side * stride[b]);
        if (known[nb] == kKnown) {
          sum += u[nb];
          ++n;
        }
      }
    }
    if (n == 0) return false;
    u[static_cast<std::size_t>(f)] = sum / n;
    known[static_cast<std::size_t>(f)] = kThisLayer;
    return true;
  };
  for (int a = 0; a < 3; ++a) {
    std::vector<Real>& u = field.u[a];
    std::fill(known.begin(), known.end(), std::uint8_t{0});
    for_each_face(g, a, [&](int f, int lo, int hi) {
      const CellFlag fl = flags[static_cast<std::size_t>(lo)];
      const CellFlag fh = flags[static_cast<std::size_t>(hi)];
      known[static_cast<std::size_t>(f)] =
          is_liquid(fl) || is_liquid(fh) || fixes_velocity(fl) || fixes_velocity(fh);
    });
    // The first layer scans the interior's faces; each later one only the unknown neighbours of
    // the faces the layer before it set (two whole-grid scans and copies per axis were 10% of a
    // FLIP dam break's time, `perf record pbm simulate scenes/dam-break.json`).
    work.frontier.clear();
    for (int layer = 0; layer < layers; ++layer) {
      work.added.clear();
      if (layer == 0) {
        for (int k = 1; k <= g.n.z(); ++k) {
          for (int j = 1; j <= g.n.y(); ++j) {
            for (int i = 1, f = g.index(1, j, k); i <= g.n.x(); ++i, ++f) {
              if (known[static_cast<std::size_t>(f)] == 0 && fill(u, f)) work.added.push_back(f);
            }
          }
        }
      } else {
        for (int f : work.frontier) {
          const int at[3] = {f % g.sy, (f / g.sy) % (g.n.y() + 2), f / g.sz};
          for (int b = 0; b < 3; ++b) {
            for (int side = -1; side <= 1; side += 2) {
              const int c = at[b] + side;
              if (c < 1 || c > g.n[b]) continue;  // the interior's faces, as the first layer's
              const int nb = f + side * stride[b];
              if (known[static_cast<std::size_t>(nb)] == 0 && fill(u, nb)) {
                work.added.push_back(nb);
              }
            }
          }
        }
      }
      for (int f : work.added) known[static_cast<std::size_t>(f)] = kKnown;
      work.frontier.swap(work.added);
    }
  }
}

}  // namespace pbm
