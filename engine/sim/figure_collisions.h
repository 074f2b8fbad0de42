// Collisions between the figures' segments (sec. 15.3's detection): of one figure with each other
// and between figures. A sweep along x over the segments' bounding boxes picks the candidate
// pairs, the figures' filters drop those that may not collide (CompiledFigure::self_pairs,
// FigureDef::figure_collisions), and Bullet's narrowphase (collide/convex_contacts.h) gives the
// contact points. In sim/ because figure/ and collide/ share a layer.
#pragma once

#include <array>
#include <vector>

#include "collide/convex_contacts.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"

namespace pbm {

struct Model;

// One contact point between segment a and segment b: the normal points from b toward a.
struct SegmentContact {
  int figure_a = 0, segment_a = 0;
  int figure_b = 0, segment_b = 0;
  Vec3 point = Vec3::Zero();  // midway between the surfaces [m]
  Vec3 normal = Vec3::UnitZ();
  Real depth = 0;  // [m], > 0
};

// The contact settings of a pair of figures (FigureDef): the smaller restitution, impact speed,
// stiffness and damping, and the geometric mean of their friction.
struct PairContactSettings {
  Real restitution = 0, impact_speed = 0, stiffness = 0, damping = 0, friction = 0;
};
PairContactSettings pair_contact_settings(const FigureDef& a, const FigureDef& b);

// Scratch of collect_segment_contacts, sized by it.
struct SegmentCollisionScratch {
  std::vector<ConvexSolid> solids;  // every segment's solid, figure by figure
  std::vector<Box3> boxes;
  std::vector<int> first;                 // index of each figure's first segment in solids
  std::vector<int> order;                 // solids sorted by their boxes' lower x
  std::vector<std::array<int, 2>> pairs;  // candidate pairs of solids whose boxes overlap
};

// The segment's shape placed by its world transform X (world -> segment): x = r + E^T p.
ConvexSolid segment_solid(const SegmentShapeDef& shape, const SpatialTransform& X);

// Whether two segments may collide (same figure: its self_pairs; two figures: both allow it).
bool segments_may_collide(const Model& model, int figure_a, int segment_a, int figure_b,
                          int segment_b);

// Clears the self pairs that overlap at the figures' initial pose (a hand modelled inside a hip
// would otherwise be thrown out at the first step) and says so in model.notes, as it does of two
// figures that overlap at the start; then sets model.segment_collisions.
void settle_initial_segment_overlaps(Model& model);

// Whether any pair of segments in the model may collide at all.
bool any_segment_pair_may_collide(const Model& model);

// The contacts between segments with each figure's segments at `worlds[f]` (inertial -> segment,
// figure/figure_impact.h's segment_world_transforms), sorted by (figure_a, segment_a, figure_b,
// segment_b) with a before b in that order: a function of the poses alone.
void collect_segment_contacts(const Model& model,
                              const std::vector<std::vector<SpatialTransform>>& worlds,
                              SegmentCollisionScratch& scratch, std::vector<SegmentContact>& out);

// The world velocity of the material of a segment at a world point, from its spatial velocity in
// its own frame (FigureWorkspace::v) and its world transform.
Vec3 segment_point_velocity(const SpatialTransform& world, const Vec6& v, const Vec3& point);

}  // namespace pbm
