// The solvers of the pressure system of liquid/pressure_system.h, after build_pressure_system.
#pragma once

#include "liquid/pressure_system.h"

namespace pbm {

// The book's relaxation (16.5)-(16.9): cell by cell, the missing mass D (16.5), the pressure
// change dp = beta D (16.6) with beta = beta_0 / (the cell's diagonal of A), which is (16.7)'s
// beta_0 / (2 dt sum 1/h^2) away from walls and keeps the relaxation at beta_0 beside them; the
// faces moved by (16.8) and the pressure by (16.9); sweeps until every |D| < epsilon.
void relax_pressure(const LiquidModel& model, Real dt, const PressureSolveOptions& options,
                    LiquidWorkspace& ws, MacField& field, std::vector<Real>& pressure,
                    PressureSolveStats& stats);

// Conjugate gradients on A dp = D preconditioned by MIC(0) (Bridson, "Fluid Simulation for
// Computer Graphics", sec. 5.3.4) or by a multigrid V-cycle (McAdams et al. 2010); then the
// faces and pressures moved by dp as (16.8), (16.9) would.
void conjugate_gradient_pressure(const LiquidModel& model, PressureSolver solver, Real dt,
                                 bool dirichlet, const PressureSolveOptions& options,
                                 LiquidWorkspace& ws, MacField& field, std::vector<Real>& pressure,
                                 PressureSolveStats& stats);

}  // namespace pbm
