// Time integrators shared by every subsystem (sec. 6.1): the book's Euler (6.1)/(6.2), classic
// fourth-order Runge-Kutta, and adaptive Runge-Kutta 4(5) (Dormand-Prince) with an error
// tolerance. They see the system only through two callbacks, so they know nothing of bodies.
#pragma once

#include "core/function_ref.h"
#include "core/types.h"

namespace pbm {

// implicit: Euler's update (6.1) with rates that subsystems with stiff parts evaluate as the
// linearized backward-Euler increment over the substep (deform/implicit_membrane.h).
enum class IntegratorKind { euler, rk4, rk45, implicit };

// qdot (n_q) and vdot (n_v) of the system at (t, q, v).
using DerivativeFn =
    FunctionRef<void(Real t, const VecX& q, const VecX& v, VecX& q_dot, VecX& v_dot)>;
// Overwrites q_dot with the kinematic rates implied by the velocities v (second-order parts only).
using KinematicFn = FunctionRef<void(const VecX& q, const VecX& v, VecX& q_dot)>;

// Scratch of the stages, sized once; what carries from one call to the next (rk45's step size)
// is the caller's, passed in and out (it belongs in the State: it changes later steps).
struct IntegratorWorkspace {
  VecX kq[7], kv[7];  // stage derivatives
  VecX q_stage, v_stage, q_err, v_err;
  void resize(int n_q, int n_v);
};

struct IntegrationStats {
  int evaluations = 0;
  int accepted = 0;
  int rejected = 0;
  Real error = 0;  // rk45: the last accepted scaled error norm
};

// (6.1): v += dt a(q, v); q += dt q-dot(q, v_new). For first-order parts (v-dot = 0) this is (6.2).
void euler_step(const DerivativeFn& f, const KinematicFn& kin, Real t, Real dt, VecX& q, VecX& v,
                IntegratorWorkspace& ws, IntegrationStats& stats);
void rk4_step(const DerivativeFn& f, Real t, Real dt, VecX& q, VecX& v, IntegratorWorkspace& ws,
              IntegrationStats& stats);
// Advances exactly dt in adaptive substeps whose scaled local error
// max_i |err_i| / (tol + tol |y_i|) stays <= 1. step_size is the step to try first (0: all of
// dt) and on return the step the last accepted one suggests. Returns false if the step size
// underflows.
bool rk45_advance(const DerivativeFn& f, Real t, Real dt, Real tolerance, VecX& q, VecX& v,
                  Real& step_size, IntegratorWorkspace& ws, IntegrationStats& stats);

}  // namespace pbm
