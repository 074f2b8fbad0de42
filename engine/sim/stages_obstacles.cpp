#include "sim/stages_obstacles.h"

#include <algorithm>

#include "collide/rigid_contact.h"

namespace pbm::stages {

namespace {

// The obstacles' look (the renderer's before obstacles became drawables; the goldens hold it).
const draw::Material kObstacleMaterial{{0.45f, 0.52f, 0.62f}, 0.6f};

}  // namespace

bool obstacles_present(const Model& model) {
  return !model.obstacles.empty();
}

void obstacle_forces(const RateContext& c) {
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    c.ws.contacts += add_contact_forces(c.ws.drive.obstacles, c.model.bodies[b], c.ws.bodies[b]);
  }
}

void obstacle_collisions(const SubstepContext& c) {
  resolve_obstacle_penetrations(c, {});
}

void resolve_obstacle_penetrations(const SubstepContext& c, std::span<const char> only) {
  // Obstacles where their tracks put them at the step's end, the time of the positions being
  // resolved (the rest of the drive stays at the last evaluation's time).
  place_obstacles(c.model, c.inputs, c.state.time, c.ws.drive.obstacles);
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    if (!only.empty() && !only[b]) continue;
    const BodyModel& body = c.model.bodies[b];
    // A dormant "auto" body has no implicit factor this substep (sim/level_of_detail.h): one a
    // collision reaches anyway is projected as the explicit integrators do.
    resolve_penetrations(
        c.ws.drive.obstacles, body, body_q(body, c.state.q), body_v(body, c.state.v),
        c.ws.bodies[b],
        c.model.solver.integrator == IntegratorKind::implicit && !c.ws.bodies[b].dormant);
  }
}

void measure_obstacles(const Model& model, const Inputs& /*inputs*/, const State& state,
                       Workspace& ws, FrameStats& stats) {
  (void)state;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    BodyWorkspace& bw = ws.bodies[b];
    stats.bodies[b].elastic += contact_potential_energy(ws.drive.obstacles, model.bodies[b], bw);
    stats.min_distance =
        std::min(stats.min_distance, min_obstacle_distance(ws.drive.obstacles, bw));
  }
}

// Kinetic energy moving obstacles may give the bodies and figures in a frame from t0 to t1 [J]. An
// obstacle is infinitely massive: a body or segment it meets at surface speed w leaves with up to
// 2 w (an elastic bounce, 5.11; e = 1 in (15.2)), so every one may gain 0.5 m (2 w)^2 with w the
// fastest surface point of any obstacle at the frame's start, middle or end. The surface speed is
// |v| + |omega| times the obstacle's reach from its point. 0 when nothing moves.
Real obstacle_energy_allowance(const Model& model, const Inputs& inputs, const State& state,
                               Real t_end, Workspace& ws) {
  bool any = false;
  for (const ObstacleModel& o : model.obstacles) any = any || o.moving;
  if (!any) return 0;
  const Real t0 = state.time;
  Real w = 0;
  for (const Real t : {t0, 0.5 * (t0 + t_end), t_end}) {
    place_obstacles(model, inputs, t, ws.placed);
    for (const ObstacleModel& o : ws.placed) {
      if (!o.moving) continue;
      Real reach = 0.5 * o.size.norm();
      if (o.kind == ObstacleKind::box) reach = o.half_extents.norm();
      if (o.kind == ObstacleKind::mesh) {
        const Vec3 centre = 0.5 * (o.mesh->lower + o.mesh->upper);
        reach = (o.mesh->upper - o.mesh->lower).norm() + (o.mesh->position - centre).norm();
      }
      w = std::max(w, o.velocity.norm() + o.angular_velocity.norm() * reach);
    }
  }
  Real mass = 0;
  for (const BodyModel& body : model.bodies) mass += body.mass;
  for (const CompiledFigure& figure : model.figures) {
    for (const SegmentModel& segment : figure.model.segments) mass += segment.inertia.m;
  }
  return 0.5 * mass * (2 * w) * (2 * w);
}

void add_obstacle_drawables(const Model& model, const Inputs& inputs, const State& state,
                            Workspace& ws, draw::Snapshot& snap) {
  (void)inputs;
  (void)state;
  // Where the tracks put each obstacle at this time (make_snapshot's drive placed them).
  for (std::size_t k = 0; k < ws.drive.obstacles.size(); ++k) {
    const ObstacleModel& o = ws.drive.obstacles[k];
    switch (o.kind) {
      case ObstacleKind::plane:
        snap.planes.push_back(
            {o.point.cast<float>(), o.normal.cast<float>(), o.size.cast<float>()});
        break;
      case ObstacleKind::box:
        snap.primitives.push_back({.shape = draw::PrimitiveShape::box,
                                   .center = o.point.cast<float>(),
                                   .rotation = o.rotation.cast<float>(),
                                   .half_size = o.half_extents.cast<float>(),
                                   .material = kObstacleMaterial});
        break;
      case ObstacleKind::mesh: {
        draw::Mesh& mesh = snap.meshes.emplace_back();
        mesh.name = o.name;
        mesh.positions = model.snapshot_geometry.obstacle_positions[k];
        mesh.topology = model.snapshot_geometry.obstacle_topology[k];
        mesh.material = kObstacleMaterial;
        mesh.shading = draw::Shading::flat;
        // x = R R0^T (x0 - p0) + p: the load placement's vertices carried to the current one.
        const Mat3 motion = o.rotation * o.mesh->rotation.transpose();
        mesh.rotation = motion.cast<float>();
        mesh.offset = (o.point - motion * o.mesh->position).cast<float>();
        break;
      }
    }
  }
}

}  // namespace pbm::stages
