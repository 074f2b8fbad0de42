#include "sim/liquid_body_loads.h"

#include <algorithm>
#include <cmath>

namespace pbm {

namespace {

// The 3-point rule exact for quadratics on a triangle: its points' barycentric weights (each
// point weighs 1/3 of the area). The pressure is linear in depth below the surface, so a
// triangle under it is integrated exactly; one the surface cuts, to its clamp's kink.
constexpr Real kRule[3][3] = {
    {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};

bool overlaps_domain(const LiquidModel& liquid, const BodyWorkspace& bw) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& x : bw.x) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  for (int a = 0; a < 3; ++a) {
    if (a == liquid.thin_axis) continue;
    if (hi[a] < liquid.def.domain.min[a] || lo[a] > liquid.def.domain.max[a]) return false;
  }
  return true;
}

}  // namespace

LiquidLoadTotals add_liquid_loads(const LiquidModel& liquid, const LiquidWorkspace& lw,
                                  const BodyModel& body, const BodyWorkspace& bw,
                                  std::vector<Vec3>& force) {
  LiquidLoadTotals totals;
  if (bw.x.empty() || !overlaps_domain(liquid, bw)) return totals;
  const Real rho = liquid.def.density;
  const Real cd = liquid.def.drag;
  // Where the body moves the liquid too (two-way), the liquid beside it moves with it, and the
  // drag's C_d is defined against the stream the body meets: its relative velocity is the
  // liquid's as far out along each face's normal as the body is large (the bounding sphere's
  // radius, at least a cell and a half: a sphere's own disturbance there is an eighth of its
  // speed), a sub-grid closure for the wake the grid cannot resolve
  // (tests/test_liquid_two_way.cpp).
  Real offset = 0;
  if (liquid.two_way) {
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
    for (const Vec3& x : bw.x) {
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    offset = 0.5 * (hi - lo).norm();
    for (int k = 0; k < 3; ++k) {
      if (k != liquid.thin_axis) offset = std::max(offset, 1.5 * liquid.grid.h[k]);
    }
  }
  for (const std::array<int, 3>& t : body.tessellation.triangles) {
    const Vec3& x0 = bw.x[t[0]];
    const Vec3& x1 = bw.x[t[1]];
    const Vec3& x2 = bw.x[t[2]];
    // Counter-clockwise from outside (deform/tessellation.h): the outward normal times the area.
    const Vec3 area = 0.5 * (x1 - x0).cross(x2 - x0);
    Real share[3] = {0, 0, 0};  // each node's share of oint p dA over the triangle [m^4/s^2]
    int wet = 0;
    for (const auto& w : kRule) {
      const Vec3 x = w[0] * x0 + w[1] * x1 + w[2] * x2;
      const Real p = probe_pressure(liquid, lw, x);
      if (p <= 0) continue;
      ++wet;
      for (int k = 0; k < 3; ++k) share[k] += p * w[k] / 3;
    }
    if (wet == 0) continue;
    Vec3 f[3];
    for (int k = 0; k < 3; ++k) f[k] = -rho * share[k] * area;
    const Real a = area.norm();
    const Real wet_fraction = wet / 3.0;
    totals.wetted_area += wet_fraction * a;
    if (cd > 0 && a > 0) {
      const Vec3 centroid = (x0 + x1 + x2) / 3 + offset / a * area;
      const Vec3 relative = (bw.x_dot[t[0]] + bw.x_dot[t[1]] + bw.x_dot[t[2]]) / 3 -
                            probe_velocity(liquid, lw, centroid);
      const Real speed = relative.norm();
      // Only the faces moving into the liquid: their projected areas, A max(0, n . v_rel /
      // |v_rel|), add up to the body's frontal area.
      const Real facing = speed > 0 ? std::max(0.0, area.dot(relative) / speed) : 0.0;
      const Vec3 drag = -0.5 * rho * cd * wet_fraction * facing * speed * relative;
      for (int k = 0; k < 3; ++k) f[k] += drag / 3;
    }
    for (int k = 0; k < 3; ++k) {
      force[static_cast<std::size_t>(t[k])] += f[k];
      totals.force += f[k];
    }
  }
  return totals;
}

}  // namespace pbm
