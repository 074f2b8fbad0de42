// Timeline tracks (docs/architecture.md, "Timeline"): keyframed values evaluated at a time, with
// the user's inputs of the moment (sim/inputs.h), and the values they drive.
#pragma once

#include <cstdint>
#include <vector>

#include "sim/inputs.h"
#include "sim/model.h"

namespace pbm {

// Value of a keyframed track at time t: held constant before the first and after the last key;
// linear, or smooth (cubic Hermite with Catmull-Rom tangents, C1 through every key).
Real evaluate_track(const TrackModel& track, Real t);

// d/dt of evaluate_track at t: 0 outside the keys and for step tracks; at a key, the slope of
// the interval that starts there (the one evaluate_track uses).
Real evaluate_track_rate(const TrackModel& track, Real t);

// Everything the tracks may change, at one time.
struct Drive {
  Vec3 gravity = Vec3::Zero();
  std::vector<VecX> q_s0;  // rest values per body (n_shape each)
  std::vector<Vec3> spring_target;
  std::vector<Real> spring_stiffness;
  // The scene's camera (renderer only; unused without one).
  Vec3 camera_position = Vec3::Zero(), camera_target = Vec3::Zero(), camera_up = Vec3::UnitZ();
  Real camera_fov = 40;
  // The model's obstacles where their tracks put them at this time, with the velocity of their
  // material (sec. 5.2.1 against a moving obstacle); copies of Model::obstacles when none moves.
  std::vector<ObstacleModel> obstacles;
  // Per liquid (16.6): the pressure on its free surface [Pa], and its inflows' velocity when a
  // track drives it (inflow_driven 1: inflow_velocity holds for every inflow of the liquid), each
  // with its rate, so a liquid stepping on its own clock takes them at its substeps' times.
  std::vector<Real> liquid_surface_pressure, liquid_surface_pressure_rate;
  std::vector<Vec3> liquid_inflow_velocity, liquid_inflow_rate;
  std::vector<std::uint8_t> liquid_inflow_driven;
};

// The value of model.tracks[k] at time t and its rate: the track's keys, unless an input set it
// at or before t (then the input's value, rate 0, as a step key).
Real track_value(const Model& model, const Inputs& inputs, int k, Real t);
Real track_rate(const Model& model, const Inputs& inputs, int k, Real t);

// Everything the tracks drive at time t. No allocation once `drive` has the model's sizes.
void evaluate_drive(const Model& model, const Inputs& inputs, Real t, Drive& drive);

// Only the obstacles of evaluate_drive: `obstacles` becomes the model's, placed at time t.
// A point track sets the point and its velocity from the track's rate; rotation tracks give the
// rotation vector r(t) (world frame, about the point), R(t) = exp([r]x) R_scene, and the angular
// velocity omega = J_l(r) r-dot (J_l the left Jacobian of SO(3)). A plane's normal turns with R.
// No allocation once `obstacles` has the model's size.
void place_obstacles(const Model& model, const Inputs& inputs, Real t,
                     std::vector<ObstacleModel>& obstacles);

}  // namespace pbm
