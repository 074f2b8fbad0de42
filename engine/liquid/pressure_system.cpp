#include "liquid/pressure_system.h"

#include <algorithm>
#include <cmath>

#include "liquid/boundary_conditions.h"
#include "liquid/pressure_solvers.h"

namespace pbm {

bool build_pressure_system(const LiquidModel& model, Real dt, LiquidWorkspace& ws) {
  const MacGrid& g = model.grid;
  for (auto& scale : ws.face_scale) std::fill(scale.begin(), scale.end(), 1.0);
  ws.cell_of_row.clear();
  bool dirichlet = false;
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (ws.flags[static_cast<std::size_t>(c)] != CellFlag::full) continue;
        ws.cell_of_row.push_back(c);
        Real diag = 0;
        for (int a = 0; a < 3; ++a) {
          const int e = g.stride(a);
          const Real w = dt / (g.h[a] * g.h[a]);
          for (int side = -1; side <= 1; side += 2) {
            const int nb = c + side * e;
            const CellFlag f = ws.flags[static_cast<std::size_t>(nb)];
            if (fixes_velocity(f)) continue;
            Real s = 1;
            if (f == CellFlag::surface && model.def.ghost_fluid) {
              const Real theta = std::clamp(0.5 + ws.fill[static_cast<std::size_t>(nb)], 0.5, 1.5);
              s = 1 / theta;
              ws.face_scale[a][static_cast<std::size_t>(side > 0 ? c : nb)] = s;
            }
            if (f != CellFlag::full) dirichlet = true;
            diag += w * s;
          }
        }
        ws.diag[static_cast<std::size_t>(c)] = diag;
        Real target = 0;
        if (model.def.surface == SurfaceMethod::markers && model.def.volume_correction > 0) {
          const Real excess =
              ws.count[static_cast<std::size_t>(c)] / static_cast<Real>(model.markers_per_cell) - 1;
          target = model.def.volume_correction / dt * std::clamp(excess, -1.0, 1.0);
        } else if (model.def.surface == SurfaceMethod::chains) {
          target = ws.chain_divergence;
        }
        ws.target[static_cast<std::size_t>(c)] = target;
      }
    }
  }
  return dirichlet;
}

Real max_full_divergence(const LiquidModel& model, const LiquidWorkspace& ws,
                         const MacField& field) {
  Real worst = 0;
  for (int c : ws.cell_of_row) {
    worst = std::max(worst, std::abs(cell_divergence(model.grid, field, c) -
                                     ws.target[static_cast<std::size_t>(c)]));
  }
  return worst;
}

PressureSolveStats solve_pressure(const LiquidModel& model, PressureSolver solver, Real dt,
                                  bool dirichlet, const PressureSolveOptions& options,
                                  LiquidWorkspace& ws, MacField& field,
                                  std::vector<Real>& pressure) {
  PressureSolveStats stats;
  stats.unknowns = static_cast<int>(ws.cell_of_row.size());
  if (stats.unknowns == 0) {
    stats.converged = true;
    return stats;
  }
  if (solver == PressureSolver::relaxation) {
    relax_pressure(model, dt, options, ws, field, pressure, stats);
  } else {
    conjugate_gradient_pressure(model, solver, dt, dirichlet, options, ws, field, pressure, stats);
  }
  stats.divergence = max_full_divergence(model, ws, field);
  return stats;
}

}  // namespace pbm
