#include "deform/stability_limit.h"

#include <cmath>
#include <limits>

#include "deform/body_model.h"

namespace pbm {

StabilityLimit explicit_stability_limit(const BodyModel& body, int iterations) {
  StabilityLimit limit;
  if (body.has_local) {
    const int n = body.n_nodes();
    // M^-1 K is similar to the symmetric M^-1/2 K M^-1/2: iterate on y = M^1/2 x so that the
    // Rayleigh quotient y^T A y / y^T y converges from below to omega_max^2.
    VecX y(3 * n), x(3 * n), f(3 * n);
    for (int i = 0; i < 3 * n; ++i) y[i] = ((i / 3 + i % 3) % 2 == 0 ? 1.0 : -1.0) + 1e-3 * i;
    y.normalize();
    Real rayleigh = 0;
    for (int k = 0; k < iterations; ++k) {
      for (int i = 0; i < n; ++i)
        x.segment<3>(3 * i) = y.segment<3>(3 * i) / std::sqrt(body.node_mass[i]);
      f.setZero();
      add_membrane_forces(body.tessellation, body.stiffness, x, f);
      for (int i = 0; i < n; ++i) f.segment<3>(3 * i) /= std::sqrt(body.node_mass[i]);
      rayleigh = y.dot(f);
      const Real norm = f.norm();
      if (!(norm > 0)) break;
      y = f / norm;
    }
    limit.omega = std::sqrt(std::max(rayleigh, 0.0));
  }
  for (int i = 0; i < body.n_s; ++i) {
    const Real eta = body.parameter_inertia_floor[i];
    if (eta > 0) limit.omega_shape = std::max(limit.omega_shape, std::sqrt(body.k_s[i] / eta));
  }
  const Real w = std::max(limit.omega, limit.omega_shape);
  const Real nu = body.damping, w2 = w * w;
  // First order (3.51): nu M q-dot = -K q decays at omega^2 / nu, a pure damper's rate.
  limit.lambda = body.order == DynamicsOrder::second ? 0.5 * nu + std::sqrt(0.25 * nu * nu + w2)
                 : nu > 0                            ? w2 / nu
                                                     : 0.0;
  const Real inf = std::numeric_limits<Real>::infinity();
  limit.dt_euler = limit.lambda > 0 ? 2.0 / limit.lambda : inf;
  limit.dt_rk4 = limit.lambda > 0 ? 2.78 / limit.lambda : inf;
  const Real ws2 = limit.omega_shape * limit.omega_shape;
  const Real lambda_shape = body.order == DynamicsOrder::second
                                ? 0.5 * nu + std::sqrt(0.25 * nu * nu + ws2)
                            : nu > 0 ? ws2 / nu
                                     : 0.0;
  limit.dt_euler_global = lambda_shape > 0 ? 2.0 / lambda_shape : inf;
  // The implicit integrator damps the rows at the step's end (implicit_row_damping), so a
  // second-order body keeps only the undamped bound omega_shape dt < 2.
  limit.dt_implicit = body.order == DynamicsOrder::second
                          ? (limit.omega_shape > 0 ? 2.0 / limit.omega_shape : inf)
                          : limit.dt_euler_global;
  limit.dt_rk4_global = lambda_shape > 0 ? 2.78 / lambda_shape : inf;
  return limit;
}

}  // namespace pbm
