#include "sim/stages_liquid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "collide/convex_contacts.h"
#include "collide/obstacle.h"
#include "deform/body_dynamics.h"
#include "liquid/cell_labels.h"
#include "liquid/liquid_probe.h"
#include "liquid/liquid_surface_mesh.h"
#include "sim/figure_collisions.h"
#include "sim/liquid_body_loads.h"
#include "sim/liquid_section.h"
#include "sim/liquid_segment_loads.h"
#include "sim/stages_figures.h"
#include "sim/tracks.h"

namespace pbm::stages {

namespace {

const draw::Material kWaterMaterial{{0.16f, 0.45f, 0.85f}, 0.15f};
// A liquid's surface (a marker liquid's mesh, a height field): translucent, so what is under the
// water shows.
const draw::Material kWaterSurfaceMaterial{{0.16f, 0.45f, 0.85f}, 0.15f, 0.7f};
const draw::Material kLiquidSolidMaterial{{0.5f, 0.47f, 0.42f}, 0.9f};
const draw::Vec3f kMarkerColor{0.25f, 0.55f, 0.95f};
const draw::Vec3f kSprayColor{0.92f, 0.95f, 1.0f};
const draw::Vec3f kFoamColor{1.0f, 1.0f, 1.0f};
const draw::Vec3f kDomainColor{0.35f, 0.6f, 0.9f};

// What drives liquid l from `drive`, evaluated at time t: gravity, and the tracks of 16.6 with
// their rates (LiquidInputs takes them at each of its substeps' times).
LiquidInputs liquid_inputs(const Model& model, const Drive& drive, std::size_t l, Real t) {
  LiquidInputs in{.gravity = drive.gravity, .time = t};
  if (l < drive.liquid_surface_pressure.size()) {
    // Beyond the scene's own value, which the liquid adds itself (exactly 0 without a track).
    in.surface_pressure = drive.liquid_surface_pressure[l] - model.liquids[l].def.surface_pressure;
    in.surface_pressure_rate = drive.liquid_surface_pressure_rate[l];
    in.inflows_driven = drive.liquid_inflow_driven[l] != 0;
    in.inflow_velocity = drive.liquid_inflow_velocity[l];
    in.inflow_rate = drive.liquid_inflow_rate[l];
  }
  return in;
}

// The first entry of `values` that is NaN or infinite, or -1.
template <typename T>
long first_not_finite(const std::vector<T>& values) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if constexpr (std::is_same_v<T, Vec3>) {
      if (!values[k].allFinite()) return static_cast<long>(k);
    } else {
      if (!std::isfinite(values[k])) return static_cast<long>(k);
    }
  }
  return -1;
}

std::string cell_text(const MacGrid& g, long c) {
  const long k = c / g.sz, j = (c % g.sz) / g.sy, i = c % g.sy;
  return "(" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) + ")";
}

// The 12 edges of a box, as segments.
void add_box_edges(const Vec3& lo, const Vec3& hi, const draw::Vec3f& color, draw::Lines& lines) {
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 p = lo, q;
      p[b] = corner & 1 ? hi[b] : lo[b];
      p[c] = corner & 2 ? hi[c] : lo[c];
      q = p;
      q[a] = hi[a];
      lines.points.push_back(p.cast<float>());
      lines.points.push_back(q.cast<float>());
      lines.colors.push_back(color);
    }
  }
}

bool two_way(const LiquidModel& liquid) {
  return liquid.two_way;
}

bool any_two_way(const Model& model) {
  return std::any_of(model.liquids.begin(), model.liquids.end(), two_way);
}

// Every body's surface at the state's time, into ws.liquid_surfaces.
void capture_body_surfaces(const Model& model, const State& state, Workspace& ws) {
  ws.liquid_surfaces.clear();  // reserved for every body: no allocation
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& k = ws.liquid_kinematics[b];
    k.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, body_q(body, state.q), body_v(body, state.v), k, false);
    ws.liquid_surfaces.push_back({k.x, k.x_dot, body.tessellation.triangles});
  }
}

// The interior cells of liquid m whose centres lie inside an obstacle placed as `obstacles` are
// (a plane's half-space, a box, a mesh), with the obstacle's velocity there.
// The first obstacle no track moves that holds each cell's centre (-1: none).
void find_static_obstacle_cells(const LiquidModel& m, const std::vector<ObstacleModel>& obstacles,
                                std::vector<int>& first) {
  const MacGrid& g = m.grid;
  first.assign(static_cast<std::size_t>(g.size), -1);
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        if (m.fixed[static_cast<std::size_t>(c)] != CellFlag::empty) continue;
        const Vec3 x = g.centre(i, j, k);
        for (std::size_t o = 0; o < obstacles.size(); ++o) {
          Vec3 normal;
          if (!obstacles[o].moving && signed_distance(obstacles[o], x, normal) < 0) {
            first[static_cast<std::size_t>(c)] = static_cast<int>(o);
            break;
          }
        }
      }
    }
  }
}

// The cells the obstacles cover now, each with the velocity of the first obstacle (in the
// scene's order) holding its centre: the static ones read from `first_static`, the moving ones
// tested where they are.
void collect_obstacle_cells(const LiquidModel& m, const std::vector<ObstacleModel>& obstacles,
                            const std::vector<int>& first_static, std::vector<SolidCell>& out) {
  out.clear();
  if (obstacles.empty()) return;
  const bool any_moving = std::any_of(obstacles.begin(), obstacles.end(),
                                      [](const ObstacleModel& o) { return o.moving; });
  const MacGrid& g = m.grid;
  for (int k = 1; k <= g.n.z(); ++k) {
    for (int j = 1; j <= g.n.y(); ++j) {
      for (int i = 1; i <= g.n.x(); ++i) {
        const int c = g.index(i, j, k);
        const auto cs = static_cast<std::size_t>(c);
        if (m.fixed[cs] != CellFlag::empty) continue;
        const int held = first_static[cs];
        if (!any_moving) {
          if (held >= 0)
            out.push_back(
                {c, obstacles[static_cast<std::size_t>(held)].velocity_at(g.centre(i, j, k))});
          continue;
        }
        const Vec3 x = g.centre(i, j, k);
        for (std::size_t o = 0; o < obstacles.size(); ++o) {
          const ObstacleModel& obstacle = obstacles[o];
          Vec3 normal;
          const bool inside = obstacle.moving ? signed_distance(obstacle, x, normal) < 0
                                              : held == static_cast<int>(o);
          if (inside) {
            out.push_back({c, obstacle.velocity_at(x)});
            break;
          }
        }
      }
    }
  }
}

// Liquid l's moving solids where the bodies (ws.liquid_surfaces) and obstacles are now: what its
// probe and its measurement see between its substeps.
// Two-way: the cells whose centres a figure's segment covers (the exact shape's signed distance,
// collide/convex_contacts.h), moving with the segment's material there, after the obstacles'
// in `out`: the figures at the state's pose.
void collect_segment_cells(const Model& model, const LiquidModel& m, const State& state,
                           FiguresWorkspace& fw, std::vector<SolidCell>& out) {
  all_figure_kinematics(model, state.q.data(), state.v.data(), fw);
  const MacGrid& g = m.grid;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureDef& def = model.scene.figures[f];
    for (std::size_t i = 0; i < def.segments.size(); ++i) {
      const SpatialTransform& X = fw.worlds[f][i];
      const ConvexSolid solid = segment_solid(def.segments[i].shape, X);
      const Box3 box = convex_bounds(solid);
      Eigen::Vector3i lo = g.cell_of(box.lo), hi = g.cell_of(box.hi);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::max(lo[a], 1);
        hi[a] = std::min(hi[a], g.n[a]);
        // A 2D grid's slab: the segment's cells where it crosses the slab's middle.
        if (a == m.thin_axis) lo[a] = hi[a] = 1;
      }
      for (int k = lo.z(); k <= hi.z(); ++k) {
        for (int j = lo.y(); j <= hi.y(); ++j) {
          for (int n = lo.x(); n <= hi.x(); ++n) {
            const int c = g.index(n, j, k);
            if (m.fixed[static_cast<std::size_t>(c)] != CellFlag::empty) continue;
            const Vec3 x = g.centre(n, j, k);
            Vec3 normal;
            if (!(convex_signed_distance(solid, x, normal) < 0)) continue;
            out.push_back({c, segment_point_velocity(X, fw.each[f].v[i], x)});
          }
        }
      }
    }
  }
}

void place_liquid_solids(const Model& model, const State& state, std::size_t l, Workspace& ws) {
  MovingSolids& moving = ws.liquids[l].moving;
  clear_moving_solids(moving);
  if (!two_way(model.liquids[l])) return;
  const LiquidModel& m = model.liquids[l];
  collect_obstacle_cells(m, ws.drive.obstacles, ws.liquid_static_obstacle[l],
                         ws.liquid_obstacle_cells);
  if (!model.figures.empty()) {
    collect_segment_cells(model, m, state, *ws.figures, ws.liquid_obstacle_cells);
  }
  for (const SolidCell& cell : ws.liquid_obstacle_cells) {
    mark_solid_cell(m, cell.cell, cell.velocity, moving);
  }
  for (const SolidSurface& surface : ws.liquid_surfaces) voxelize_surface(m, surface, 0, moving);
}

}  // namespace

bool liquids_present(const Model& model) {
  return !model.liquids.empty();
}

void size_liquids(const Model& model, Workspace& ws) {
  ws.liquids.resize(model.liquids.size());
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    size_liquid_workspace(model.liquids[l], ws.liquids[l]);
  }
  ws.liquid_steps.assign(model.liquids.size(), LiquidStepStats{});
  ws.liquid_static_obstacle.assign(model.liquids.size(), {});
  if (any_two_way(model)) {
    for (std::size_t l = 0; l < model.liquids.size(); ++l) {
      if (two_way(model.liquids[l])) {
        find_static_obstacle_cells(model.liquids[l], model.obstacles, ws.liquid_static_obstacle[l]);
      }
    }
    ws.liquid_kinematics = ws.bodies;  // sized as the bodies' own
    ws.liquid_surfaces.reserve(model.bodies.size());
    ws.liquid_obstacle_cells.reserve(
        static_cast<std::size_t>(std::max_element(model.liquids.begin(), model.liquids.end(),
                                                  [](const LiquidModel& a, const LiquidModel& b) {
                                                    return a.grid.size < b.grid.size;
                                                  })
                                     ->grid.size));
  }
}

void advance_liquids(const SubstepContext& c) {
  // Tracks drive a liquid from its own time, where this advance starts (its substeps then follow
  // the tracks' rates): one evaluation of the drive, only in scenes that have tracks.
  const bool tracked = !c.model.tracks.empty();
  // A frame's last substep ends within rounding of the frame's time, to which advance_frame then
  // snaps the state's: the liquid goes there exactly.
  Real target = c.state.time;
  if (c.ws.substep_ends_frame) {
    const Real fps = c.model.solver.fps;
    const Real frame_time = std::round(c.state.time * fps) / fps;
    if (std::abs(frame_time - target) < 1e-6 / fps) target = frame_time;
  }
  bool captured = false;
  for (std::size_t l = 0; l < c.model.liquids.size(); ++l) {
    LiquidState& liquid = c.state.liquids[l];
    if (liquid.overrun) continue;  // the frame fails (describe_liquid_failure)
    // Every decision reads the State only (next_step is part of it): bit-identical with any
    // workspace.
    // Once the next substep of the bodies would take the liquid past its own limit: it then
    // advances in one substep of its own rather than two halves.
    if (!c.ws.substep_ends_frame && c.state.time - liquid.time + c.dt < liquid.next_step) continue;
    if (tracked) evaluate_drive(c.model, c.inputs, liquid.time, c.ws.liquid_drive);
    LiquidInputs inputs =
        liquid_inputs(c.model, tracked ? c.ws.liquid_drive : c.ws.drive, l, liquid.time);
    if (two_way(c.model.liquids[l])) {
      // The bodies at the end of this substep of theirs; each substep of the liquid moves them
      // back to its own time along their velocities.
      if (!captured) capture_body_surfaces(c.model, c.state, c.ws);
      captured = true;
      collect_obstacle_cells(c.model.liquids[l], c.ws.drive.obstacles,
                             c.ws.liquid_static_obstacle[l], c.ws.liquid_obstacle_cells);
      // The figures' segments where this substep of theirs ends, as the obstacles (with their
      // material's velocity).
      if (!c.model.figures.empty()) {
        collect_segment_cells(c.model, c.model.liquids[l], c.state, *c.ws.figures,
                              c.ws.liquid_obstacle_cells);
      }
      inputs.obstacle_cells = c.ws.liquid_obstacle_cells;
      inputs.surfaces = c.ws.liquid_surfaces;
      inputs.surfaces_time = c.state.time;
    }
    advance_liquid(c.model.liquids[l], inputs, target, liquid, c.ws.liquids[l],
                   c.ws.liquid_steps[l]);
  }
}

bool liquid_bodies_present(const Model& model) {
  return !model.liquids.empty() && (!model.bodies.empty() || !model.figures.empty());
}

void size_liquid_bodies(const Model& model, Workspace& ws) {
  ws.liquid_body_force.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    ws.liquid_body_force[b].assign(static_cast<std::size_t>(model.bodies[b].n_nodes()),
                                   Vec3::Zero());
  }
  if (model.figures.empty()) return;
  FiguresWorkspace& fw = *ws.figures;  // the figures' row sized it first (sim/subsystems.cpp)
  fw.liquid_patches.resize(model.figures.size());
  std::size_t most = 0;
  for (std::size_t f = 0; f < model.figures.size(); ++f) {
    const FigureDef& def = model.scene.figures[f];
    fw.liquid_patches[f].resize(def.segments.size());
    for (std::size_t i = 0; i < def.segments.size(); ++i) {
      segment_surface_patches(def.segments[i].shape, kSegmentSurfaceDivisions,
                              fw.liquid_patches[f][i]);
    }
    most = std::max(most, def.segments.size());
  }
  fw.liquid_measured.assign(most, ForceVector{});
}

void liquid_probe_start(const SubstepContext& c) {
  // Rebuilt every substep from the State alone, never kept from an earlier one: a retry, a seek
  // or the adaptive integrator's rejection restores the State, and the bodies must feel the
  // liquid it holds (docs/architecture.md, "Determinism"). The solids where they are now.
  if (any_two_way(c.model)) capture_body_surfaces(c.model, c.state, c.ws);
  for (std::size_t l = 0; l < c.model.liquids.size(); ++l) {
    place_liquid_solids(c.model, c.state, l, c.ws);
    build_liquid_probe(c.model.liquids[l], c.state.liquids[l], c.ws.drive.gravity, c.ws.liquids[l]);
  }
}

void liquid_body_forces(const RateContext& c) {
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    std::vector<Vec3>& force = c.ws.liquid_body_force[b];
    std::fill(force.begin(), force.end(), Vec3::Zero());
    BodyWorkspace& bw = c.ws.bodies[b];
    for (std::size_t l = 0; l < c.model.liquids.size(); ++l) {
      add_liquid_loads(c.model.liquids[l], c.ws.liquids[l], c.model.bodies[b], bw, force);
    }
    for (std::size_t i = 0; i < force.size(); ++i) bw.force[i] += force[i];
  }
  if (c.model.figures.empty()) return;
  // Into the contact stage's forces on the segments: figure_contact_forces, a hook before this
  // one, cleared them and left this rate's kinematics where a scene has contacts.
  FiguresWorkspace& fw = *c.ws.figures;
  if (!figure_contacts_present(c.model)) {
    all_figure_kinematics(c.model, c.q.data(), c.v.data(), fw);
    for (std::vector<ForceVector>& forces : fw.contact_forces) {
      std::fill(forces.begin(), forces.end(), ForceVector{});
    }
  }
  fw.liquid_power = 0;
  for (std::size_t f = 0; f < c.model.figures.size(); ++f) {
    for (std::size_t l = 0; l < c.model.liquids.size(); ++l) {
      fw.liquid_power +=
          add_liquid_segment_loads(c.model.liquids[l], c.ws.liquids[l], fw.liquid_patches[f],
                                   fw.worlds[f], fw.each[f].v, fw.contact_forces[f])
              .power;
    }
  }
}

void liquid_body_work(const SubstepContext& c) {
  // The power of the last rate evaluation's forces at its velocities, over the substep: the
  // rectangle rule, first order in dt like the guard's other allowances.
  Real power = 0;
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    const std::vector<Vec3>& force = c.ws.liquid_body_force[b];
    const BodyWorkspace& bw = c.ws.bodies[b];
    for (std::size_t i = 0; i < force.size(); ++i) power += force[i].dot(bw.x_dot[i]);
  }
  if (!c.model.figures.empty()) power += c.ws.figures->liquid_power;
  c.state.liquid_work += power * c.dt;
}

void measure_liquids(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                     FrameStats& stats) {
  (void)inputs;
  stats.liquids.resize(model.liquids.size());
  if (any_two_way(model)) capture_body_surfaces(model, state, ws);
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    const LiquidModel& m = model.liquids[l];
    const LiquidState& s = state.liquids[l];
    LiquidWorkspace& w = ws.liquids[l];
    LiquidFrameStats& out = stats.liquids[l];
    out.body_force.setZero();
    out.wetted_area = 0;
    // What the frame's substeps cost (advance_frame starts each attempt afresh).
    out.step = ws.liquid_steps[l];
    place_liquid_solids(model, state, l, ws);
    if (model.bodies.empty() && model.figures.empty()) {
      label_cells(m, s, w.flags, w.fill, w.count, &w.moving);
    } else {
      // The push on the bodies at this state (their kinematics are measure_bodies'): the probe
      // labels the cells too.
      build_liquid_probe(m, s, ws.drive.gravity, w);
      std::vector<Vec3>& scratch = ws.liquid_measure_force;  // sized once: no allocation
      for (std::size_t b = 0; b < model.bodies.size(); ++b) {
        scratch.assign(static_cast<std::size_t>(model.bodies[b].n_nodes()), Vec3::Zero());
        const LiquidLoadTotals t = add_liquid_loads(m, w, model.bodies[b], ws.bodies[b], scratch);
        out.body_force += t.force;
        out.wetted_area += t.wetted_area;
      }
      if (!model.figures.empty()) {
        FiguresWorkspace& fw = *ws.figures;
        all_figure_kinematics(model, state.q.data(), state.v.data(), fw);
        for (std::size_t f = 0; f < model.figures.size(); ++f) {
          const std::span<ForceVector> forces(fw.liquid_measured.data(),
                                              fw.liquid_patches[f].size());
          const LiquidSegmentTotals t = add_liquid_segment_loads(
              m, w, fw.liquid_patches[f], fw.worlds[f], fw.each[f].v, forces);
          out.body_force += t.force;
          out.wetted_area += t.wetted_area;
        }
      }
    }
    out.volume = liquid_volume(m, w.flags, w.fill);
    out.markers = static_cast<int>(s.markers.size() + s.chain.size());
    out.spray = static_cast<int>(s.spray.size());
    out.foam = static_cast<int>(s.foam.size());
    const MacGrid& g = m.grid;
    Real sum = 0, fastest = 0;
    for (int c = 0; c < g.size; ++c) {
      if (!is_liquid(w.flags[static_cast<std::size_t>(c)])) continue;
      Real speed2 = 0;
      for (int a = 0; a < 3; ++a) {
        const std::vector<Real>& u = s.velocity.u[a];
        const Real lo = u[static_cast<std::size_t>(c - g.stride(a))];
        const Real hi = u[static_cast<std::size_t>(c)];
        const Real centre = 0.5 * (lo + hi);
        speed2 += centre * centre;
        fastest = std::max({fastest, std::abs(lo), std::abs(hi)});
      }
      sum += speed2 * w.fill[static_cast<std::size_t>(c)];
    }
    out.kinetic = 0.5 * m.def.density * g.cell_volume() * sum;
    out.max_speed = fastest;
  }
}

void remove_covered_liquid(const Model& model, State& state, Workspace& ws) {
  if (!any_two_way(model)) return;
  capture_body_surfaces(model, state, ws);
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    place_liquid_solids(model, state, l, ws);
    const MovingSolids& moving = ws.liquids[l].moving;
    const MacGrid& g = model.liquids[l].grid;
    std::vector<Vec3>& markers = state.liquids[l].markers;
    std::vector<Vec3>& velocities = state.liquids[l].marker_velocity;  // empty unless flip
    std::size_t kept = 0;
    for (std::size_t m = 0; m < markers.size(); ++m) {
      const Eigen::Vector3i c = g.cell_of(markers[m]);
      if (g.interior(c.x(), c.y(), c.z()) &&
          moving.inside[static_cast<std::size_t>(g.index(c.x(), c.y(), c.z()))]) {
        continue;
      }
      if (!velocities.empty()) velocities[kept] = velocities[m];
      markers[kept++] = markers[m];
    }
    markers.resize(kept);
    if (!velocities.empty()) velocities.resize(kept);
  }
}

std::string describe_liquid_failure(const Model& model, const State& state) {
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    const LiquidModel& m = model.liquids[l];
    const LiquidState& s = state.liquids[l];
    const std::string name = "liquid '" + m.def.name + "'";
    static constexpr const char* kAxis[] = {"u", "v", "w"};
    for (int a = 0; a < 3; ++a) {
      if (const long c = first_not_finite(s.velocity.u[a]); c >= 0) {
        return name + ": velocity " + kAxis[a] + " became NaN or infinite at cell " +
               cell_text(m.grid, c);
      }
    }
    if (const long c = first_not_finite(s.pressure); c >= 0) {
      return name + ": pressure became NaN or infinite at cell " + cell_text(m.grid, c);
    }
    if (const long k = first_not_finite(s.markers); k >= 0) {
      return name + ": marker " + std::to_string(k) + " became NaN or infinite";
    }
    if (const long k = first_not_finite(s.chain); k >= 0) {
      return name + ": chain marker " + std::to_string(k) + " became NaN or infinite";
    }
    if (first_not_finite(s.height) >= 0) return name + ": the height field became NaN";
    if (s.overrun) {
      char text[400];
      std::snprintf(text, sizeof text,
                    ": %d substeps did not reach the frame's end (its CFL substeps shrank to "
                    "%.3g s, cfl %g): the flow is unstable; advection \"semi_lagrangian\" is "
                    "unconditionally stable, or raise max_substeps",
                    m.def.max_substeps, s.next_step, m.def.cfl);
      return name + text;
    }
  }
  return {};
}

void add_liquid_drawables(const Model& model, const Inputs& inputs, const State& state,
                          Workspace& ws, draw::Snapshot& snap) {
  (void)inputs;
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    const LiquidModel& m = model.liquids[l];
    const LiquidState& s = state.liquids[l];
    const MacGrid& g = m.grid;
    const Vec3 lo = m.def.domain.min, hi = m.def.domain.max;
    snap.focus.add(lo.cast<float>());
    snap.focus.add(hi.cast<float>());
    draw::Lines& outline = snap.lines.emplace_back();
    add_box_edges(lo, hi, kDomainColor, outline);
    if (m.def.section != LiquidSection::none) {
      // The cells as the state holds them (those a two-way body covers hold no markers).
      LiquidWorkspace& w = ws.liquids[l];
      label_cells(m, s, w.flags, w.fill, w.count);
      if (std::optional<draw::FieldSection> section = liquid_section(m, s, w.flags)) {
        snap.sections.push_back(std::move(*section));
      }
    }
    for (const LiquidBoxDef& box : m.def.solids) {
      const Vec3 a = box.min.cwiseMax(lo), b = box.max.cwiseMin(hi);
      snap.primitives.push_back({.shape = draw::PrimitiveShape::box,
                                 .center = (0.5 * (a + b)).cast<float>(),
                                 .half_size = (0.5 * (b - a)).cast<float>(),
                                 .material = kLiquidSolidMaterial});
    }
    if (m.def.surface == SurfaceMethod::height_field && m.vertical_axis == 2 && m.thin_axis < 0) {
      // The surface itself (16.3.3): one vertex per column at its centre.
      draw::HeightField& field = snap.height_fields.emplace_back();
      field.origin =
          Vec3(g.origin.x() + 0.5 * g.h.x(), g.origin.y() + 0.5 * g.h.y(), 0).cast<float>();
      field.cell = draw::Vec2f(static_cast<float>(g.h.x()), static_cast<float>(g.h.y()));
      field.nx = g.n.x();
      field.ny = g.n.y();
      field.heights.assign(s.height.begin(), s.height.end());
      field.material = kWaterSurfaceMaterial;
    } else if (m.def.surface == SurfaceMethod::height_field) {
      // A 2D liquid's surface (or one whose columns are not along z): the columns' tops joined
      // along the first horizontal axis.
      const ColumnAxes axes = column_axes(m);
      draw::Lines& surface = snap.lines.emplace_back();
      surface.layer = draw::Layer::scene;
      const int n0 = g.n[axes.h0], n1 = g.n[axes.h1];
      for (int i1 = 0; i1 < n1; ++i1) {
        for (int i0 = 0; i0 + 1 < n0; ++i0) {
          for (int side = 0; side < 2; ++side) {
            Vec3 x = g.centre(1, 1, 1);
            x[axes.h0] = g.origin[axes.h0] + (i0 + side + 0.5) * g.h[axes.h0];
            x[axes.h1] = g.origin[axes.h1] + (i1 + 0.5) * g.h[axes.h1];
            x[axes.v] = s.height[static_cast<std::size_t>(i0 + side + n0 * i1)];
            surface.points.push_back(x.cast<float>());
          }
          surface.colors.push_back(kWaterMaterial.color);
        }
      }
    } else if (!s.markers.empty() || !s.chain.empty()) {
      const LiquidDisplay display = m.def.display;
      if (display != LiquidDisplay::markers) {
        // The surface around the markers, from their level set (16.3.1, liquid_surface_mesh.h).
        // At half a cell's voxels: a display, rebuilt every frame drawn (0.1 s a frame for the
        // 32 x 16 x 16 dam break, against 0.4 s at the export's default of half the markers'
        // spacing, `pbm simulate --vdb-dir` with --surface-voxel 0.5 and 0.25).
        LiquidSurfaceMesh surface = liquid_surface_mesh(m, s, {.voxel = 0.5});
        auto positions = std::make_shared<std::vector<draw::Vec3f>>();
        positions->reserve(surface.positions.size());
        for (const Vec3& x : surface.positions) positions->push_back(x.cast<float>());
        auto topology = std::make_shared<draw::MeshTopology>();
        topology->triangles = std::move(surface.triangles);
        snap.meshes.push_back({.name = m.def.name,
                               .positions = std::move(positions),
                               .topology = std::move(topology),
                               .material = kWaterSurfaceMaterial});
      }
      // Spray and foam (liquid/spray.h), white points in the picture.
      for (const std::vector<Vec3>* particles : {&s.spray, &s.foam}) {
        if (particles->empty()) continue;
        draw::Points& points = snap.points.emplace_back();
        for (const Vec3& x : *particles) points.positions.push_back(x.cast<float>());
        points.colors.assign(particles->size(), particles == &s.spray ? kSprayColor : kFoamColor);
        points.size = particles == &s.spray ? 2.5f : 3.5f;
        points.layer = draw::Layer::scene;
      }
      if (display == LiquidDisplay::surface) continue;
      if (!s.chain.empty()) {
        // The chains are the surface (16.3.2): their links and markers, as the book drew them.
        draw::Lines& links = snap.lines.emplace_back();
        links.layer = draw::Layer::scene;
        for (std::size_t k = 0; k < s.chain.size(); ++k) {
          links.points.push_back(s.chain[k].cast<float>());
          links.points.push_back(s.chain[static_cast<std::size_t>(s.chain_next[k])].cast<float>());
          links.colors.push_back(kMarkerColor);
        }
      }
      // The marker particles are the liquid (16.3.1): drawn in the picture, not as an overlay.
      draw::Points& points = snap.points.emplace_back();
      const std::vector<Vec3>& markers = s.chain.empty() ? s.markers : s.chain;
      points.positions.reserve(markers.size());
      for (const Vec3& x : markers) points.positions.push_back(x.cast<float>());
      points.colors.assign(markers.size(), kMarkerColor);
      points.size = 3;
      points.layer = draw::Layer::scene;
    }
  }
}

}  // namespace pbm::stages
