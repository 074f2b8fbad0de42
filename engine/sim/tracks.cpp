#include "sim/tracks.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace pbm {

Real evaluate_track(const TrackModel& track, Real t) {
  return evaluate_keys(track.interpolation, track.keys, t);
}

Real evaluate_track_rate(const TrackModel& track, Real t) {
  return evaluate_keys_rate(track.interpolation, track.keys, t);
}

namespace {

const TrackInput* input_for(const Inputs& inputs, int k, Real t) {
  for (const TrackInput& input : inputs.tracks) {
    if (input.track == k && t >= input.time) return &input;
  }
  return nullptr;
}

}  // namespace

Real track_value(const Model& model, const Inputs& inputs, int k, Real t) {
  if (const TrackInput* input = input_for(inputs, k, t)) return input->value;
  return evaluate_track(model.tracks[static_cast<std::size_t>(k)], t);
}

Real track_rate(const Model& model, const Inputs& inputs, int k, Real t) {
  if (input_for(inputs, k, t)) return 0;
  return evaluate_track_rate(model.tracks[static_cast<std::size_t>(k)], t);
}

namespace {

// exp([r]x) and the left Jacobian J_l(r) = I + (1 - cos a) / a^2 [r]x + (a - sin a) / a^3 [r]x^2,
// a = |r|, which maps r-dot to the world angular velocity of exp([r]x) R0.
void rotation_and_jacobian(const Vec3& r, Mat3& R, Mat3& J) {
  const Real a = r.norm();
  Mat3 K;
  K << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  Real c1, c2;  // (1 - cos a) / a^2, (a - sin a) / a^3; their series below 1e-4 rad
  if (a < 1e-4) {
    c1 = 0.5 - a * a / 24;
    c2 = 1.0 / 6 - a * a / 120;
    R = Mat3::Identity() + K + c1 * K * K;
  } else {
    c1 = (1 - std::cos(a)) / (a * a);
    c2 = (a - std::sin(a)) / (a * a * a);
    R = Eigen::AngleAxis<Real>(a, r / a).toRotationMatrix();
  }
  J = Mat3::Identity() + c1 * K + c2 * K * K;
}

}  // namespace

void place_obstacles(const Model& model, const Inputs& inputs, Real t,
                     std::vector<ObstacleModel>& obstacles) {
  obstacles.resize(model.obstacles.size());
  for (std::size_t o = 0; o < model.obstacles.size(); ++o) {
    const ObstacleModel& source = model.obstacles[o];
    ObstacleModel& placed = obstacles[o];
    placed = source;
    if (!source.moving) continue;
    Vec3 r = Vec3::Zero(), r_dot = Vec3::Zero();
    bool rotates = false;
    for (int k = 0; k < static_cast<int>(model.tracks.size()); ++k) {
      const TrackModel& track = model.tracks[static_cast<std::size_t>(k)];
      if (track.object != static_cast<int>(o)) continue;
      if (track.target == TrackTarget::obstacle_point) {
        placed.point[track.index] = track_value(model, inputs, k, t);
        placed.velocity[track.index] = track_rate(model, inputs, k, t);
      } else if (track.target == TrackTarget::obstacle_rotation) {
        r[track.index] = track_value(model, inputs, k, t);
        r_dot[track.index] = track_rate(model, inputs, k, t);
        rotates = true;
      }
    }
    if (!rotates) continue;
    Mat3 R, J;
    rotation_and_jacobian(r, R, J);
    placed.rotation = R * source.rotation;
    placed.normal = R * source.normal;
    placed.angular_velocity = J * r_dot;
  }
}

void evaluate_drive(const Model& model, const Inputs& inputs, Real t, Drive& drive) {
  drive.gravity = model.gravity;
  drive.q_s0.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) drive.q_s0[b] = model.bodies[b].q_s0;
  drive.spring_target.resize(model.springs.size());
  drive.spring_stiffness.resize(model.springs.size());
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    drive.spring_target[s] = model.springs[s].target;
    drive.spring_stiffness[s] = model.springs[s].stiffness;
  }
  if (model.scene.camera) {
    drive.camera_position = model.scene.camera->position;
    drive.camera_target = model.scene.camera->target;
    drive.camera_up = model.scene.camera->up;
    drive.camera_fov = model.scene.camera->fov;
  }
  place_obstacles(model, inputs, t, drive.obstacles);
  const std::size_t n_liquids = model.liquids.size();
  drive.liquid_surface_pressure.resize(n_liquids);
  drive.liquid_surface_pressure_rate.assign(n_liquids, 0.0);
  drive.liquid_inflow_velocity.resize(n_liquids);
  drive.liquid_inflow_rate.assign(n_liquids, Vec3::Zero());
  drive.liquid_inflow_driven.assign(n_liquids, 0);
  for (std::size_t l = 0; l < n_liquids; ++l) {
    drive.liquid_surface_pressure[l] = model.liquids[l].def.surface_pressure;
    const std::vector<InflowModel>& inflows = model.liquids[l].inflows;
    drive.liquid_inflow_velocity[l] = inflows.empty() ? Vec3::Zero() : inflows[0].velocity;
  }
  for (int k = 0; k < static_cast<int>(model.tracks.size()); ++k) {
    const TrackModel& track = model.tracks[static_cast<std::size_t>(k)];
    if (track.target == TrackTarget::obstacle_point ||
        track.target == TrackTarget::obstacle_rotation) {
      continue;  // place_obstacles
    }
    const Real value = track_value(model, inputs, k, t);
    switch (track.target) {
      case TrackTarget::body_rest_parameter:
        drive.q_s0[track.object][track.index] = value;
        break;
      case TrackTarget::gravity:
        drive.gravity[track.index] = value;
        break;
      case TrackTarget::spring_target:
        drive.spring_target[track.object][track.index] = value;
        break;
      case TrackTarget::spring_stiffness:
        drive.spring_stiffness[track.object] = value;
        break;
      case TrackTarget::camera_position:
        drive.camera_position[track.index] = value;
        break;
      case TrackTarget::camera_target:
        drive.camera_target[track.index] = value;
        break;
      case TrackTarget::camera_fov:
        drive.camera_fov = value;
        break;
      case TrackTarget::liquid_surface_pressure:
        drive.liquid_surface_pressure[track.object] = value;
        drive.liquid_surface_pressure_rate[track.object] = track_rate(model, inputs, k, t);
        break;
      case TrackTarget::liquid_inflow_velocity:
        drive.liquid_inflow_velocity[track.object][track.index] = value;
        drive.liquid_inflow_rate[track.object][track.index] = track_rate(model, inputs, k, t);
        drive.liquid_inflow_driven[track.object] = 1;
        break;
      case TrackTarget::obstacle_point:
      case TrackTarget::obstacle_rotation:
        break;
    }
  }
}

}  // namespace pbm
