// A joint controller compiled against its figure (figure/figure_controllers.h) and the explicit
// laws a rate evaluation applies: MRAC (15.10)-(15.17) and PD, on a single-axis DOF or on one
// component of a spherical joint's rotation vector (control/ball_coordinates.h). The stable PD is
// not explicit: its gains enter the figure's mass matrix (figure/stable_pd.h), so the figure's
// dynamics stage solves for it; here it only reports its desired motion.
#pragma once

#include <optional>

#include "control/controller_def.h"
#include "control/mrac.h"

namespace pbm {

// Entries of a controller's state in the figure's controller slice of State::q (its integrals,
// sec. 15.4.2): MRAC keeps (q_m, q_m-dot, K_1, K_2, K_r, u_b) (u_b: its adaptive bias, beyond
// the book); PD and stable PD keep none.
inline constexpr int kMracStateSize = 6;

struct JointController {
  ControllerDef def;
  int segment = 0;        // the driven joint's segment
  int q_index = 0;        // the DOF's entry in the figure's q (a ball: its quaternion's first)
  int v_index = 0;        // and in its v (a ball: omega's component def.dof)
  bool ball = false;      // drives component def.dof of a spherical joint's rotation vector
  int state_offset = -1;  // MRAC: first of its kMracStateSize entries in the controller slice
  MracSettings mrac;      // from def, for mrac_control
};

// What a controller does at one time: its desired, reference-model and actual positions, and its
// output (the force or torque on the DOF, within the limit). Figs. 15.7, 15.8 plot the first three.
struct ControlSample {
  Real desired = 0;
  Real reference = 0;  // MRAC's q_m; PD: the desired position
  Real actual = 0;
  Real output = 0;
  bool saturated = false;
};

// The coordinate a controller drives at the figure's (q, v): a DOF's q and q-dot, or a ball's
// r_k and r_k-dot (control/ball_coordinates.h); `torque`: the joint forces per unit output u on
// it, at v_index for a DOF (1) or at the ball's omega (the row J_r^-T e_k).
struct ControlledCoordinate {
  Real x = 0, x_dot = 0;
  Vec3 torque = Vec3::UnitX();
};
ControlledCoordinate controlled_coordinate(const JointController& c, const Real* q, const Real* v);

// Adds the output u on the coordinate to the figure's joint forces tau (n_v).
void add_controller_output(const JointController& c, const ControlledCoordinate& x, Real u,
                           Real* tau);

// The desired motion a live key sets at time t >= key.time: value + rate (t - time), the rate,
// zero acceleration.
inline DesiredMotion live_desired(const LiveKey& key, Real t) {
  return {key.value + key.rate * (t - key.time), key.rate, 0};
}

// The desired motion at time t: `held` (a target set live during play, sim/inputs.h's
// ControlInput) once its time has come, else the last live key at or before t, else the keys.
DesiredMotion controller_desired(const JointController& c, Real t,
                                 const std::optional<LiveKey>& held = {});

// The explicit laws (MRAC, PD) at time t on a DOF at (q, q_dot): the sample, and the rates of the
// controller's state entries (state, rate: its kMracStateSize entries; unused for PD).
ControlSample explicit_control(const JointController& c, Real t, Real q, Real q_dot,
                               const Real* state, Real* rate,
                               const std::optional<LiveKey>& held = {});

// The state a controller starts with at (q, q_dot): MRAC's model at the DOF, integrals zero
// (mrac_start); writes kMracStateSize entries.
void controller_start(const JointController& c, Real q, Real q_dot, Real* state);

}  // namespace pbm
