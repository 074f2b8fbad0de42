#include "liquid/momentum.h"

#include "liquid/mac_grid.h"

namespace pbm {

namespace {

// The convective terms of (16.2) for component a at face f: d(u_a^2)/dx_a and d(u_a u_b)/dx_b
// in flux form, each product taken of averages at the cell centres and the cells' edges.
Real book_convection(const MacGrid& g, const MacField& v, int a, int f, int thin) {
  const auto s = [](int i) { return static_cast<std::size_t>(i); };
  const std::vector<Real>& ua = v.u[a];
  const int ea = g.stride(a);
  const Real centre_lo = 0.5 * (ua[s(f - ea)] + ua[s(f)]);
  const Real centre_hi = 0.5 * (ua[s(f)] + ua[s(f + ea)]);
  Real rate = (centre_lo * centre_lo - centre_hi * centre_hi) / g.h[a];
  for (int b = 0; b < 3; ++b) {
    if (b == a || b == thin) continue;
    const int eb = g.stride(b);
    const std::vector<Real>& ub = v.u[b];
    // Edge at +1/2 along b: u_a between f and f+eb, u_b between the cells f and f+ea on their
    // + faces along b; at -1/2 likewise one cell down.
    const Real ua_plus = 0.5 * (ua[s(f)] + ua[s(f + eb)]);
    const Real ub_plus = 0.5 * (ub[s(f)] + ub[s(f + ea)]);
    const Real ua_minus = 0.5 * (ua[s(f - eb)] + ua[s(f)]);
    const Real ub_minus = 0.5 * (ub[s(f - eb)] + ub[s(f + ea - eb)]);
    rate += (ua_minus * ub_minus - ua_plus * ub_plus) / g.h[b];
  }
  return rate;
}

Real laplacian(const MacGrid& g, const std::vector<Real>& u, int f, int thin) {
  const auto s = [](int i) { return static_cast<std::size_t>(i); };
  Real lap = 0;
  for (int b = 0; b < 3; ++b) {
    if (b == thin) continue;
    const int eb = g.stride(b);
    lap += (u[s(f + eb)] - 2 * u[s(f)] + u[s(f - eb)]) / (g.h[b] * g.h[b]);
  }
  return lap;
}

// Where the face's sample sits [m].
Vec3 face_position(const MacGrid& g, int a, int i, int j, int k) {
  Vec3 x = g.centre(i, j, k);
  x[a] += 0.5 * g.h[a];
  return x;
}

// The velocity at face f of axis a: its own component exactly, each other one the mean of the
// four faces around it (what the trilinear blend gives there, without its 8-sample stencils:
// the backtrace's first stage was 3 of its 7 blends), zero along a 2D grid's thin axis.
Vec3 face_velocity(const MacGrid& g, const std::vector<Real> (&u)[3], int a, int f, int thin) {
  const auto s = [](int i) { return static_cast<std::size_t>(i); };
  Vec3 v = Vec3::Zero();
  const int ea = g.stride(a);
  for (int b = 0; b < 3; ++b) {
    if (b == thin) continue;
    if (b == a) {
      v[b] = u[a][s(f)];
      continue;
    }
    const int eb = g.stride(b);
    const std::vector<Real>& ub = u[b];
    v[b] = 0.25 * ((ub[s(f - eb)] + ub[s(f)]) + (ub[s(f + ea - eb)] + ub[s(f + ea)]));
  }
  return v;
}

}  // namespace

void update_momentum(const LiquidModel& model, const MomentumInput& in, MacField& out) {
  const MacGrid& g = model.grid;
  const int thin = model.thin_axis;
  const Real nu = model.def.viscosity;
  const bool book = model.def.advection == LiquidAdvection::book;
  const bool carried = model.def.advection == LiquidAdvection::flip;  // by the markers
  const Real dt = in.dt;
  for (int a = 0; a < 3; ++a) {
    if (a == thin) continue;
    const int ea = g.stride(a);
    Eigen::Vector3i last = g.n;
    last[a] = g.n[a] - 1;  // the faces between two interior cells
    for (int k = 1; k <= last.z(); ++k) {
      for (int j = 1; j <= last.y(); ++j) {
        for (int i = 1; i <= last.x(); ++i) {
          const int f = g.index(i, j, k);
          const CellFlag lo = in.flags[static_cast<std::size_t>(f)];
          const CellFlag hi = in.flags[static_cast<std::size_t>(f + ea)];
          if (!(is_liquid(lo) || is_liquid(hi)) || fixes_velocity(lo) || fixes_velocity(hi)) {
            continue;
          }
          const auto fs = static_cast<std::size_t>(f);
          const std::vector<Real>& prev = in.previous.u[a];
          Real convected = 0;
          if (carried) {
            convected = prev[fs];
          } else if (book) {
            convected = prev[fs] + dt * book_convection(g, in.previous, a, f, thin);
          } else {
            // Backtrace by the midpoint rule through the substep's starting field.
            const Vec3 x = face_position(g, a, i, j, k);
            const Vec3 v1 = face_velocity(g, in.previous.u, a, f, thin);
            const Vec3 v2 = interpolate_velocity(g, in.previous.u, x - 0.5 * dt * v1, thin);
            convected = interpolate_component(g, prev, a, x - dt * v2);
          }
          const Real grad_p = (in.pressure[static_cast<std::size_t>(f + ea)] - in.pressure[fs]) /
                              g.h[a] * in.face_scale[a][fs];
          out.u[a][fs] =
              convected + dt * (in.gravity[a] - grad_p + nu * laplacian(g, prev, f, thin));
        }
      }
    }
  }
}

}  // namespace pbm
