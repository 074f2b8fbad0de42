// Step 6 of 16.5: the pressure that makes every Full cell's divergence vanish (16.4). Whatever
// the solver, the system is the one the book's relaxation (16.5)-(16.9) iterates on: a change dp
// of a Full cell's pressure moves each of its open faces by (dt / h_a) dp (16.8), so the cell's
// missing mass D (16.5) changes by -(A dp)_c with
//   (A dp)_c = sum over faces not shared with a Solid or Inflow cell of dt / h_a^2 s_f (dp_c -
//   dp_nb),
// dp_nb = 0 where nb is Surface, Empty or Outflow (their pressure is applied, 16.2.2). s_f is 1,
// or 1/theta on a face to a Surface cell whose liquid fills it to theta - 1/2 beyond the face (the
// ghost-fluid boundary: the applied pressure at the surface rather than at the cell's centre).
// Solving A dp = D leaves every Full cell divergence-free.
#pragma once

#include <vector>

#include "liquid/liquid_workspace.h"

namespace pbm {

struct PressureSolveStats {
  int iterations = 0;      // sweeps (relaxation) or conjugate-gradient iterations
  int unknowns = 0;        // Full cells
  Real divergence = 0;     // max |div u| over the Full cells after the solve [1/s]
  Real residual = 0;       // ||D - A dp||_2 / ||D||_2 at the end (0 when D is 0)
  bool converged = false;  // within the tolerance before max_iterations
};

struct PressureSolveOptions {
  Real tolerance = 1e-4;  // every Full cell's |D| below it [1/s] (the book's epsilon)
  Real relative = 0;      // or, when > 0, ||r||_2 <= relative ||D||_2 (the benchmark's criterion)
  int max_iterations = 1000;
};

// The diagonal of A, the faces' ghost-fluid scales and the list of Full cells, for this
// substep's labels (ws.flags, ws.fill). Returns whether some Full cell touches a Dirichlet cell
// (else A is singular: a closed box full of liquid, solved up to a constant).
bool build_pressure_system(const LiquidModel& model, Real dt, LiquidWorkspace& ws);

// Solves the system build_pressure_system made (`dirichlet` its result) with `solver`: changes the
// Full cells' faces in `field` and their pressures.
PressureSolveStats solve_pressure(const LiquidModel& model, PressureSolver solver, Real dt,
                                  bool dirichlet, const PressureSolveOptions& options,
                                  LiquidWorkspace& ws, MacField& field,
                                  std::vector<Real>& pressure);

// The largest |div u - target| over the Full cells [1/s] (the target is 0 without the volume
// correction).
Real max_full_divergence(const LiquidModel& model, const LiquidWorkspace& ws,
                         const MacField& field);

}  // namespace pbm
