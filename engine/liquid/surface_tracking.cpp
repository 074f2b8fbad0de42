#include "liquid/surface_tracking.h"

#include <algorithm>
#include <cmath>

#include "liquid/cell_labels.h"

namespace pbm {

int advect_markers(const LiquidModel& model, const MacField& field, Real dt,
                   std::vector<Vec3>& markers, std::vector<Vec3>& velocities,
                   const MovingSolids* moving) {
  const bool carried = !velocities.empty();
  const MacGrid& g = model.grid;
  std::size_t kept = 0;
  for (std::size_t m = 0; m < markers.size(); ++m) {
    const Vec3 x = markers[m];
    const Vec3 v1 = interpolate_velocity(g, field.u, x);
    const Vec3 v2 = interpolate_velocity(g, field.u, x + 0.5 * dt * v1);
    Vec3 next = x + dt * v2;
    if (model.thin_axis >= 0) next[model.thin_axis] = x[model.thin_axis];
    const Eigen::Vector3i c = g.cell_of(next);
    if (!g.interior(c.x(), c.y(), c.z())) {
      next = x;
    } else {
      const auto k = static_cast<std::size_t>(g.index(c.x(), c.y(), c.z()));
      const CellFlag f = model.fixed[k];
      if (f == CellFlag::outflow) continue;  // removed
      if (f == CellFlag::solid || (moving && moving->inside[k])) next = x;
    }
    if (carried) velocities[kept] = velocities[m];
    markers[kept++] = next;
  }
  const int removed = static_cast<int>(markers.size() - kept);
  markers.resize(kept);
  if (carried) velocities.resize(kept);
  return removed;
}

int release_markers(const LiquidModel& model, const std::vector<Vec3>& inflow_velocity, Real dt,
                    LiquidState& state) {
  // The additive recurrence of the plastic number (Roberts' R3 sequence): evenly spread points
  // in a box, the same from any state that has released as many.
  constexpr Real kPlastic = 1.2207440845057265;
  const Vec3 alpha(1 / kPlastic, 1 / (kPlastic * kPlastic), 1 / (kPlastic * kPlastic * kPlastic));
  const MacGrid& g = model.grid;
  int dropped = 0;
  for (std::size_t s = 0; s < model.inflows.size(); ++s) {
    const InflowModel& inflow = model.inflows[s];
    const Vec3& velocity = inflow_velocity[s];
    // The main axis of the scene's velocity (of the velocity now, where the scene gives none).
    int axis = 0;
    (inflow.velocity.isZero() ? velocity : inflow.velocity).cwiseAbs().maxCoeff(&axis);
    Real rate = inflow.markers_per_second;
    if (rate > 0) {
      rate *=
          inflow.velocity[axis] != 0 ? std::max(0.0, velocity[axis] / inflow.velocity[axis]) : 0.0;
    } else {
      // The flux through the box's cross-section across its flow, at the marker density; none
      // while the inflow runs backwards (its cells drain the liquid then).
      const Real sign =
          std::copysign(1.0, inflow.velocity[axis] != 0 ? inflow.velocity[axis] : velocity[axis]);
      const Vec3 size = inflow.box.max - inflow.box.min;
      // Per cell and per box, their measure in the grid's dimensions (a 2D grid's thin axis out).
      Real cell = 1, box = 1;
      for (int a = 0; a < 3; ++a) {
        if (a == model.thin_axis) continue;
        cell *= g.h[a];
        box *= size[a];
      }
      rate =
          model.markers_per_cell / cell * std::max(0.0, sign * velocity[axis]) * box / size[axis];
    }
    Real& owed = state.released[s];
    owed += rate * dt;
    while (owed >= 1) {
      owed -= 1;
      if (state.markers.size() >= state.markers.capacity()) {
        ++dropped;
        continue;
      }
      const Real n = static_cast<Real>(state.released_total++);
      Vec3 u;
      for (int a = 0; a < 3; ++a) u[a] = std::fmod(0.5 + n * alpha[a], 1.0);
      Vec3 x = inflow.box.min + u.cwiseProduct(inflow.box.max - inflow.box.min);
      if (model.thin_axis >= 0)
        x[model.thin_axis] = 0.5 * (inflow.box.min + inflow.box.max)[model.thin_axis];
      state.markers.push_back(x);
      if (model.def.advection == LiquidAdvection::flip) state.marker_velocity.push_back(velocity);
    }
  }
  return dropped;
}

void advance_height_field(const LiquidModel& model, const MacField& field, Real dt,
                          LiquidState& state, LiquidWorkspace& ws) {
  const MacGrid& g = model.grid;
  const ColumnAxes axes = column_axes(model);
  const int n0 = g.n[axes.h0], n1 = g.n[axes.h1];
  const Real bottom = g.origin[axes.v];
  const Real top = bottom + g.n[axes.v] * g.h[axes.v];
  auto h_at = [&](int i0, int i1, Real own) {
    if (i0 < 0 || i1 < 0 || i0 >= n0 || i1 >= n1) return own;  // a wall: no slope across it
    return state.height[static_cast<std::size_t>(i0 + n0 * i1)];
  };
  for (int i1 = 0; i1 < n1; ++i1) {
    for (int i0 = 0; i0 < n0; ++i0) {
      const Real h = state.height[static_cast<std::size_t>(i0 + n0 * i1)];
      int ijk[3];
      ijk[axes.h0] = i0 + 1;
      ijk[axes.h1] = i1 + 1;
      ijk[axes.v] =
          std::clamp(static_cast<int>(std::floor((h - bottom) / g.h[axes.v])) + 1, 1, g.n[axes.v]);
      const int c = g.index(ijk[0], ijk[1], ijk[2]);
      Vec3 x = g.centre(ijk[0], ijk[1], ijk[2]);
      x[axes.v] = h;
      const Real w = interpolate_component(g, field.u[axes.v], axes.v, x);
      const auto cs = static_cast<std::size_t>(c);
      const Real u0 =
          field.u[axes.h0][cs] + field.u[axes.h0][cs - static_cast<std::size_t>(g.stride(axes.h0))];
      const Real u1 =
          field.u[axes.h1][cs] + field.u[axes.h1][cs - static_cast<std::size_t>(g.stride(axes.h1))];
      Real rate = w + (h_at(i0 - 1, i1, h) - h_at(i0 + 1, i1, h)) / (4 * g.h[axes.h0]) * u0;
      if (axes.h1 != model.thin_axis) {
        rate += (h_at(i0, i1 - 1, h) - h_at(i0, i1 + 1, h)) / (4 * g.h[axes.h1]) * u1;
      }
      ws.height_next[static_cast<std::size_t>(i0 + n0 * i1)] =
          std::clamp(h + dt * rate, bottom, top);
    }
  }
  state.height.swap(ws.height_next);
}

}  // namespace pbm
