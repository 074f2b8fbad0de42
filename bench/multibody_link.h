// A link as Bullet's btMultiBody describes it, and our figure of the same links: what
// `pbm bench figures` races and tests/test_figure_vs_bullet.cpp checks against Bullet. Plain data
// and the figure model only, no Bullet header, so either precision of Bullet can read it.
#pragma once

#include <vector>

#include "figure/figure_model.h"

namespace pbm::bench {

// Pivot offsets, the rotation at q = 0 (parent coordinates to its own), a revolute axis in its
// own frame (or a spherical joint), principal inertia at its centre.
struct MultibodyLink {
  int parent = -1;  // -1: the fixed base
  bool spherical = false;
  Real mass = 1;
  Vec3 principal = Vec3::Ones();            // [kg m^2], link axes
  Vec3 parent_com_to_pivot = Vec3::Zero();  // parent frame, from the parent's centre [m]
  Vec3 pivot_to_com = Vec3::Zero();         // own frame [m]
  Mat3 rot_parent_to_this = Mat3::Identity();
  Vec3 axis = Vec3::UnitZ();
};

// Our figure of the links: a segment's frame at its pivot, turned as the link's frame, its centre
// of mass at pivot_to_com; the joint's frame on the parent at the parent's centre (its own
// pivot_to_com; the base's centre is the origin) plus parent_com_to_pivot.
inline FigureModel figure_of_links(const std::vector<MultibodyLink>& links) {
  FigureModel figure;
  for (const MultibodyLink& l : links) {
    SegmentModel s;
    s.parent = l.parent;
    s.joint.kind = l.spherical ? JointKind::spherical : JointKind::revolute;
    s.joint.axis = l.axis;
    const Vec3 parent_com =
        l.parent >= 0 ? links[static_cast<std::size_t>(l.parent)].pivot_to_com : Vec3::Zero();
    s.X_tree = SpatialTransform{l.rot_parent_to_this, parent_com + l.parent_com_to_pivot};
    s.inertia = SpatialInertia{l.mass, l.pivot_to_com, l.principal.asDiagonal().toDenseMatrix()};
    figure.segments.push_back(s);
  }
  finalize_figure_model(figure);
  return figure;
}

}  // namespace pbm::bench
