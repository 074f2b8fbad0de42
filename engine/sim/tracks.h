// Timeline tracks (DESIGN §5): keyframed values evaluated at a time, and the values they drive.
#pragma once

#include <vector>

#include "sim/model.h"

namespace pbm {

// Value of a keyframed track at time t: held constant before the first and after the last key;
// linear, or smooth (cubic Hermite with Catmull-Rom tangents, C1 through every key).
Real evaluate_track(const TrackModel& track, Real t);

// Everything the tracks may change, at one time.
struct Drive {
  Vec3 gravity = Vec3::Zero();
  std::vector<VecX> q_s0;  // rest values per body (n_shape each)
  std::vector<Vec3> spring_target;
  std::vector<Real> spring_stiffness;
  // The scene's camera (renderer only; unused without one).
  Vec3 camera_position = Vec3::Zero(), camera_target = Vec3::Zero(), camera_up = Vec3::UnitZ();
  Real camera_fov = 40;
};

void evaluate_drive(const Model& model, Real t, Drive& drive);

}  // namespace pbm
