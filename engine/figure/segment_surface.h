// A segment's surface as patches for integrals over it (a liquid's pressure on a segment: the
// book's buoyancy f = -grad p dV (16.13) summed over a segment is, by the divergence theorem,
// -oint p n dA). Each patch is a point on the exact surface and its outward normal times its
// share of the exact area: the sphere's and the capsule's caps are cut in bands of equal height,
// which on a sphere are bands of equal area (Archimedes' hat-box theorem), the cylinder's side
// and caps in sectors, the box's faces in squares. Along a round shape's axis each band holds the
// two points of Gauss's rule, around it the sectors' middles: a linear pressure times the normal
// is integrated exactly over a shape wholly under water, and where the water line cuts a shape
// to within 0.15% of its full buoyancy at 4 divisions (tests/test_liquid_figure.cpp).
#pragma once

#include <vector>

#include "core/types.h"
#include "figure/figure_def.h"

namespace pbm {

struct SurfacePatch {
  Vec3 point = Vec3::Zero();        // on the surface, in the segment's frame [m]
  Vec3 area_normal = Vec3::Zero();  // outward normal times area, in the segment's frame [m^2]
};

// The shape's patches, in the segment's frame (its centre and orientation applied), `divisions`
// patches along a box's edge, a quarter circle of a round shape and its length (>= 1).
void segment_surface_patches(const SegmentShapeDef& shape, int divisions,
                             std::vector<SurfacePatch>& patches);

}  // namespace pbm
