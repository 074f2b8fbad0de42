// The boundary conditions of 16.2.2, set once per pass over the grid so that the updates of
// (16.2) and (16.5)-(16.9) apply "blindly" (homogeneous boundaries): obstacles' and walls'
// velocities, inflows', the free surface's (16.10), and the velocities just outside the liquid
// that advection and the markers read.
#pragma once

#include <cstdint>
#include <vector>

#include "liquid/liquid_model.h"
#include "liquid/moving_solids.h"

namespace pbm {

// Faces of Solid cells carry no flow across; faces of Inflow cells their inflow's velocity (one
// per inflow, as tracks set it, 16.6.1); the tangential velocity inside a wall mirrors the
// liquid's beside it: w0 = -w1 no-slip, w0 = w1 free-slip. A face of a cell a moving solid covers
// carries the solid's velocity (the mean of both sides' where both are covered): the liquid beside
// it moves with it across the face, free to slip along it.
void set_wall_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                         const std::vector<Vec3>& inflow_velocity, const MovingSolids& moving,
                         MacField& field);

// The faces of Surface cells open to Empty cells (16.10 and the text after it): an open face
// whose opposite face is closed takes the opposite's velocity (each dx/dx vanishes), and what
// divergence the cell's other axes still have is shared among those faces, so every Surface
// cell's D of (16.5) is zero: one open face is (16.10) itself. An axis open on both sides keeps
// the velocities the body force gave it.
void set_surface_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                            MacField& field);

// The extrapolation's scratch: a mark per face and the faces the last layer set.
struct ExtrapolationWork {
  std::vector<std::uint8_t> known;  // one per grid cell (face index)
  std::vector<int> frontier, added;
};

// Velocities of faces with no liquid on either side, from their neighbours', `layers` deep: what
// a marker just outside the liquid and a backtrace that leaves it read.
void extrapolate_velocities(const LiquidModel& model, const std::vector<CellFlag>& flags,
                            int layers, ExtrapolationWork& work, MacField& field);

// The divergence of (16.4) in cell c, sum_a (u_a+ - u_a-) / h_a [1/s] (minus D of (16.5)).
inline Real cell_divergence(const MacGrid& g, const MacField& f, int c) {
  const auto s = static_cast<std::size_t>(c);
  return (f.u[0][s] - f.u[0][s - static_cast<std::size_t>(g.sx)]) / g.h.x() +
         (f.u[1][s] - f.u[1][s - static_cast<std::size_t>(g.sy)]) / g.h.y() +
         (f.u[2][s] - f.u[2][s - static_cast<std::size_t>(g.sz)]) / g.h.z();
}

}  // namespace pbm
