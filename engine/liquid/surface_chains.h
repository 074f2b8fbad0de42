// Free-surface marker chains (16.3.2), 2D grids only: the liquid's boundary as closed loops of
// massless markers, each linked to the next with the liquid on its left in the grid's plane
// (ChainPlane: its first axis to the right, its second up), carried by the flow with the
// interpolation of fig. 16.3. Kept even by the book's rules: a link longer than the spacing gets
// markers on it, and two markers too close are both deleted and their neighbours linked; two
// linked markers close together are a link shrunk away, two unlinked ones facing each other are
// two surfaces meeting, and crossing their chains over there joins the surfaces (a drop into its
// pool) or pinches a sheet too thin to hold off (the chains' topology changes, never their
// orientation). Cells are labelled by the book's region growing (fig. 16.5), each grown region
// decided by the area the chains enclose in it, computed exactly in every cell: so an air pocket
// the surface's cells seal off stays air, where the book's alternation of Empty and Full regions
// would fill it.
#pragma once

#include <cstdint>
#include <vector>

#include "liquid/liquid_model.h"

namespace pbm {

// The grid's plane: axes a0 (right) and a1 (up) of the counter-clockwise loops.
struct ChainPlane {
  int a0 = 0, a1 = 2, thin = 1;
};
ChainPlane chain_plane(const LiquidModel& model);

// The markers' spacing along a chain [m]: the plane's smaller cell over markers_per_axis. A link
// longer than this is split; linked markers closer than kChainMergeFraction of it are deleted;
// unlinked ones facing each other closer than kChainJoinFraction of it cross over.
Real chain_spacing(const LiquidModel& model);
inline constexpr Real kChainMergeFraction = 0.2;
inline constexpr Real kChainJoinFraction = 0.5;

// Markers a chain state may hold: a chain crossing every cell of the plane eight times at the
// spacing. Insertion stops there (the guard sees it as an overrun).
std::size_t chain_capacity(const LiquidModel& model);

// One counter-clockwise loop around each fluid region (clipped to the domain, a hair inside its
// walls so that every marker's cell is an interior one), at the spacing; the thin axis's
// coordinate at the slab's middle. next[m] is the marker after m on its loop.
void seed_chains(const LiquidModel& model, std::vector<Vec3>& points, std::vector<int>& next);

// Every marker moved by the midpoint rule through the field, held a hair inside the walls; a
// marker that would enter one of the scene's Solid cells stays where it was.
void advect_chains(const LiquidModel& model, const MacField& field, Real dt,
                   std::vector<Vec3>& points);

struct ChainRemeshStats {
  int inserted = 0;       // markers put on long links
  int deleted = 0;        // linked markers deleted in pairs as too close
  int joined = 0;         // crossings-over of two surfaces meeting (each deletes two markers)
  int loops_dropped = 0;  // loops left with fewer than three markers (liquid below resolution)
  bool full = false;      // insertion stopped at chain_capacity
};

// Scratch of remesh_chains (a workspace's: nothing in it outlives the call).
struct ChainScratch {
  std::vector<int> prev, bucket_head, bucket_next, order;
  std::vector<std::uint8_t> alive, visited;
  std::vector<Vec3> points;
  std::vector<int> next;
};

// The book's insertion and deletion rules and the surfaces' joins (above), then the loops
// renumbered in order of their first marker (deterministic: the same chains give the same
// arrays).
ChainRemeshStats remesh_chains(const LiquidModel& model, std::vector<Vec3>& points,
                               std::vector<int>& next, ChainScratch& scratch);

// The fraction of each cell of the plane the loops enclose, exactly (the signed area of the
// polygons clipped to the cell, by the column integral -oint clamp(y) dx): 0 or 1 away from the
// chains, in between where they cross. `fraction` is grid.size long.
void chain_cell_fractions(const LiquidModel& model, const std::vector<Vec3>& points,
                          const std::vector<int>& next, std::vector<Real>& fraction);

// Labels the free cells of `flags` (those still Empty: walls, solid boxes and moving solids are
// already set) as Full where the chains hold liquid, with fill its fraction; the caller makes
// those next to an Empty cell Surface. Cells a link crosses (`marks`, set to 1 there) take their
// own fraction; the others are grown into 4-connected regions (fig. 16.5) and each region is
// Full when the chains enclose most of it.
void label_from_chains(const LiquidModel& model, const std::vector<Vec3>& points,
                       const std::vector<int>& next, std::vector<CellFlag>& flags,
                       std::vector<Real>& fill, std::vector<int>& marks);

// The signed area the loops enclose in the plane [m^2] and its centroid (the thin axis's at the
// slab's middle).
Real chains_area(const LiquidModel& model, const std::vector<Vec3>& points,
                 const std::vector<int>& next, Vec3* centroid = nullptr);

// Loops in the chains.
int chain_loops(const std::vector<int>& next);

}  // namespace pbm
