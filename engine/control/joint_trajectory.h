// A joint trajectory (sec. 15.1.2): a DOF's desired displacement given as keys, and the desired
// motion a controller reads from it at time t (q_d, q_d-dot, q_d-ddot for (15.14)).
#pragma once

#include <vector>

#include "control/mrac.h"
#include "core/keyframes.h"

namespace pbm {

inline DesiredMotion desired_motion(Interpolation interpolation, const std::vector<Keyframe>& keys,
                                    Real t) {
  return {evaluate_keys(interpolation, keys, t), evaluate_keys_rate(interpolation, keys, t),
          evaluate_keys_acceleration(interpolation, keys, t)};
}

}  // namespace pbm
