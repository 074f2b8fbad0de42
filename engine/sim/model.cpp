#include "sim/model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "sim/figure_collisions.h"

namespace pbm {
namespace {

std::string body_path(int b) {
  return "bodies[" + std::to_string(b) + "]";
}

TrackModel build_track(const Scene& scene, int t) {
  const TrackDef& def = scene.tracks[t];
  const std::string path = "tracks[" + std::to_string(t) + "].target";
  TrackModel track;
  track.interpolation = def.interpolation;
  track.keys = def.keys;
  // The reader stored the target in its index form, checked against the scene; a Scene made in
  // code is checked the same way.
  std::string problem;
  const std::string stored = resolve_track_target(scene, def.target, problem);
  if (stored != def.target) {
    throw Error(
        scene.file, path,
        stored.empty() ? problem : "'" + def.target + "' is not in index form ('" + stored + "')");
  }
  const TrackTargetRef ref = *parse_track_target(def.target);
  track.target = ref.target;
  track.object = ref.object;
  track.index = ref.index;
  if (track.keys.empty())
    throw Error(scene.file, "tracks[" + std::to_string(t) + "].keys",
                "needs at least one keyframe");
  return track;
}

// A figure's step limit under the integrator: euler and implicit take its joint damping
// implicitly (sim/stages_figures.cpp), the Runge-Kutta ones explicitly.
const JointStepLimit& joint_step_limit(const CompiledFigure& figure, IntegratorKind kind) {
  const bool implicit_damping = kind == IntegratorKind::euler || kind == IntegratorKind::implicit;
  return implicit_damping ? figure.step_limit_implicit_damping : figure.step_limit_explicit_damping;
}

// Shortens the substep below every body's explicit stability limit for the configured
// integrator (sec. 6.1; deform/stability_limit.h), with 10% to spare, and says so in the notes:
// a step past the limit grows the fastest mode by a factor every step, an explosion the
// stability guard sees only once it is large. rk45 adapts its own steps and needs no limit; the
// implicit integrator takes the membrane at the step's end and needs only the global block's.
void limit_substep(Model& model) {
  const BodyModel* limiting = nullptr;
  model.substep = stable_substep(model, {}, &limiting);
  const Real frame = 1.0 / model.solver.fps;
  const Real taken = frame / std::max(1.0, std::ceil(frame / model.solver.dt - 1e-9));
  const Real limit = model.substep;
  char note[512];
  if (limiting == nullptr) {
    // A figure's explicit joint forces, if any, set the limit.
    for (const CompiledFigure& figure : model.figures) {
      const JointStepLimit& j = joint_step_limit(figure, model.solver.integrator);
      if (!(kStabilitySafety * j.step == limit)) continue;
      const std::string joint = figure.model.segments[j.segment].name;
      const std::string by =
          j.controller >= 0 ? "controller " + std::to_string(j.controller) + "'s explicit PD and"
                            : "its";
      std::snprintf(note, sizeof note,
                    "figure '%s', joint '%s' DOF %d: the substep %.3g s (solver.dt %g s) is past "
                    "the stability limit %.3g s of %s joint forces (stiffness %g, damping %g on "
                    "%.4g of inertia); substeps shortened to %.3g s (a stable_pd servo needs no "
                    "limit)",
                    figure.model.name.c_str(), joint.c_str(), j.dof, taken, model.solver.dt, j.step,
                    by.c_str(), j.stiffness, j.damping, j.inertia, limit);
      model.notes += (model.notes.empty() ? "" : "; ") + std::string(note);
      return;
    }
    return;
  }
  const StabilityLimit& s = limiting->stability;
  if (s.omega >= s.omega_shape && model.solver.integrator != IntegratorKind::implicit) {
    std::snprintf(note, sizeof note,
                  "body '%s': the substep %.3g s (solver.dt %g s) is past its explicit stability "
                  "limit %.3g s (fastest membrane mode %.4g rad/s, damping %g 1/s); substeps "
                  "shortened to %.3g s",
                  limiting->name.c_str(), taken, model.solver.dt, limit / kStabilitySafety, s.omega,
                  limiting->damping, limit);
  } else {
    std::snprintf(note, sizeof note,
                  "body '%s': the substep %.3g s (solver.dt %g s) is past the explicit stability "
                  "limit %.3g s of its shape parameters (inertia floor k_s tau^2, "
                  "solver.shape_inertia_time %g s: modes up to %.4g rad/s); substeps shortened "
                  "to %.3g s",
                  limiting->name.c_str(), taken, model.solver.dt, limit / kStabilitySafety,
                  1.0 / s.omega_shape, s.omega_shape, limit);
  }
  model.notes += (model.notes.empty() ? "" : "; ") + std::string(note);
}

}  // namespace

Real stable_substep(const Model& model, std::span<const std::uint8_t> dormant,
                    const BodyModel** limiting) {
  if (model.solver.integrator == IntegratorKind::rk45) return model.solver.dt;
  // The substep the frames take at solver.dt: a frame is divided into equal substeps.
  const Real frame = 1.0 / model.solver.fps;
  const Real taken = frame / std::max(1.0, std::ceil(frame / model.solver.dt - 1e-9));
  Real limit = taken;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    const StabilityLimit& s = body.stability;
    // A dormant "auto" body runs as a global one: only its global block limits the step.
    const bool global_only = b < dormant.size() && dormant[b] != 0;
    Real stable = 0;
    switch (model.solver.integrator) {
      case IntegratorKind::euler:
        stable = global_only ? s.dt_euler_global : s.dt_euler;
        break;
      case IntegratorKind::implicit:
        stable = s.dt_implicit;
        break;
      default:
        stable = global_only ? s.dt_rk4_global : s.dt_rk4;
        break;
    }
    if (kStabilitySafety * stable < limit) {
      limit = kStabilitySafety * stable;
      if (limiting) *limiting = &body;
    }
  }
  // Figures' explicit joint forces (figure/figure_controllers.h): their own limit, once.
  for (const CompiledFigure& figure : model.figures) {
    const Real step = joint_step_limit(figure, model.solver.integrator).step;
    if (kStabilitySafety * step < limit) {
      limit = kStabilitySafety * step;
      if (limiting) *limiting = nullptr;
    }
  }
  return limit < taken ? limit : model.solver.dt;
}

Model build_model(const Scene& scene) {
  Model model;
  model.scene = scene;
  model.gravity = scene.gravity;
  model.solver = scene.solver;
  if (scene.bodies.empty() && scene.figures.empty() && scene.liquids.empty()) {
    throw Error(scene.file, "bodies", "needs at least one body (or a figure or a liquid)");
  }
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    BodyModel body =
        build_body_model(scene.bodies[b], scene.solver.shape_inertia_time.value_or(scene.solver.dt),
                         scene.file, body_path(b));
    body.q_offset = model.n_q;
    body.v_offset = model.n_v;
    model.n_q += body.q_size;
    model.n_v += body.v_size;
    model.bodies.push_back(std::move(body));
  }
  for (std::size_t f = 0; f < scene.figures.size(); ++f) {
    CompiledFigure figure =
        build_figure_model(scene.figures[f], scene.file, "figures[" + std::to_string(f) + "]");
    figure.model.state_q_offset = model.n_q;
    figure.model.state_v_offset = model.n_v;
    model.n_q += figure.model.n_q;
    model.n_v += figure.model.n_v;
    // The controllers' first-order state follows the figure's q (figure/figure_build.h).
    figure.state_control_offset = model.n_q;
    model.n_q += figure.n_control;
    size_joint_limits(figure.model, figure.q0, scene.solver.dt, figure.limits);
    model.figures.push_back(std::move(figure));
  }
  settle_initial_segment_overlaps(model);
  for (std::size_t l = 0; l < scene.liquids.size(); ++l) {
    model.liquids.push_back(
        build_liquid_model(scene.liquids[l], scene.gravity, scene.file, static_cast<int>(l)));
  }
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
    model.obstacles.push_back(build_obstacle_model(scene.obstacles[o], scene.file,
                                                   "obstacles[" + std::to_string(o) + "]"));
  }
  model.force_fields = scene.force_fields;
  for (int s = 0; s < static_cast<int>(scene.springs.size()); ++s) {
    const SpringDef& def = scene.springs[s];
    const std::string path = "springs[" + std::to_string(s) + "]";
    if (def.body < 0 || def.body >= static_cast<int>(model.bodies.size())) {
      throw Error(scene.file, path + ".body", "no such body");
    }
    const BodyModel& body = model.bodies[def.body];
    SpringModel spring;
    spring.name = def.name;
    spring.body = def.body;
    if (def.node >= 0) {
      if (def.node >= body.n_nodes()) throw Error(scene.file, path + ".node", "no such node");
      spring.node = def.node;
    } else if (def.material_point) {
      spring.node = nearest_node(body.tessellation, *def.material_point);
    } else {
      throw Error(scene.file, path, "needs node or material_point");
    }
    spring.target = def.target;
    spring.stiffness = def.stiffness;
    spring.damping = def.damping;
    spring.t_begin = def.t_begin;
    spring.t_end = def.t_end;
    spring.max_force = def.max_force;
    model.springs.push_back(spring);
  }
  for (int t = 0; t < static_cast<int>(scene.tracks.size()); ++t) {
    model.tracks.push_back(build_track(scene, t));
    const TrackModel& track = model.tracks.back();
    if (track.target == TrackTarget::obstacle_point ||
        track.target == TrackTarget::obstacle_rotation) {
      model.obstacles[track.object].moving = true;
    }
  }
  model.constraints = build_constraints(scene.constraints, scene.bodies, model.bodies,
                                        {.alpha = scene.solver.constraint_alpha,
                                         .beta = scene.solver.constraint_beta,
                                         .solver = scene.solver.constraint_solver,
                                         .integrator = scene.solver.integrator,
                                         .dt = scene.solver.dt},
                                        scene.file);
  BodyCollisionOptions& options = model.body_collisions.options;
  options.enabled = scene.solver.body_collisions;
  options.self_collision = scene.solver.self_collision;
  options.friction = scene.solver.body_friction;
  options.elasticity = scene.solver.body_elasticity;
  options.margin = scene.solver.collision_margin;
  for (const std::string& note : model.constraints.notes) {
    model.notes += (model.notes.empty() ? "" : "; ") + note;
  }
  limit_substep(model);
  // Nothing but liquids: their own CFL substeps are the only ones, so the frame is one substep of
  // the World (solver.dt is the bodies' and figures' step).
  if (model.bodies.empty() && model.figures.empty()) model.substep = 1.0 / model.solver.fps;
  model.body_collisions.constrained.assign(model.bodies.size(), 0);
  for (const PointConstraintModel& c : model.constraints.points) {
    const int a = c.ends[0].body, b = c.ends[1].body;
    if (a >= 0 && b >= 0) model.body_collisions.joined.push_back({a, b});
    for (const ConstraintPoint& end : c.ends) {
      if (end.body >= 0) model.body_collisions.constrained[end.body] = 1;
    }
  }
  model.snapshot_geometry = build_snapshot_geometry(model.bodies, model.obstacles);
  return model;
}

}  // namespace pbm
