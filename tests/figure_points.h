// A figure's pose as the tests probe it: every segment's world transform and spatial velocity at
// (q, v), a point attached to a segment in the world, its velocity and its Jacobian (tests of the
// impacts, the impulse events, the collisions and the momentum).
#pragma once

#include <vector>

#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"

namespace pbm::test {

struct FigurePose {
  FigureWorkspace ws;                   // ws.v: each segment's spatial velocity, own coordinates
  std::vector<SpatialTransform> world;  // inertial -> segment
};

// v may be null (at rest).
inline FigurePose pose_of(const FigureModel& figure, const Real* q, const Real* v = nullptr) {
  FigurePose pose;
  size_figure_workspace(figure, pose.ws);
  figure_kinematics(figure, q, v, pose.ws);
  segment_world_transforms(figure, pose.ws, pose.world);
  return pose;
}

// The world position of the point at body coordinates p of the segment.
inline Vec3 world_point(const FigureModel& figure, const VecX& q, int segment, const Vec3& p) {
  const FigurePose pose = pose_of(figure, q.data());
  return pose.world[segment].r + pose.world[segment].E.transpose() * p;
}

// The world velocity of the world point `point` moving with the segment.
inline Vec3 point_velocity(const FigureModel& figure, const VecX& q, const VecX& v, int segment,
                           const Vec3& point) {
  const FigurePose pose = pose_of(figure, q.data(), v.data());
  const MotionVector s =
      transform_motion(inverse(pose.world[segment]), motion_from_vec6(pose.ws.v[segment]));
  return s.linear + s.angular.cross(point);
}

// J (3 x n_v) of the world point `point` moving with the segment: its velocity is J v.
inline MatX point_jacobian(const FigureModel& figure, const VecX& q, int segment,
                           const Vec3& point) {
  const FigurePose pose = pose_of(figure, q.data());
  MatX J = MatX::Zero(3, figure.n_v);
  add_point_jacobian(figure, pose.ws, pose.world, segment, point, 1.0, J);
  return J;
}

}  // namespace pbm::test
