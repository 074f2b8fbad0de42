#include "sim/liquid_segment_loads.h"

#include <algorithm>
#include <cmath>

namespace pbm {

LiquidSegmentTotals add_liquid_segment_loads(const LiquidModel& liquid, const LiquidWorkspace& lw,
                                             const std::vector<std::vector<SurfacePatch>>& patches,
                                             const std::vector<SpatialTransform>& world,
                                             std::span<const Vec6> v,
                                             std::span<ForceVector> forces) {
  LiquidSegmentTotals totals;
  const Real rho = liquid.def.density;
  const Real cd = liquid.def.drag;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const SpatialTransform& X = world[i];  // x_segment = E (x_world - r)
    const MotionVector m = motion_from_vec6(v[i]);
    ForceVector total;
    for (const SurfacePatch& patch : patches[i]) {
      const Vec3 x = X.r + X.E.transpose() * patch.point;
      const Real p = probe_pressure(liquid, lw, x);
      if (!(p > 0)) continue;
      // Pressure and drag in the segment's own frame: the patch's are already.
      Vec3 f = -rho * p * patch.area_normal;
      const Real area = patch.area_normal.norm();
      totals.wetted_area += area;
      if (cd > 0 && area > 0) {
        const Vec3 material = m.linear + m.angular.cross(patch.point);
        const Vec3 relative = material - X.E * probe_velocity(liquid, lw, x);
        const Real speed = relative.norm();
        const Real facing =
            speed > 0 ? std::max(Real(0), patch.area_normal.dot(relative) / speed) : Real(0);
        f += -0.5 * rho * cd * facing * speed * relative;
      }
      total += ForceVector{patch.point.cross(f), f};
    }
    forces[i] += total;
    totals.force += X.E.transpose() * total.force;
    totals.power += dot(m, total);
  }
  return totals;
}

}  // namespace pbm
