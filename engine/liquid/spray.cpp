#include "liquid/spray.h"

#include <algorithm>
#include <cmath>

namespace pbm {

namespace {

// Roberts' R3 sequence (as the inflows' markers, surface_tracking.cpp): evenly spread points in a
// cell, the same from any state that has emitted as many.
Vec3 spread(std::uint64_t n) {
  constexpr Real kPlastic = 1.2207440845057265;
  const Vec3 alpha(1 / kPlastic, 1 / (kPlastic * kPlastic), 1 / (kPlastic * kPlastic * kPlastic));
  Vec3 u;
  for (int a = 0; a < 3; ++a) u[a] = std::fmod(0.5 + static_cast<Real>(n) * alpha[a], 1.0);
  return u;
}

// The interior cell holding x, or -1 outside the domain.
int cell_at(const MacGrid& g, const Vec3& x) {
  const Eigen::Vector3i c = g.cell_of(x);
  return g.interior(c.x(), c.y(), c.z()) ? g.index(c.x(), c.y(), c.z()) : -1;
}

}  // namespace

void fly_spray(const Vec3& gravity, Real drag, Real dt, Vec3& x, Vec3& v) {
  // v' = (v + g dt) / (1 + k |v| dt): the drag implicit in v, lagged in |v|.
  v = (v + dt * gravity) / (1 + drag * v.norm() * dt);
  x += dt * v;
}

void advance_spray(const LiquidModel& model, const MacField& field, const Vec3& gravity, Real dt,
                   const LiquidWorkspace& ws, LiquidState& state, SprayStats& stats) {
  const LiquidDef& def = model.def;
  if (def.spray_speed <= 0 || def.surface != SurfaceMethod::markers) return;
  const MacGrid& g = model.grid;
  const int v_axis = model.vertical_axis;
  const int up = gravity[v_axis] <= 0 ? g.stride(v_axis) : -g.stride(v_axis);
  const Real sign = up > 0 ? 1.0 : -1.0;
  auto liquid = [&](int c) { return c >= 0 && is_liquid(ws.flags[static_cast<std::size_t>(c)]); };
  auto open_air = [&](int c) {
    return c >= 0 && ws.flags[static_cast<std::size_t>(c)] == CellFlag::empty;
  };

  // Emission: Surface cells with air above whose liquid rises faster than spray_speed through
  // their top face.
  std::vector<int> rising;
  for (int c = 0; c < g.size; ++c) {
    if (ws.flags[static_cast<std::size_t>(c)] != CellFlag::surface) continue;
    const int above = c + up;
    if (above < 0 || above >= g.size || !open_air(above)) continue;
    const int top_face = up > 0 ? c : above;  // face f lies between cells f and f + stride
    if (sign * field.u[v_axis][static_cast<std::size_t>(top_face)] > def.spray_speed) {
      rising.push_back(c);
    }
  }
  if (!rising.empty()) {
    state.spray_owed += def.spray_rate * dt * static_cast<Real>(rising.size());
    const auto count = static_cast<long>(std::floor(state.spray_owed));
    state.spray_owed -= static_cast<Real>(count);
    for (long k = 0; k < count; ++k) {
      if (static_cast<int>(state.spray.size()) >= def.max_spray) break;
      const std::uint64_t n = state.spray_total++;
      const int c = rising[static_cast<std::size_t>(n % rising.size())];
      // A point in the cell's upper half, where the surface is.
      const Vec3 lo = g.centre(c) - 0.5 * g.h;
      Vec3 u = spread(n);
      u[v_axis] = 0.5 + 0.5 * u[v_axis];
      if (up < 0) u[v_axis] = 1 - u[v_axis];
      Vec3 x = lo + u.cwiseProduct(g.h);
      if (model.thin_axis >= 0) x[model.thin_axis] = g.centre(c)[model.thin_axis];
      state.spray.push_back(x);
      state.spray_velocity.push_back(interpolate_velocity(g, field.u, x));
      ++stats.emitted;
    }
  }

  // Spray in the air: gravity and drag; into the liquid while falling, it becomes foam.
  std::size_t kept = 0;
  for (std::size_t p = 0; p < state.spray.size(); ++p) {
    Vec3 x = state.spray[p], v = state.spray_velocity[p];
    fly_spray(gravity, def.spray_drag, dt, x, v);
    if (model.thin_axis >= 0) {
      x[model.thin_axis] = state.spray[p][model.thin_axis];
      v[model.thin_axis] = 0;
    }
    const int c = cell_at(g, x);
    if (c < 0 || fixes_velocity(model.fixed[static_cast<std::size_t>(c)])) continue;  // gone
    if (liquid(c) && v.dot(gravity) > 0) {
      if (static_cast<int>(state.foam.size()) < def.max_spray) {
        state.foam.push_back(x);
        state.foam_age.push_back(0);
        ++stats.landed;
      }
      continue;
    }
    state.spray[kept] = x;
    state.spray_velocity[kept++] = v;
  }
  state.spray.resize(kept);
  state.spray_velocity.resize(kept);

  // Foam rides the liquid and fades.
  kept = 0;
  for (std::size_t p = 0; p < state.foam.size(); ++p) {
    Vec3 x = state.foam[p];
    const Real age = state.foam_age[p] + dt;
    if (age > def.foam_lifetime) {
      ++stats.faded;
      continue;
    }
    // The liquid's velocity, continued past its surface (the substep's extrapolation).
    x += dt * interpolate_velocity(g, field.u, x);
    if (model.thin_axis >= 0) x[model.thin_axis] = state.foam[p][model.thin_axis];
    const int c = cell_at(g, x);
    if (c < 0 || model.fixed[static_cast<std::size_t>(c)] != CellFlag::empty) continue;
    state.foam[kept] = x;
    state.foam_age[kept++] = age;
  }
  state.foam.resize(kept);
  state.foam_age.resize(kept);
}

}  // namespace pbm
