#include "liquid/mac_grid.h"

#include <algorithm>

namespace pbm {

void component_stencil(const MacGrid& grid, int axis, const Vec3& x, int (&base)[3],
                       Real (&frac)[3]) {
  // Grid coordinates in which the component's samples sit at integers: the faces of axis `axis`
  // at i * h (index i), the other axes' samples at the cells' centres (index j, centre j - 1/2).
  for (int a = 0; a < 3; ++a) {
    Real g = (x[a] - grid.origin[a]) / grid.h[a] + (a == axis ? 0.0 : 0.5);
    // Faces 0..n along the axis, cells 0..n+1 across it (the ghosts carry the walls' values).
    const int last = a == axis ? grid.n[a] : grid.n[a] + 1;
    // A NaN position (a state the guard will reject) reads the first sample, not past the array.
    g = g >= 0 ? std::min(g, static_cast<Real>(last)) : 0.0;
    int b = static_cast<int>(g);
    if (b >= last) b = last - 1;
    if (last == 0) b = 0;
    base[a] = b;
    frac[a] = last == 0 ? 0.0 : g - b;
  }
}

Real interpolate_component(const MacGrid& grid, const std::vector<Real>& u, int axis,
                           const Vec3& x) {
  int base[3];
  Real frac[3];
  component_stencil(grid, axis, x, base, frac);
  return blend_trilinear(grid, u, base, frac);
}

Real blend_trilinear(const MacGrid& grid, const std::vector<Real>& values, const int (&base)[3],
                     const Real (&frac)[3]) {
  Real value = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const Real w =
        (di ? frac[0] : 1 - frac[0]) * (dj ? frac[1] : 1 - frac[1]) * (dk ? frac[2] : 1 - frac[2]);
    if (w == 0) continue;
    value +=
        w * values[static_cast<std::size_t>(grid.index(base[0] + di, base[1] + dj, base[2] + dk))];
  }
  return value;
}

Vec3 interpolate_velocity(const MacGrid& grid, const std::vector<Real> (&u)[3], const Vec3& x) {
  return {interpolate_component(grid, u[0], 0, x), interpolate_component(grid, u[1], 1, x),
          interpolate_component(grid, u[2], 2, x)};
}

}  // namespace pbm
