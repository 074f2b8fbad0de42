#include "liquid/particle_transfer.h"

namespace pbm {

void markers_to_grid(const LiquidModel& model, const std::vector<Vec3>& markers,
                     const std::vector<Vec3>& velocities, LiquidWorkspace& ws, MacField& field) {
  const MacGrid& g = model.grid;
  for (int a = 0; a < 3; ++a) {
    if (a == model.thin_axis) continue;
    std::vector<Real>& weight = ws.transfer_weight[a];
    // The weighted sums gather in ws.previous (the substep overwrites it after this).
    std::vector<Real>& sum = ws.previous.u[a];
    std::fill(weight.begin(), weight.end(), 0.0);
    std::fill(sum.begin(), sum.end(), 0.0);
    for (std::size_t m = 0; m < markers.size(); ++m) {
      int base[3];
      Real frac[3];
      component_stencil(g, a, markers[m], base, frac);
      const Real v = velocities[m][a];
      // The transpose of blend_trilinear: the weights a read at the marker would give each face.
      for (int c = 0; c < 8; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
        const Real w = (di ? frac[0] : 1 - frac[0]) * (dj ? frac[1] : 1 - frac[1]) *
                       (dk ? frac[2] : 1 - frac[2]);
        if (w == 0) continue;
        const auto f = static_cast<std::size_t>(g.index(base[0] + di, base[1] + dj, base[2] + dk));
        weight[f] += w;
        sum[f] += w * v;
      }
    }
    std::vector<Real>& u = field.u[a];
    // A face a marker barely reaches (a corner's weight) would take its velocity whole: below
    // this weight the grid's own value is blended in.
    constexpr Real kFullWeight = 1e-3;
    for (std::size_t f = 0; f < u.size(); ++f) {
      const Real w = weight[f];
      if (w <= 0) continue;
      u[f] = w >= kFullWeight ? sum[f] / w : (sum[f] + (kFullWeight - w) * u[f]) / kFullWeight;
    }
  }
}

void grid_to_markers(const LiquidModel& model, const MacField& before, const MacField& after,
                     const std::vector<Vec3>& markers, std::vector<Vec3>& velocities) {
  const MacGrid& g = model.grid;
  const Real ratio = model.def.flip_ratio;
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const Vec3 now = interpolate_velocity(g, after.u, markers[m]);
    const Vec3 change = now - interpolate_velocity(g, before.u, markers[m]);
    Vec3 v = ratio * (velocities[m] + change) + (1 - ratio) * now;
    if (model.thin_axis >= 0) v[model.thin_axis] = 0;
    velocities[m] = v;
  }
}

}  // namespace pbm
