// A scene's joint controller (sec. 15.4): which DOF it drives, the trajectory it follows (a
// keyframed joint trajectory, sec. 15.1.2) and its law with its gains. Plain data with defaults,
// as a scene file states it; figure/figure_controllers.h checks it against its figure.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/keyframes.h"
#include "core/types.h"

namespace pbm {

enum class ControllerKind {
  mrac,       // decoupled model reference adaptive control, (15.10)-(15.17)
  pd,         // u = kp (q_d - q) + kd (q_d-dot - q-dot), explicit
  stable_pd,  // the same servo taken at the step's end, its gains folded into the step
};

// A target set live from the control panel (fig. 15.11's crane panel): from `time` on the desired
// position is value + rate (t - time), the desired rate `rate` and the acceleration zero. A rate
// of zero holds a position (a boom angle); a nonzero rate is a jog, a lever held at a speed (the
// crane's crawlers and winch).
struct LiveKey {
  Real time = 0;   // [s]
  Real value = 0;  // [rad or m]
  Real rate = 0;   // [rad/s or m/s]
};

struct ControllerDef {
  ControllerKind kind = ControllerKind::mrac;
  std::string joint;  // the segment whose parent joint it drives
  int dof = 0;        // which of the joint's DOFs (a universal joint has 2)
  // The desired q_d(t) [rad or m]; q_d-dot and q_d-ddot are its derivatives (15.14).
  Interpolation interpolation = Interpolation::smooth;
  std::vector<Keyframe> keys;
  // Targets set live during play from the studio's control panel (fig. 15.11's crane panel),
  // recorded so that playback and the saved file repeat them: they replace `keys` from the first
  // one's time on, each acting until the next (LiveKey). Empty: `keys` alone.
  std::vector<LiveKey> live;
  // MRAC: the reference model's settling time t_s and the adaptation's alpha, beta (15.16),
  // (15.17); control/mrac.h says why these defaults.
  Real settling_time = 0.3;
  Real alpha = 10;
  Real beta = 2;
  // MRAC beyond the book: an adaptive bias torque (control/mrac.h), so a DOF is held where
  // gravity pulls it without a steady error; off, the book's law.
  bool adaptive_bias = false;
  // PD and stable PD gains [N m/rad, N m s/rad or N/m, N s/m].
  Real kp = 0;
  Real kd = 0;
  // The actuator's limit |u| <= max_output [N m or N]; none when absent.
  std::optional<Real> max_output;
};

}  // namespace pbm
