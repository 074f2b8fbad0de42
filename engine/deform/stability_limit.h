// The explicit step's stability limit of a body (sec. 6.1): the fastest mode of its local
// displacements, omega_max^2 = the largest eigenvalue of M^-1 K_dd (lumped nodal masses, the
// membrane's element matrices of (4.38)), found by power iteration without assembling K_dd. The
// book's Euler (6.1) integrates a mode of frequency omega with damping nu (D = nu M) stably while
// dt lambda < 2, lambda = nu / 2 + sqrt(nu^2 / 4 + omega^2) (the undamped oscillator's
// omega dt < 2 and the pure damper's nu dt < 2 are its ends); classic RK4 while dt lambda < 2.78
// (its stability boundary on the imaginary axis is 2 sqrt 2). A first-order body (3.51) decays
// its mode at lambda = omega^2 / nu, under the same bounds. The global block's fastest mode is
// at most omega_s = max_i sqrt(k_i / eta_i) = 1 / tau: its inertia floor eta_i = k_i tau^2
// bounds M_ss from below (deform/body_model.h); with tau = dt (the default) it never limits.
#pragma once

#include "core/types.h"

namespace pbm {

struct BodyModel;

struct StabilityLimit {
  Real omega = 0;        // fastest membrane mode [rad/s]; 0 without local displacements
  Real omega_shape = 0;  // bound on the global block's fastest mode, 1 / tau [rad/s]; 0 without
  // nu / 2 + sqrt(nu^2 / 4 + w^2), first order w^2 / nu, w = max(omega, omega_shape) [1/s]
  Real lambda = 0;
  // Largest stable step of the book's Euler and of RK4 [s] (infinite when nothing limits it).
  Real dt_euler = 0, dt_rk4 = 0;
  // The implicit integrator's: the global block's undamped bound 2 / omega_shape for a
  // second-order body (the membrane and the rows' damping are taken implicitly,
  // deform/implicit_membrane.h), Euler's limit on the global block for a first-order one.
  Real dt_implicit = 0;
  // Euler's and RK4's limits on the global block alone: a body of level "auto" while its
  // displacements are off (sim/level_of_detail.h).
  Real dt_euler_global = 0, dt_rk4_global = 0;
};

// Power iteration on M^-1 K_dd: `iterations` products, started from an alternating pattern that
// excites the mesh's shortest wavelengths (deterministic: the limit is part of the model).
StabilityLimit explicit_stability_limit(const BodyModel& body, int iterations = 60);

}  // namespace pbm
