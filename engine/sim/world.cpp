#include "sim/world.h"

#include <chrono>
#include <cmath>
#include <cstring>

#include "collide/rigid_contact.h"
#include "constrain/hinge_spring.h"
#include "deform/reference_shape.h"
#include "deform/shape_parameters.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Nodal forces in the world frame: gravity and force fields (f in 3.47), the scene's springs
// and the user's mouse springs (sec. 6.4), and the damping D = nu M of second-order bodies.
void accumulate_external_forces(const Model& model, const Inputs& inputs, Real t, int b,
                                Workspace& ws) {
  const BodyModel& body = model.bodies[b];
  BodyWorkspace& bw = ws.bodies[b];
  const bool second = body.order == DynamicsOrder::second;
  Vec3 acceleration = ws.drive.gravity;
  Vec3 per_node = Vec3::Zero();
  for (const ForceFieldDef& field : model.force_fields) {
    bool applies = field.bodies.empty();
    for (int target : field.bodies) applies = applies || target == b;
    if (!applies) continue;
    if (field.kind == ForceFieldKind::acceleration)
      acceleration += field.value;
    else
      per_node += field.value;
  }
  for (int i = 0; i < body.n_nodes(); ++i) {
    const Real m = body.node_mass[i];
    bw.force[i] = m * acceleration + per_node;
    if (second) bw.force[i] -= body.damping * m * bw.x_dot[i];
  }
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& spring = model.springs[s];
    if (spring.body != b || t < spring.t_begin || t > spring.t_end) continue;
    const int i = spring.node;
    Vec3 f = ws.drive.spring_stiffness[s] * (ws.drive.spring_target[s] - bw.x[i]) -
             spring.damping * bw.x_dot[i];
    // A dragged point far from its body must not fling it: the pull saturates (mouse springs).
    const Real norm = f.norm();
    if (norm > spring.max_force) f *= spring.max_force / norm;
    bw.force[i] += f;
  }
  for (const MouseSpring& spring : inputs.springs) {
    if (spring.body != b || spring.node < 0 || spring.node >= body.n_nodes()) continue;
    const int i = spring.node;
    bw.force[i] += spring.stiffness * (spring.target - bw.x[i]) - spring.damping * bw.x_dot[i];
  }
}

// q-dot of one body from its velocity coordinates (quaternion kinematics, sec. 3.1.1).
void body_kinematic_rates(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                          const Eigen::Ref<const VecX>& v, Eigen::Ref<VecX> q_dot) {
  q_dot.segment<3>(0) = v.segment<3>(0);
  q_dot.segment<4>(3) = quaternion_rate(q.segment<4>(3), v.segment<3>(3));
  const int rest = body.q_size - 7;
  if (rest > 0) q_dot.segment(7, rest) = v.segment(6, rest);
}

void evaluate_derivative(const Model& model, const Inputs& inputs, Workspace& ws, Real t,
                         const VecX& q, const VecX& v, VecX& q_dot, VecX& v_dot) {
  evaluate_drive(model, t, ws.drive);
  ws.contacts = 0;
  for (int b = 0; b < static_cast<int>(model.bodies.size()); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    const auto qb = q.segment(body.q_offset, body.q_size);
    const auto vb = v.segment(body.v_offset, body.v_size);
    auto t0 = Clock::now();
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, qb, vb, bw);
    compute_elastic_forces(body, qb, bw);
    accumulate_external_forces(model, inputs, t, b, ws);
    factor_generalized_mass(body, qb, bw);  // the contact forces need the body's mobility
    ws.stage_seconds[static_cast<int>(StepStage::forces)] += seconds_since(t0);
    t0 = Clock::now();
    ws.contacts += add_contact_forces(ws.drive.obstacles, body, bw);
    ws.stage_seconds[static_cast<int>(StepStage::contact_forces)] += seconds_since(t0);
    t0 = Clock::now();
    auto out = v_dot.segment(body.v_offset, body.v_size);
    solve_body_dynamics(body, qb, vb, bw, out);
    ws.stage_seconds[static_cast<int>(StepStage::dynamics)] += seconds_since(t0);
  }
  // (7.3), (7.4): every body's unconstrained rates are known; the constraint forces couple them.
  if (!model.constraints.empty()) {
    const auto t0 = Clock::now();
    add_constraint_rates({model.constraints, model.bodies}, q, v, ws.bodies, ws.constraints, v_dot);
    ws.stage_seconds[static_cast<int>(StepStage::constraints)] += seconds_since(t0);
  }
  for (const BodyModel& body : model.bodies) {
    const auto qb = q.segment(body.q_offset, body.q_size);
    const auto vb = v.segment(body.v_offset, body.v_size);
    auto out = v_dot.segment(body.v_offset, body.v_size);
    auto qd = q_dot.segment(body.q_offset, body.q_size);
    if (body.order == DynamicsOrder::second) {
      body_kinematic_rates(body, qb, vb, qd);
    } else {
      // (3.51): the solve returned the velocity itself; v is not integrated.
      ws.first_order_velocity.segment(body.v_offset, body.v_size) = out;
      body_kinematic_rates(body, qb, out, qd);
      out.setZero();
    }
  }
}

void kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot) {
  for (const BodyModel& body : model.bodies) {
    if (body.order != DynamicsOrder::second) continue;
    body_kinematic_rates(body, q.segment(body.q_offset, body.q_size),
                         v.segment(body.v_offset, body.v_size),
                         q_dot.segment(body.q_offset, body.q_size));
  }
}

bool same_bits(const VecX& a, const VecX& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(Real) * static_cast<std::size_t>(a.size())) == 0;
}

bool all_finite(const State& s) {
  return s.q.allFinite() && s.v.allFinite();
}

// The scale a0, aspect ratios a1..a3 and squareness eps1, eps2 (the first six entries of every
// shape kind) must stay positive: a step that drives one through zero has diverged.
std::string describe_invalid_shape(const Model& model, const State& s) {
  for (const BodyModel& body : model.bodies) {
    for (int k = 0; k < std::min(body.n_s, 6); ++k) {
      const Real value = s.q[body.q_offset + 7 + k];
      if (!(value > 0)) {
        return "body '" + body.name + "': global parameter " + shape_parameter_name(body.shape, k) +
               " = " + std::to_string(value) + " left its valid range (must be > 0)";
      }
    }
  }
  return {};
}

// Names the body and the part of its state that is not finite.
std::string describe_nan(const Model& model, const State& s) {
  for (const BodyModel& body : model.bodies) {
    const auto q = s.q.segment(body.q_offset, body.q_size);
    const auto v = s.v.segment(body.v_offset, body.v_size);
    const char* what = nullptr;
    if (!q.segment<3>(0).allFinite() || !v.segment<3>(0).allFinite())
      what = "position q_c";
    else if (!q.segment<4>(3).allFinite() || !v.segment<3>(3).allFinite())
      what = "rotation q_theta";
    else if (body.n_s > 0 &&
             (!q.segment(7, body.n_s).allFinite() || !v.segment(6, body.n_s).allFinite()))
      what = "global deformation q_s";
    else if (!q.allFinite() || !v.allFinite())
      what = "local deformation q_d";
    if (what) return "body '" + body.name + "': " + what + " became NaN or infinite";
  }
  return "state became NaN or infinite";
}

// Kinetic energy moving obstacles may give the bodies in a frame from t0 to t1 [J]. An obstacle
// is infinitely massive: a body it meets at surface speed w leaves with up to 2 w (an elastic
// bounce, 5.11), so every body may gain 0.5 m (2 w)^2 with w the fastest surface point of any
// obstacle at the frame's start, middle or end. The surface speed is |v| + |omega| times the
// obstacle's reach from its point. 0 when nothing moves.
Real moving_obstacle_allowance(const Model& model, Real t0, Real t1) {
  bool any = false;
  for (const ObstacleModel& o : model.obstacles) any = any || o.moving;
  if (!any) return 0;
  std::vector<ObstacleModel> placed;
  Real w = 0;
  for (const Real t : {t0, 0.5 * (t0 + t1), t1}) {
    place_obstacles(model, t, placed);
    for (const ObstacleModel& o : placed) {
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
  return 0.5 * mass * (2 * w) * (2 * w);
}

}  // namespace

const char* stage_name(StepStage stage) {
  switch (stage) {
    case StepStage::forces:
      return "forces";
    case StepStage::contact_forces:
      return "contact_forces";
    case StepStage::dynamics:
      return "dynamics";
    case StepStage::constraints:
      return "constraints";
    case StepStage::integrate:
      return "integrate";
    case StepStage::collisions:
      return "collisions";
    case StepStage::count:
      break;
  }
  return "?";
}

void init_workspace(const Model& model, const Inputs& inputs, Workspace& ws) {
  ws.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    resize_workspace(model.bodies[b], ws.bodies[b]);
  ws.integrator.resize(model.n_q, model.n_v);
  ws.last_measured.valid = false;
  ws.first_order_velocity.setZero(model.n_v);
  init_constraint_workspace({model.constraints, model.bodies}, ws.constraints);
  evaluate_drive(model, 0, ws.drive);
  ws.inputs = &inputs;
  ws.stage_seconds.fill(0);
}

bool advance_substep(const Model& model, State& state, Real dt, Workspace& ws, int& evaluations) {
  auto t0 = Clock::now();
  for (BodyWorkspace& bw : ws.bodies) bw.dt = dt;
  // Self-collision follows each node from where it is now (collide/self_collision.h).
  record_step_start(model.bodies, state.q, state.v, state.time, dt, model.body_collisions.options,
                    ws.body_collisions.self);
  IntegrationStats istats;
  bool ok = true;
  auto derivative_seconds = [&ws] {
    return ws.stage_seconds[static_cast<int>(StepStage::forces)] +
           ws.stage_seconds[static_cast<int>(StepStage::contact_forces)] +
           ws.stage_seconds[static_cast<int>(StepStage::constraints)];
  };
  const double before = derivative_seconds();
  const Inputs& inputs = *ws.inputs;
  auto derivative = [&model, &inputs, &ws](Real t, const VecX& q, const VecX& v, VecX& q_dot,
                                           VecX& v_dot) {
    evaluate_derivative(model, inputs, ws, t, q, v, q_dot, v_dot);
  };
  auto kinematic = [&model](const VecX& q, const VecX& v, VecX& q_dot) {
    kinematic_rates(model, q, v, q_dot);
  };
  switch (model.solver.integrator) {
    case IntegratorKind::euler:
      euler_step(derivative, kinematic, state.time, dt, state.q, state.v, ws.integrator, istats);
      break;
    case IntegratorKind::rk4:
      rk4_step(derivative, state.time, dt, state.q, state.v, ws.integrator, istats);
      break;
    case IntegratorKind::rk45:
      ok = rk45_advance(derivative, state.time, dt, model.solver.tolerance, state.q, state.v,
                        state.rk45_step, ws.integrator, istats);
      break;
  }
  evaluations += istats.evaluations;
  state.time += dt;
  ws.stage_seconds[static_cast<int>(StepStage::integrate)] +=
      seconds_since(t0) - (derivative_seconds() - before);
  t0 = Clock::now();
  for (const BodyModel& body : model.bodies) {
    auto q = state.q.segment(body.q_offset, body.q_size);
    auto v = state.v.segment(body.v_offset, body.v_size);
    q.segment<4>(3).normalize();  // sec. 6.1: renormalize the quaternion every step
    if (body.order == DynamicsOrder::first) {
      v = ws.first_order_velocity.segment(body.v_offset, body.v_size);
    }
  }
  // Bodies against bodies first (5.2.2), then obstacles (5.2.1), so that no node is left inside
  // an obstacle by another body, then each local body with itself (its guarantee needs the
  // obstacles' moves inside the checked motion; collide/body_collisions.h): obstacles where their
  // tracks put them at the step's end, the time of the positions being resolved (the rest of the
  // drive stays at the last evaluation's time).
  place_obstacles(model, state.time, ws.drive.obstacles);
  const BodySet bodies{model.bodies, ws.bodies, state.q, state.v, state.time};
  ws.body_collision_stats =
      resolve_body_collisions(model.body_collisions, bodies, dt, ws.body_collisions);
  ws.contacts += ws.body_collision_stats.contacts;  // the end of 5.2.2's step reduction
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    resolve_penetrations(ws.drive.obstacles, body, state.q.segment(body.q_offset, body.q_size),
                         state.v.segment(body.v_offset, body.v_size), ws.bodies[b]);
  }
  resolve_body_self_collisions(model.body_collisions.options, bodies, dt, ws.body_collisions,
                               ws.body_collision_stats);
  state.contact_nodes = ws.contacts;
  ws.stage_seconds[static_cast<int>(StepStage::collisions)] += seconds_since(t0);
  return ok && all_finite(state);
}

void measure_state(const Model& model, const State& state, Workspace& ws, FrameStats& stats) {
  stats.time = state.time;
  stats.kinetic = stats.elastic = stats.potential = 0;
  stats.min_distance = 1e300;
  stats.bodies.resize(model.bodies.size());
  evaluate_drive(model, state.time, ws.drive);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    const auto q = state.q.segment(body.q_offset, body.q_size);
    const auto v = state.v.segment(body.v_offset, body.v_size);
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, q, v, bw);
    BodyEnergy e = compute_body_energy(body, q, v, ws.drive.gravity, bw);
    e.elastic += contact_potential_energy(ws.drive.obstacles, body, bw);
    stats.kinetic += e.kinetic;
    stats.elastic += e.elastic;
    stats.potential += e.potential;
    if (!model.obstacles.empty()) {
      stats.min_distance =
          std::min(stats.min_distance, min_obstacle_distance(ws.drive.obstacles, bw));
    }
    BodyFrameStats& bs = stats.bodies[b];
    bs.q_s = bw.q_s;
    bs.kinetic = e.kinetic;
    bs.elastic = e.elastic;
    bs.position = q.segment<3>(0);
  }
  if (!model.constraints.empty()) {
    const ConstrainedSystem system{model.constraints, model.bodies};
    stats.elastic += hinge_spring_energy(system, ws.bodies);
    stats.constraint_violation =
        measure_constraint_violations(system, state.q, ws.bodies, stats.constraint_violations);
  }
}

FrameResult advance_frame(const Model& model, State& state, Workspace& ws) {
  FrameResult result;
  const auto wall0 = Clock::now();
  const Real frame_dt = 1.0 / model.solver.fps;
  const Real t_end = (std::round(state.time * model.solver.fps) + 1.0) / model.solver.fps;
  const int base_substeps =
      std::max(1, static_cast<int>(std::ceil(frame_dt / model.solver.dt - 1e-9)));
  FrameStats before;
  const Workspace::Measured& last = ws.last_measured;
  if (last.valid && last.time == state.time && same_bits(last.q, state.q) &&
      same_bits(last.v, state.v)) {
    before = last.stats;  // ws.drive is still at this time too
  } else {
    measure_state(model, state, ws, before);
  }
  // Energy the frame may legitimately gain besides potential energy: a floor per body so bodies
  // starting at rest are not flagged, plus what the springs hold.
  Real floor = 0;
  for (const BodyModel& body : model.bodies)
    floor += body.mass * (ws.drive.gravity.norm() + 1.0) * 1e-2;
  // A spring ramped in (a studio drag) has no stiffness at the frame's start: count the larger
  // of its stiffnesses at the two ends, or grabbing a body at rest trips the guard.
  Drive end_drive;
  if (!model.springs.empty()) evaluate_drive(model, t_end, end_drive);
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& sp = model.springs[s];
    const Vec3 d = ws.drive.spring_target[s] - ws.bodies[sp.body].x[sp.node];
    const Real k = std::max(ws.drive.spring_stiffness[s], end_drive.spring_stiffness[s]);
    floor += k * d.squaredNorm();
  }
  floor += moving_obstacle_allowance(model, state.time, t_end);
  // Assembling parts (7.16) gain the kinetic energy Baumgarte's feedback gives them.
  if (!model.constraints.empty()) {
    floor +=
        constraint_energy_allowance({model.constraints, model.bodies}, state.q, state.v, ws.bodies);
  }
  const State start = state;
  ws.stage_seconds.fill(0);
  for (int attempt = 0; attempt <= model.solver.max_retries; ++attempt) {
    const int substeps = base_substeps << attempt;
    const Real h = frame_dt / substeps;
    bool ok = true;
    int evaluations = 0;
    int done = 0;
    for (int k = 0; k < substeps && ok; ++k) {
      // End of sec. 5.2.2: smaller steps while in contact, back to h after.
      if (model.solver.contact_step_reduction && state.contact_nodes > 0) {
        const int m = static_cast<int>(std::ceil(1.0 / model.solver.contact_dt_factor - 1e-9));
        for (int j = 0; j < m && ok; ++j)
          ok = advance_substep(model, state, h / m, ws, evaluations);
        done += m;
      } else {
        ok = advance_substep(model, state, h, ws, evaluations);
        ++done;
      }
    }
    FrameStats after;
    std::string failure;
    if (!ok || !all_finite(state)) {
      failure = describe_nan(model, state);
    } else if (failure = describe_invalid_shape(model, state); !failure.empty()) {
    } else {
      state.time = t_end;
      measure_state(model, state, ws, after);
      const Real e0 = before.kinetic + before.elastic;
      const Real e1 = after.kinetic + after.elastic;
      const Real allowed = model.solver.energy_growth_bound *
                           (e0 + std::abs(after.potential - before.potential) + floor);
      if (!(e1 <= allowed)) {
        failure = "kinetic+elastic energy grew from " + std::to_string(e0) + " J to " +
                  std::to_string(e1) + " J in one frame";
        for (std::size_t b = 0; b < model.bodies.size(); ++b) {
          if (after.bodies[b].kinetic + after.bodies[b].elastic >
              before.bodies[b].kinetic + before.bodies[b].elastic + 0.5 * (e1 - e0)) {
            failure = "body '" + model.bodies[b].name + "': " + failure;
            break;
          }
        }
      }
    }
    if (failure.empty()) {
      ws.last_measured.valid = true;
      ws.last_measured.time = state.time;
      ws.last_measured.q = state.q;
      ws.last_measured.v = state.v;
      ws.last_measured.stats = after;
      result.stats = after;
      result.stats.substeps = done;
      result.stats.retries = attempt;
      result.stats.evaluations = evaluations;
      result.stats.contacts = state.contact_nodes;
      result.stats.stage_seconds = ws.stage_seconds;
      for (const std::string& note : model.constraints.notes) {
        result.stats.notes += (result.stats.notes.empty() ? "" : "; ") + note;
      }
      result.stats.wall_seconds = seconds_since(wall0);
      return result;
    }
    state = start;
    state.rk45_step = 0;  // the retry starts with the whole substep
    result.message = failure;
  }
  result.ok = false;
  result.message += " (after " + std::to_string(model.solver.max_retries) +
                    " retries with halved substeps, at t = " + std::to_string(state.time) + " s)";
  result.stats = before;
  result.stats.wall_seconds = seconds_since(wall0);
  return result;
}

}  // namespace pbm
