#include "sim/liquid_section.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pbm {

std::optional<draw::FieldSection> liquid_section(const LiquidModel& model, const LiquidState& state,
                                                 const std::vector<CellFlag>& flags) {
  const LiquidDef& def = model.def;
  if (def.section == LiquidSection::none) return std::nullopt;
  const MacGrid& g = model.grid;
  const int a = static_cast<int>(def.section_axis);
  // The other two axes in order: across y, u along x and v along z (a 2D liquid's plane).
  const int b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
  // The layer of cells holding the position (1-based, as the grid counts interior cells).
  const int layer =
      std::clamp(static_cast<int>(std::floor(def.section_position * g.n[a])), 0, g.n[a] - 1) + 1;
  draw::FieldSection s;
  s.label = def.section == LiquidSection::pressure ? def.name + " pressure [Pa]"
                                                   : def.name + " speed [m/s]";
  Vec3 corner = g.origin;
  corner[a] += (layer - 0.5) * g.h[a];
  Vec3 u = Vec3::Zero(), v = Vec3::Zero();
  u[b] = g.n[b] * g.h[b];
  v[c] = g.n[c] * g.h[c];
  s.corner = corner.cast<float>();
  s.u = u.cast<float>();
  s.v = v.cast<float>();
  s.nu = g.n[b];
  s.nv = g.n[c];
  s.values.assign(static_cast<std::size_t>(s.nu) * s.nv, std::numeric_limits<float>::quiet_NaN());
  float high = 0;
  for (int j = 0; j < s.nv; ++j) {
    for (int i = 0; i < s.nu; ++i) {
      Eigen::Vector3i cell;
      cell[a] = layer;
      cell[b] = i + 1;
      cell[c] = j + 1;
      const int k = g.index(cell.x(), cell.y(), cell.z());
      if (!is_liquid(flags[static_cast<std::size_t>(k)])) continue;
      Real value = 0;
      if (def.section == LiquidSection::pressure) {
        value = def.density * state.pressure[static_cast<std::size_t>(k)];  // p = rho (p / rho)
      } else {
        Real speed2 = 0;
        for (int axis = 0; axis < 3; ++axis) {
          const std::vector<Real>& face = state.velocity.u[axis];
          const Real centre = 0.5 * (face[static_cast<std::size_t>(k - g.stride(axis))] +
                                     face[static_cast<std::size_t>(k)]);
          speed2 += centre * centre;
        }
        value = std::sqrt(speed2);
      }
      const float f = static_cast<float>(value);
      s.values[static_cast<std::size_t>(i + s.nu * j)] = f;
      if (std::isfinite(f)) high = std::max(high, f);
    }
  }
  s.low = 0;
  s.high = high > 0 ? high : 1;
  return s;
}

}  // namespace pbm
