// A liquid compiled for the step (docs/architecture.md, "Model"): its grid, the cells the scene
// fixes (walls and solid boxes, inflows, outflows) and its knobs. Constant while time runs.
#pragma once

#include <string>
#include <vector>

#include "liquid/liquid_def.h"
#include "liquid/mac_grid.h"

namespace pbm {

struct InflowModel {
  std::vector<int> cells;  // grid indices of its Inflow cells
  Vec3 velocity = Vec3::Zero();
  Real markers_per_second = 0;  // markers released, spread over its cells
  LiquidBoxDef box;             // where they are released (clipped to the domain)
};

// A surface wave of the scene compiled (liquid_def.h, SurfaceWaveDef): the kinematic pressure
// amplitude B / rho of (16.17) [m^2/s^2], its wave vector C n (16.19) and frequency.
struct SurfaceWaveModel {
  Vec3 wave_vector = Vec3::Zero();  // [1/m], across gravity
  Real omega = 0;                   // [rad/s], from omega^2 = g k tanh(k D)
  Real pressure = 0;                // B / rho [m^2/s^2]
  Real start = 0, end = 0;          // [s]
};

struct LiquidModel {
  LiquidDef def;
  MacGrid grid;
  // Solid, Inflow and Outflow where the scene puts them (the ghost layer is Solid); Empty
  // elsewhere: the liquid's own cells are labelled every substep (16.3).
  std::vector<CellFlag> fixed;
  // The Inflow index of each Inflow cell (-1 elsewhere).
  std::vector<int> inflow_of;
  std::vector<InflowModel> inflows;
  std::vector<SurfaceWaveModel> surface_waves;
  int thin_axis = -1;     // the axis of one cell in a 2D grid, -1 in 3D
  int vertical_axis = 2;  // the axis most against gravity (the height field's columns)
  int markers_per_cell = 8;
  // Bodies and obstacles displace this liquid (liquid/moving_solids.h): coupling two_way with
  // marker particles. A height field's one surface per column cannot pass around a body that
  // pierces it (measured: a ball sinking through one lost 58% of the tank's volume), so a
  // height-field liquid is coupled one way.
  bool two_way = false;
  // Solid-solid faces next to the liquid's faces: their velocity is the mirror of their
  // neighbours' (16.2.2: w0 = -w1 no-slip, w0 = w1 free-slip). Per axis: the face and up to four
  // neighbours across the other axes (-1: none).
  struct MirrorFace {
    int face = 0;
    int neighbours[4] = {-1, -1, -1, -1};
  };
  std::vector<MirrorFace> mirror_faces[3];
};

// Throws pbm::Error(file, "liquids[index]...") when the liquid cannot be compiled (a grid over
// the cell limit).
LiquidModel build_liquid_model(const LiquidDef& def, const Vec3& gravity, const std::string& file,
                               int index);

// The surface waves' kinematic pressure [m^2/s^2] at x and time t (0 where none is forcing).
Real surface_wave_pressure(const LiquidModel& model, const Vec3& x, Real t);

// The most cells a grid may have: a 256^3 grid's arrays are about 1 GB (scenes/README.md,
// "Limits").
inline constexpr long kMaxLiquidCells = 256L * 256L * 256L;

}  // namespace pbm
