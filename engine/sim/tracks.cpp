#include "sim/tracks.h"

#include <algorithm>

namespace pbm {

Real evaluate_track(const TrackModel& track, Real t) {
  const auto& k = track.keys;
  if (t <= k.front().time) return k.front().value;
  if (t >= k.back().time) return k.back().value;
  const auto it = std::upper_bound(k.begin(), k.end(), t,
                                   [](Real time, const Keyframe& key) { return time < key.time; });
  const std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;
  const Keyframe& a = k[i];
  if (track.interpolation == Interpolation::step) return a.value;
  const Keyframe& b = k[i + 1];
  const Real h = b.time - a.time;
  const Real x = (t - a.time) / h;
  if (track.interpolation == Interpolation::linear) return a.value + x * (b.value - a.value);
  // Catmull-Rom slopes (one-sided at the ends), scaled to the interval.
  auto slope = [&k](std::size_t j) {
    const std::size_t lo = j == 0 ? 0 : j - 1;
    const std::size_t hi = std::min(j + 1, k.size() - 1);
    return (k[hi].value - k[lo].value) / (k[hi].time - k[lo].time);
  };
  const Real m0 = slope(i) * h, m1 = slope(i + 1) * h;
  const Real x2 = x * x, x3 = x2 * x;
  return (2 * x3 - 3 * x2 + 1) * a.value + (x3 - 2 * x2 + x) * m0 + (-2 * x3 + 3 * x2) * b.value +
         (x3 - x2) * m1;
}

void evaluate_drive(const Model& model, Real t, Drive& drive) {
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
  for (const TrackModel& track : model.tracks) {
    const Real value = evaluate_track(track, t);
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
    }
  }
}

}  // namespace pbm
