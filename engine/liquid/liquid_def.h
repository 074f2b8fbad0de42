// A liquid of a scene (the "liquids[i]" section, scenes/README.md): the grid of ch. 16 over a box
// of the world, the liquid it starts with, its walls, sources and sinks, and the solver's knobs.
// Plain definitions with defaults; liquid/liquid_model.h compiles one into a LiquidModel.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

// The convective terms of the momentum update: the book's explicit finite differences of (16.2),
// the semi-Lagrangian backtrace of the velocity (unconditionally stable, more diffusive), or
// PIC/FLIP: the markers carry the velocity (their own, liquid/particle_transfer.h), the grid
// only adds gravity, viscosity and pressure (the low-dissipation choice of Houdini's and
// Blender's FLIP liquids; markers only).
enum class LiquidAdvection { book, semi_lagrangian, flip };
// The pressure solve: the book's cell-by-cell relaxation (16.5)-(16.9), or conjugate gradients on
// the same system preconditioned by incomplete Cholesky MIC(0) or by a multigrid V-cycle.
enum class PressureSolver { relaxation, mic_pcg, mgpcg };
// How the liquid's position is tracked (16.3): marker particles (16.3.1), a height field
// (16.3.3) for surfaces that do not overturn, or, in 2D, free-surface marker chains (16.3.2:
// closed loops of markers along the liquid's boundaries, liquid/surface_chains.h).
enum class SurfaceMethod { markers, height_field, chains };
// The walls of the domain (16.2.2): no-slip (tangential velocity zero at the wall) or free-slip (a
// plane of symmetry for the tangential motion).
enum class WallKind { free_slip, no_slip };
// How the liquid and the scene's solids act on each other: one_way, the book's assumption (16.4:
// bodies feel the liquid's pressure and drag; the liquid sees only its own solid boxes), or
// two_way, where bodies and obstacles are also Solid cells moving with them, so they displace the
// liquid and make waves (liquid/moving_solids.h).
enum class LiquidCoupling { one_way, two_way };

// An axis-aligned box of the world [m].
struct LiquidBoxDef {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
};

// Where the liquid starts, and how fast it moves there.
struct FluidRegionDef {
  LiquidBoxDef box;
  Vec3 velocity = Vec3::Zero();  // [m/s]
};

// Cells where liquid enters at a fixed velocity (16.2.2, "Inflow and Outflow") and markers are
// released at a rate.
struct InflowDef {
  LiquidBoxDef box;
  Vec3 velocity = Vec3::Zero();  // [m/s]
  Real markers_per_second = 0;   // 0: enough to keep the released liquid at the marker density
};

// A travelling wave forced by a pressure history on the free surface (16.6.2): the book's (16.17)
// p = A + B cos(C s - omega t) on every Surface cell, s the distance along `direction`, with C =
// pi / L (16.19) for a wavelength 2L. The book's B of (16.18) is not dimensionally a pressure;
// ours is the pressure whose resonant forcing (omega from the wave's dispersion, omega^2 = g C
// tanh(C D)) grows the wave to `amplitude` in `duration`: B = 2 rho g a / (omega T) (linear
// theory, liquid/liquid_model.cpp). After the forcing stops the wave runs on freely.
struct SurfaceWaveDef {
  Real amplitude = 0.02;           // a [m], reached at the end of the forcing
  Real wavelength = 1;             // 2L [m]
  Vec3 direction = Vec3::UnitX();  // across gravity: the way the wave travels
  Real depth = 0;                  // D [m], the mean depth; 0: the liquid's at the start
  Real start = 0;                  // [s]
  Real duration = 2;               // T [s], the forcing's time
};

// What the studio and `pbm render` draw of a marker liquid: its surface (a translucent mesh from
// a level set of the markers, liquid/liquid_surface_mesh.h), the markers as points, or both. A
// height field always draws its surface.
enum class LiquidDisplay { surface, markers, both };

// A cross-section of the grid the studio and `pbm render` draw in false colour with a colour bar
// (none, the pressure [Pa] or the speed [m/s] at the cells' centres), across the axis given at a
// fraction of the domain along it.
enum class LiquidSection { none, pressure, speed };
enum class SectionAxis { x, y, z };

struct LiquidDef {
  std::string name;
  LiquidBoxDef domain{Vec3::Zero(), Vec3::Ones()};  // the grid's extent [m]
  Eigen::Vector3i resolution{16, 16, 16};           // cells per axis; 1 on an axis: 2D
  std::vector<FluidRegionDef> fluid;                // where the liquid starts
  std::vector<LiquidBoxDef> solids;                 // boxes of Solid cells inside the domain
  std::vector<InflowDef> inflows;
  std::vector<LiquidBoxDef> outflows;  // cells the liquid leaves by at its natural rate
  Real density = 1000;                 // rho [kg/m^3], > 0
  Real viscosity = 1e-6;               // kinematic nu of (16.1) [m^2/s], >= 0
  // C_d of the quadratic drag on bodies in the liquid (sim/liquid_body_loads.h): about 0.5 for
  // a sphere, 1 for a cube face on.
  Real drag = 0.5;
  WallKind walls = WallKind::free_slip;
  LiquidCoupling coupling = LiquidCoupling::two_way;
  Real surface_pressure = 0;  // applied on Surface cells above the atmosphere's [Pa]
  std::vector<SurfaceWaveDef> surface_waves;  // travelling pressure waves on top of it
  LiquidAdvection advection = LiquidAdvection::semi_lagrangian;
  // advection flip: the FLIP share of each marker's velocity update (Zhu & Bridson 2005): 1, pure
  // FLIP (the grid's change added to the marker's own velocity: no dissipation, some noise);
  // 0, PIC (the grid's velocity taken: smooth, as diffusive as one interpolation per substep).
  Real flip_ratio = 0.95;
  PressureSolver solver = PressureSolver::mic_pcg;
  SurfaceMethod surface = SurfaceMethod::markers;
  LiquidDisplay display = LiquidDisplay::surface;
  LiquidSection section = LiquidSection::none;
  SectionAxis section_axis = SectionAxis::y;
  Real section_position = 0.5;  // in [0, 1] of the domain along section_axis
  Real cfl = 0.5;               // the CFL number (16.3) each substep keeps to, in (0, 1]
  Real relaxation = 1.7;        // beta_0 of (16.7), in [1, 2)
  Real tolerance = 1e-4;        // epsilon: every Full cell's |D| of (16.5) below it [1/s]
  // Or, when > 0, the solve's residual ||D - A dp||_2 below this fraction of ||D||_2.
  Real relative_tolerance = 0;
  int max_iterations = 1000;  // of a pressure solve
  // Substeps one advance may take (the World advances a liquid at least once a frame): a flow
  // whose CFL substeps shrink past it is unstable (the book's central differences at a high cell
  // Reynolds number), and the run stops with a message rather than crawling.
  int max_substeps = 500;
  int markers_per_axis = 2;  // markers per cell along each axis of the grid's plane
  // Surface cells' pressure placed at the surface inside the cell (its fill) rather than at the
  // cell's centre (the book's): the ghost-fluid boundary, exact for still water.
  bool ghost_fluid = true;
  // Markers packed denser than markers_per_axis^dims in a Full cell push apart, sparser ones draw
  // together: the solve's divergence target is this fraction of the density's excess per substep
  // (0: the book's div u = 0 exactly). Counters the slow loss of volume of markers advected
  // through a discrete field (tests/test_liquid_solver.cpp: 21% in a 4 s dam break at 2 x 2
  // markers a cell without it, under 1% at 0.2), at some cost in the waves' period (0.05 makes
  // the sloshing period's error grow under refinement). With chains: the share of the drift of
  // the area they enclose from their starting area restored per substep (a uniform divergence).
  Real volume_correction = 0;
  // Spray and foam (liquid/spray.h; markers only): spray leaves Surface cells whose liquid rises
  // faster than spray_speed [m/s] (0: no spray), spray_rate particles per such cell per second,
  // flying with the quadratic air drag k = spray_drag [1/m] (terminal speed sqrt(g / k)); foam
  // lasts foam_lifetime [s]. At most max_spray of each.
  Real spray_speed = 0;
  Real spray_rate = 200;
  Real spray_drag = 0.1;
  Real foam_lifetime = 2;
  int max_spray = 100000;
};

}  // namespace pbm
