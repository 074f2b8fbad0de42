// Where a segment's shape can touch an obstacle (sec. 15.3's detection, against rigid surfaces):
// a few spheres in the segment's frame whose union's lowest points are the shape's. A sphere is
// one, a capsule the two centres of its ends (exact against any surface), a box its 8 corners
// (radius 0: exact against a plane, whose deepest point of a box is always a corner), a cylinder
// 8 points on the rim of each cap (a tilted cylinder's deepest rim point lies between two of
// them: at most r (1 - cos 22.5 deg) = 0.076 r shallower than the true one).
#pragma once

#include <array>

#include "core/types.h"
#include "figure/figure_def.h"

namespace pbm {

struct SegmentProbe {
  Vec3 center = Vec3::Zero();  // in the segment's frame [m]
  Real radius = 0;             // [m]
};

inline constexpr int kMaxSegmentProbes = 16;
using SegmentProbes = std::array<SegmentProbe, kMaxSegmentProbes>;

// Fills probes with the shape's spheres; returns how many.
int segment_probes(const SegmentShapeDef& shape, SegmentProbes& probes);

}  // namespace pbm
