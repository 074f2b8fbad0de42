// Keyframed curves: a value given at increasing times and interpolated between them. Every
// subsystem's tracks use them (rest shapes, gravity, spring targets, obstacle and camera paths;
// joint trajectories and inflow rates to come).
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

// step holds each key's value until the next key (recorded mouse drags).
enum class Interpolation { linear, smooth, step };

struct Keyframe {
  Real time = 0;  // [s]
  Real value = 0;
};

// Value at time t of keys (strictly increasing times, at least one): held constant before the
// first and after the last key; linear, or smooth (cubic Hermite with Catmull-Rom tangents, C1
// through every key), or step.
Real evaluate_keys(Interpolation interpolation, const std::vector<Keyframe>& keys, Real t);

// d/dt of evaluate_keys at t: 0 outside the keys and for step curves; at a key, the slope of the
// interval that starts there (the one evaluate_keys uses).
Real evaluate_keys_rate(Interpolation interpolation, const std::vector<Keyframe>& keys, Real t);

// d^2/dt^2 of evaluate_keys at t: the smooth curve's, piecewise linear in t (it jumps at keys);
// 0 for linear and step curves and outside the keys. Joint trajectories give a controller its
// desired acceleration with it ((15.14)).
Real evaluate_keys_acceleration(Interpolation interpolation, const std::vector<Keyframe>& keys,
                                Real t);

// Checks keys a compiled scene relies on: at least one, finite, times increasing strictly.
// Throws pbm::Error naming `file` and `at` (the JSON path of the list; a key's own index added).
void require_keyframes(const std::vector<Keyframe>& keys, const std::string& file,
                       const std::string& at);

}  // namespace pbm
