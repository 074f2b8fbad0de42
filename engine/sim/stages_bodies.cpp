#include "sim/stages_bodies.h"

#include <algorithm>

#include "collide/implicit_contact.h"
#include "deform/body_dynamics.h"
#include "deform/implicit_membrane.h"
#include "deform/nodal_loads.h"
#include "deform/shape_parameters.h"
#include "sim/snapshot_geometry.h"

namespace pbm::stages {

namespace {

// The overlay's spring colour (the renderer's before springs became drawables).
const draw::Vec3f kSpringColor(0.95f, 0.85f, 0.2f);

}  // namespace

bool bodies_present(const Model& model) {
  return !model.bodies.empty();
}

void size_bodies(const Model& model, Workspace& ws) {
  ws.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    resize_workspace(model.bodies[b], ws.bodies[b]);
    // Only a scene that asks for the implicit integrator pays for K_dd's factor.
    if (model.solver.integrator == IntegratorKind::implicit) {
      prepare_implicit_membrane(model.bodies[b], ws.bodies[b]);
      prepare_implicit_contact(model.bodies[b], ws.bodies[b]);
    }
  }
  ws.first_order_velocity.setZero(model.n_v);
}

void body_step_start(const SubstepContext& c) {
  for (BodyWorkspace& bw : c.ws.bodies) bw.dt = c.dt;
}

void body_forces(const RateContext& c) {
  const Drive& drive = c.ws.drive;
  const NodalLoadDrive loads{drive.gravity, drive.spring_target, drive.spring_stiffness};
  for (int b = 0; b < static_cast<int>(c.model.bodies.size()); ++b) {
    const BodyModel& body = c.model.bodies[b];
    BodyWorkspace& bw = c.ws.bodies[b];
    const auto qb = body_q(body, c.q);
    const auto vb = body_v(body, c.v);
    bw.q_s_rest = drive.q_s0[b];
    compute_body_kinematics(body, qb, vb, bw);
    compute_elastic_forces(body, qb, bw);
    compute_nodal_loads(body, b, c.model.force_fields, c.model.springs, loads, c.t, bw);
    factor_generalized_mass(body, qb, bw);  // contact forces need the body's mobility
  }
}

void body_dynamics(const RateContext& c) {
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    const BodyModel& body = c.model.bodies[b];
    auto out = body_v(body, c.v_dot);
    BodyWorkspace& bw = c.ws.bodies[b];
    solve_body_dynamics(body, body_q(body, c.q), body_v(body, c.v), bw, out);
    if (c.model.solver.integrator == IntegratorKind::implicit) {
      if (!bw.dormant) implicit_membrane_rates(body, body_v(body, c.v), bw, bw.dt, out);
      implicit_row_damping(body, bw.dt, out);
      implicit_contact_rates(body, bw, out);
    }
  }
}

namespace {

// q-dot of one body from its velocity coordinates (quaternion kinematics, sec. 3.1.1): q_c-dot =
// c-dot, q_theta-dot = 1/2 q_theta (x) (0, omega), and the rest are their own rates.
void rates_of_body(const BodyModel& body, const Eigen::Ref<const VecX>& q,
                   const Eigen::Ref<const VecX>& v, Eigen::Ref<VecX> q_dot) {
  position_of(q_dot) = velocity_of(v);
  quaternion_of(q_dot) = quaternion_rate(quaternion_of(q), omega_of(v));
  const int rest = body.layout.q_after_rigid();
  if (rest > 0) {
    q_dot.segment(BodyLayout::kShapeInQ, rest) = v.segment(BodyLayout::kShapeInV, rest);
  }
}

}  // namespace

void body_kinematics(const RateContext& c) {
  for (const BodyModel& body : c.model.bodies) {
    const auto qb = body_q(body, c.q);
    const auto vb = body_v(body, c.v);
    auto out = body_v(body, c.v_dot);
    auto qd = body_q(body, c.q_dot);
    if (body.order == DynamicsOrder::second) {
      rates_of_body(body, qb, vb, qd);
    } else {
      // (3.51): the solve returned the velocity itself; v is not integrated.
      body_v(body, c.ws.first_order_velocity) = out;
      rates_of_body(body, qb, out, qd);
      out.setZero();
    }
  }
}

void body_kinematic_rates(const Model& model, const VecX& q, const VecX& v, VecX& q_dot) {
  for (const BodyModel& body : model.bodies) {
    if (body.order != DynamicsOrder::second) continue;
    rates_of_body(body, body_q(body, q), body_v(body, v), body_q(body, q_dot));
  }
}

void body_renormalize(const SubstepContext& c) {
  for (const BodyModel& body : c.model.bodies) {
    auto q = body_q(body, c.state.q);
    auto v = body_v(body, c.state.v);
    quaternion_of(q).normalize();  // sec. 6.1: renormalize the quaternion every step
    if (body.order == DynamicsOrder::first) v = body_v(body, c.ws.first_order_velocity);
  }
}

bool velocity_split_needed(const Model& model) {
  return model.obstacles.empty();
}

void body_velocity_split(const SubstepContext& c) {
  // Once a frame, at a fixed time: restored after every substep, the split made the result
  // depend on how many substeps a frame took at first order (it moves velocity into the shape
  // parameters, whose inertia floor carries it), and RK4 converged at order 1.
  if (!c.ws.substep_ends_frame) return;
  for (std::size_t b = 0; b < c.model.bodies.size(); ++b) {
    const BodyModel& body = c.model.bodies[b];
    restore_velocity_split(body, body_q(body, c.state.q), body_v(body, c.state.v), c.ws.bodies[b]);
  }
}

void measure_bodies(const Model& model, const Inputs& /*inputs*/, const State& state, Workspace& ws,
                    FrameStats& stats) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    const auto q = body_q(body, state.q);
    const auto v = body_v(body, state.v);
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, q, v, bw);
    const BodyEnergy e = compute_body_energy(body, q, v, ws.drive.gravity, bw);
    BodyFrameStats& bs = stats.bodies[b];
    bs.q_s = bw.q_s;
    bs.kinetic = e.kinetic;
    bs.elastic = e.elastic;
    const NodalLoadDrive loads{ws.drive.gravity, ws.drive.spring_target, ws.drive.spring_stiffness};
    bs.potential = e.potential + nodal_load_potential(body, static_cast<int>(b), model.force_fields,
                                                      model.springs, loads, state.time, bw);
    bs.position = position_of(q);
  }
}

Real body_energy_allowance(const Model& model, const Inputs& inputs, const State& state, Real t_end,
                           Workspace& ws) {
  (void)state;
  // A floor per body so bodies starting at rest are not flagged, plus what the springs hold.
  Real floor = 0;
  for (const BodyModel& body : model.bodies) {
    floor += body.mass * (ws.drive.gravity.norm() + 1.0) * 1e-2;
  }
  if (model.springs.empty()) return floor;
  // A spring ramped in (a studio drag) has no stiffness at the frame's start: count the larger
  // of its stiffnesses at the two ends, or grabbing a body at rest trips the guard.
  evaluate_drive(model, inputs, t_end, ws.end_drive);
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& sp = model.springs[s];
    const Vec3 d = ws.drive.spring_target[s] - ws.bodies[sp.body].x[sp.node];
    const Real k = std::max(ws.drive.spring_stiffness[s], ws.end_drive.spring_stiffness[s]);
    floor += k * d.squaredNorm();
  }
  return floor;
}

namespace {

// The scale a0, aspect ratios a1..a3 and squareness eps1, eps2 (the first six entries of every
// shape kind) must stay positive: a step that drives one through zero has diverged.
std::string describe_invalid_shape(const Model& model, const State& s) {
  for (const BodyModel& body : model.bodies) {
    const auto q_s = shape_of(body.layout, body_q(body, s.q));
    for (int k = 0; k < std::min(body.n_s, 6); ++k) {
      const Real value = q_s[k];
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
    const auto q = body_q(body, s.q);
    const auto v = body_v(body, s.v);
    const BodyLayout& l = body.layout;
    const char* what = nullptr;
    if (!position_of(q).allFinite() || !velocity_of(v).allFinite())
      what = "position q_c";
    else if (!quaternion_of(q).allFinite() || !omega_of(v).allFinite())
      what = "rotation q_theta";
    else if (body.n_s > 0 && (!shape_of(l, q).allFinite() || !shape_rate_of(l, v).allFinite()))
      what = "global deformation q_s";
    else if (!q.allFinite() || !v.allFinite())
      what = "local deformation q_d";
    if (what) return "body '" + body.name + "': " + what + " became NaN or infinite";
  }
  return {};
}

}  // namespace

std::string describe_body_failure(const Model& model, const State& state) {
  if (!state.q.allFinite() || !state.v.allFinite()) return describe_nan(model, state);
  return describe_invalid_shape(model, state);
}

void add_body_drawables(const Model& model, const Inputs& inputs, const State& state, Workspace& ws,
                        draw::Snapshot& snap) {
  (void)inputs;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, body_q(body, state.q), body_v(body, state.v), bw, false);
    auto positions = std::make_shared<std::vector<draw::Vec3f>>(bw.x.size());
    for (std::size_t i = 0; i < bw.x.size(); ++i) {
      (*positions)[i] = bw.x[i].cast<float>();
      snap.focus.add((*positions)[i]);
    }
    draw::Mesh& mesh = snap.meshes.emplace_back();
    mesh.name = body.name;
    mesh.pick = static_cast<int>(b);
    mesh.positions = std::move(positions);
    mesh.topology = model.snapshot_geometry.body_topology[b];
    mesh.material = {body.color.cast<float>(), static_cast<float>(body.roughness)};
    mesh.shading = draw::Shading::smooth;
  }
  // Springs active at this time, from the body point to the target (overlay).
  draw::Lines springs{.end_points = true, .layer = draw::Layer::overlay};
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& spring = model.springs[s];
    if (state.time < spring.t_begin || state.time > spring.t_end) continue;
    springs.points.push_back(ws.bodies[spring.body].x[spring.node].cast<float>());
    springs.points.push_back(ws.drive.spring_target[s].cast<float>());
    springs.colors.push_back(kSpringColor);
  }
  if (!springs.points.empty()) snap.lines.push_back(std::move(springs));
}

}  // namespace pbm::stages
