// Two-way coupling, beyond the book (16.4 assumes bodies too small to disturb the flow): the
// scene's bodies and obstacles are Solid cells of the grid that move with them (16.2.2's
// obstacle cells, given the velocity of the solid at each): the faces between such a cell and the
// liquid carry the solid's velocity, so the pressure solve pushes the liquid aside as a body
// enters it and draws it in behind, and the water level rises by what a body displaces
// (tests/test_liquid_two_way.cpp). Rebuilt every substep from the solids' positions then, never
// kept (docs/architecture.md, "Determinism").
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "liquid/liquid_model.h"

namespace pbm {

// A closed surface, counter-clockwise from outside, and its vertices' velocities [m], [m/s].
struct SolidSurface {
  std::span<const Vec3> x;
  std::span<const Vec3> x_dot;
  std::span<const std::array<int, 3>> triangles;
};

// A cell a solid covers and the solid's velocity at its centre.
struct SolidCell {
  int cell = 0;
  Vec3 velocity = Vec3::Zero();
};

// The cells moving solids cover this substep (never a cell the scene fixes: walls, the liquid's
// own solid boxes, inflows and outflows keep their own conditions).
struct MovingSolids {
  std::vector<std::uint8_t> inside;  // per cell: 1 where a moving solid covers the centre
  std::vector<Vec3> velocity;        // the solid's velocity there [m/s]
  std::vector<int> cells;            // the covered cells, in the order marked
  // Scratch of the voxelization: where each column's line crosses a surface.
  struct Crossing {
    int column = 0;
    Real at = 0;   // the coordinate along the scan axis [m]
    int step = 0;  // +1 entering the solid along the axis, -1 leaving it
    Vec3 velocity = Vec3::Zero();
    bool operator<(const Crossing& o) const {
      return column != o.column ? column < o.column : at != o.at ? at < o.at : step < o.step;
    }
  };
  std::vector<Crossing> crossings;
};

void size_moving_solids(const LiquidModel& model, MovingSolids& solids);
void clear_moving_solids(MovingSolids& solids);

// Marks cell c (an interior cell the scene leaves Empty) as covered, moving at `velocity`; a cell
// already covered keeps the first solid's.
void mark_solid_cell(const LiquidModel& model, int c, const Vec3& velocity, MovingSolids& solids);

// Marks the cells whose centres the surface encloses, at its vertices moved by dt at their
// velocities (x + dt x_dot: the liquid's substeps fall inside the step that placed the solid).
// Scan lines along the vertical axis through the columns' centres (a 2D grid's through its
// slab's middle); the winding of the crossings decides inside, and each covered cell's velocity
// is the crossings' velocities blended linearly along the line (exact for a rigid motion).
void voxelize_surface(const LiquidModel& model, const SolidSurface& surface, Real dt,
                      MovingSolids& solids);

// Markers inside covered cells moved to the first cell no solid covers ahead of the solid, along
// the main axis of its velocity there (just past that cell's face): the liquid a solid sweeps is
// pushed ahead of it, not carried inside it. A solid at rest pushes them up or down its column,
// whichever is nearer. Returns how many moved.
int push_markers_out(const LiquidModel& model, const MovingSolids& solids,
                     std::vector<Vec3>& markers);

}  // namespace pbm
