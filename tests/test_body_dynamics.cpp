// Lagrangian dynamics of one body (ch. 3): the inertial forces g_q, the mean-axis split and the
// global stiffness, checked against conservation laws and closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "deform/body_dynamics.h"
#include "deform/shape_parameters.h"
#include "deform/superquadric.h"
#include "scene_builders.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

struct Totals {
  Real energy = 0;
  Vec3 p = Vec3::Zero(), l = Vec3::Zero();
};

Totals totals(Simulation& sim) {
  const Model& model = sim.model;
  const State& state = sim.state;
  Workspace& ws = sim.ws;
  FrameStats stats;
  measure_state(sim.world, sim.inputs, state, ws, stats);
  Totals t;
  t.energy = stats.kinetic + stats.elastic;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyEnergy e = compute_body_energy(
        model.bodies[b], state.q.segment(model.bodies[b].q_offset, model.bodies[b].q_size),
        state.v.segment(model.bodies[b].v_offset, model.bodies[b].v_size), model.gravity,
        ws.bodies[b]);
    t.p += e.linear_momentum;
    t.l += e.angular_momentum;
  }
  return t;
}

// A free body spinning about a tilted axis while its global and local coordinates oscillate:
// with no external force and no damping, sum m x-dot and sum m x cross x-dot are conserved
// exactly by (3.13) and the energy by the Lagrangian structure, if and only if g_q (3.24) is
// right. RK4 at a small step keeps the discretization error far below the tolerances.
// The body alone, no gravity, RK4 at 2 ms in 20 ms frames: the accurate setting of these tests.
Scene accurate_free_space(const BodyDef& body) {
  Scene scene = test::free_space(body);
  scene.solver.integrator = IntegratorKind::rk4;
  scene.solver.dt = 2e-3;
  scene.solver.fps = 50;
  return scene;
}

TEST(BodyDynamics, SpinningDeformingFreeBodyConservesMomentaAndEnergy) {
  BodyDef body = test::ball(DeformLevel::local, 8);
  body.velocity = Vec3(0.3, -0.2, 0.1);
  body.angular_velocity = Vec3(0.5, 1.5, 2.5);
  test::Simulation sim(accurate_free_space(body));
  const Model& model = sim.model;
  State& state = sim.state;
  // Excite q_s (a1 stretched) and q_d (a bump at one node) so both deform while spinning.
  const BodyModel& b = model.bodies[0];
  state.v[6 + 1] = 0.4;
  state.q[7 + 6 + 3 * 10 + 2] = 0.05;
  const Totals t0 = totals(sim);
  ASSERT_GT(t0.energy, 1.0);
  Real max_rel_p = 0, max_rel_l = 0, max_rel_e = 0;
  for (int frame = 0; frame < 500; ++frame) {  // 10 s
    FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    const Totals t = totals(sim);
    max_rel_p = std::max(max_rel_p, (t.p - t0.p).norm() / t0.p.norm());
    max_rel_l = std::max(max_rel_l, (t.l - t0.l).norm() / t0.l.norm());
    max_rel_e = std::max(max_rel_e, std::abs(t.energy - t0.energy) / t0.energy);
  }
  // The body really deformed and turned.
  EXPECT_GT(std::abs(state.q[7 + 1] - 1.0) + std::abs(state.q[7 + 6 + 3 * 10 + 2]), 1e-3);
  EXPECT_LT(max_rel_p, 1e-6);
  EXPECT_LT(max_rel_l, 1e-6);
  EXPECT_LT(max_rel_e, 1e-3);
  RecordProperty("max_rel_linear_momentum", std::to_string(max_rel_p));
  RecordProperty("max_rel_angular_momentum", std::to_string(max_rel_l));
  RecordProperty("max_rel_energy", std::to_string(max_rel_e));
  std::printf("relative drift over 10 s: linear %.3g angular %.3g energy %.3g (n_v = %d)\n",
              max_rel_p, max_rel_l, max_rel_e, b.v_size);
}

}  // namespace
}  // namespace pbm

namespace pbm {
namespace {

// The mass block (3.16) as the superquadric's sparse pass and the run-time path assemble it,
// against sum_i m_i P_i^T P_i built node by node from P_i = [I, -p~_i, J_i] (3.14), plus the
// parameter inertia floor and the gauge term: for a deformed, spinning superquadric (n_s = 6) and
// a tapered, bent one (n_s = 11).
TEST(BodyDynamics, MassBlockIsTheSumOfTheNodesPTransposeP) {
  for (const ShapeKind shape : {ShapeKind::superquadric, ShapeKind::taper_bend}) {
    BodyDef b = test::ball(DeformLevel::local, 8);
    b.shape = shape;
    b.q_s = default_shape_parameters(shape);
    b.q_s[1] = 1.3;
    b.q_s[4] = 0.7;
    if (shape == ShapeKind::taper_bend) b.q_s[6] = 0.2;
    b.q_s0 = b.q_s;
    b.k_s = VecX::Constant(b.q_s.size(), 2000.0);
    b.angular_velocity = Vec3(0.3, 1.0, 2.0);
    Simulation sim(test::free_space(b));
    const BodyModel& body = sim.model.bodies[0];
    auto q = body_q(body, sim.state.q);
    auto d = displacement_of(body.layout, q);
    for (int i = 0; i < d.size(); ++i) d[i] = 0.03 * std::sin(1.3 * i);
    BodyWorkspace& ws = sim.ws.bodies[0];
    const auto qc = body_q(body, std::as_const(sim.state.q));
    const auto vc = body_v(body, std::as_const(sim.state.v));
    compute_body_kinematics(body, qc, vc, ws);
    factor_generalized_mass(body, qc, ws);
    const int k = body.n_generalized(), ns = body.n_s;
    ASSERT_EQ(ns, shape_parameter_count(shape));
    MatX expected = MatX::Zero(k, k);
    for (int i = 0; i < body.n_nodes(); ++i) {
      MatX P = MatX::Zero(3, k);
      P.leftCols(3) = Mat3::Identity();
      P.middleCols(3, 3) = -skew(ws.p[i]);
      P.rightCols(ns) = ws.Jt.middleCols(3 * i, 3).transpose();
      expected += body.node_mass[i] * P.transpose() * P;
    }
    const VecX n = gauge_direction(ws.q_s);
    expected.bottomRightCorner(ns, ns).diagonal() += body.parameter_inertia_floor;
    expected.bottomRightCorner(ns, ns) += body.parameter_inertia * n * n.transpose();
    EXPECT_LT((ws.A - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff())
        << "shape " << static_cast<int>(shape);
  }
}

// The superquadric's kinematics pass writes s_i and J_i itself (deform/body_dynamics.cpp,
// superquadric_kinematics): s_i must be bitwise (2.7) as evaluate_superquadric gives it (the
// contact pass reuses whichever computed it), J_i its (2.9), p_i-dot = J_i q_s-dot + d_i-dot and
// the velocity-product acceleration J-dot q_s-dot as superquadric_second_derivative's series give
// it, at a shape away from the sphere with every q_s moving.
TEST(BodyDynamics, SuperquadricKinematicsAreTheShapesAndItsJacobian) {
  BodyDef b = test::ball(DeformLevel::local, 8);
  b.q_s = default_shape_parameters(ShapeKind::superquadric);
  b.q_s[1] = 1.3;
  b.q_s[3] = 0.8;
  b.q_s[4] = 0.7;
  b.q_s[5] = 1.4;
  b.q_s0 = b.q_s;
  b.k_s = VecX::Constant(b.q_s.size(), 2000.0);
  Simulation sim(test::free_space(b));
  const BodyModel& body = sim.model.bodies[0];
  ASSERT_EQ(body.n_s, 6);
  auto v = body_v(body, sim.state.v);
  auto d_dot = v.segment(body.layout.displacement_in_v(), 3 * body.n_nodes());
  for (int i = 0; i < d_dot.size(); ++i) d_dot[i] = 0.02 * std::cos(0.7 * i);
  VecX q_s_dot(6);
  q_s_dot << 0.3, -0.2, 0.5, 0.1, -0.4, 0.6;
  v.segment(BodyLayout::kShapeInV, 6) = q_s_dot;
  BodyWorkspace& ws = sim.ws.bodies[0];
  const auto qc = body_q(body, std::as_const(sim.state.q));
  const auto vc = body_v(body, std::as_const(sim.state.v));
  compute_body_kinematics(body, qc, vc, ws);
  const VecX q_s = shape_of(body.layout, qc);
  for (int i = 0; i < body.n_nodes(); ++i) {
    Vec3 same_basis, e;
    SuperquadricJacobian J;
    evaluate_superquadric(q_s, ws.basis[i], 1.0, same_basis, nullptr);
    EXPECT_EQ(ws.s[i], same_basis) << "node " << i;  // bitwise
    evaluate_superquadric(q_s, body.node_angles[i], 1.0, e, &J);
    EXPECT_LT((ws.s[i] - e).norm(), 1e-14) << "node " << i;
    const MatX Jt = ws.Jt.middleCols(3 * i, 3);
    EXPECT_LT((Jt.transpose() - J).cwiseAbs().maxCoeff(), 1e-13) << "node " << i;
    const Vec3 expected = J * q_s_dot + d_dot.segment<3>(3 * i);
    EXPECT_LT((ws.p_dot[i] - expected).norm(), 1e-13) << "node " << i;
    // With no spin, the velocity-product acceleration (3.18) is J-dot q_s-dot alone.
    const Vec3 jq =
        superquadric_second_derivative(q_s, ws.basis[i], body.node_angles[i], 1.0, q_s_dot);
    EXPECT_LT((ws.a_vp[i] - jq).norm(), 1e-12 * (1 + jq.norm())) << "node " << i;
  }
}

TEST(BodyDynamics, LumpedMassSumsToTheBodyMass) {
  for (int resolution : {6, 16}) {
    BodyDef body = test::ball(DeformLevel::local, resolution);
    body.material.nodal_mass = 0;
    body.material.mass = 7.5;
    const Model model = build_model(test::free_space(body));
    EXPECT_NEAR(model.bodies[0].node_mass.sum(), 7.5, 1e-12);
    body.material.mass = 0;
    body.material.nodal_mass = 8.0;  // the book's jello-ball gives the mass per node
    const Model per_node = build_model(test::free_space(body));
    EXPECT_NEAR(per_node.bodies[0].mass, 8.0 * (2 + resolution * resolution), 1e-9);
  }
}

// (3.31)-(3.33): after an impulse on a global parameter, the Hookean force k_s (q_s - q_s0)
// brings it back to its rest value. With D = nu M the oscillation decays like exp(-nu t / 2).
TEST(BodyDynamics, GlobalDeformationImpulseReturnsToRestValue) {
  BodyDef body = test::ball(DeformLevel::global, 8);
  body.material.damping = 2.0;
  test::Simulation sim(accurate_free_space(body));
  const Model& model = sim.model;
  State& state = sim.state;
  state.v[6 + 1] = 2.0;  // impulse on a1 (stretch along x)
  Real max_excursion = 0;
  for (int frame = 0; frame < 500; ++frame) {
    ASSERT_TRUE(advance_frame(sim).ok);
    max_excursion = std::max(max_excursion, std::abs(state.q[7 + 1] - 1.0));
  }
  EXPECT_GT(max_excursion, 0.05);  // it really deformed
  const VecX q_s = state.q.segment(7, 6);
  const VecX q_s0 = model.bodies[0].q_s0;
  // The shape is back: every point of s within 1e-4 of the rest shape. (Along the gauge
  // direction a0 a_i is what matters, so compare products, not raw entries.)
  for (int i = 1; i <= 3; ++i) EXPECT_NEAR(q_s[0] * q_s[i], q_s0[0] * q_s0[i], 1e-4) << i;
  EXPECT_NEAR(q_s[4], q_s0[4], 1e-4);
  EXPECT_NEAR(q_s[5], q_s0[5], 1e-4);
}

// (3.51): the first-order model D q-dot + K q = f_q settles where the generalized forces balance.
// Two springs pull the poles of a local body apart; at rest the solve gives zero velocity and the
// displacement is what K_dd and K_ss balance against f_q.
TEST(BodyDynamics, FirstOrderModelReachesEquilibrium) {
  BodyDef body = test::ball(DeformLevel::local, 8);
  body.order = DynamicsOrder::first;
  body.material.damping = 1.0;
  Scene scene = test::free_space(body);
  scene.solver.dt = 5e-4;
  scene.solver.fps = 10;
  // The global block's inertia floor k_s tau^2 decays a first-order body's light parameters at
  // 1 / (nu tau^2) (deform/stability_limit.h): at tau = dt that is a 5e-7 s Euler limit, six
  // million substeps for this test. tau = 20 ms lets the membrane set the step.
  scene.solver.shape_inertia_time = 0.02;
  SpringDef north, south;
  north.node = 2 + 8 * 8 - 1;
  north.target = Vec3(0, 0, 1.5);
  north.stiffness = 50;
  north.damping = 0;
  south.node = 0;
  south.target = Vec3(0, 0, -1.5);
  south.stiffness = 50;
  south.damping = 0;
  scene.springs = {north, south};
  test::Simulation sim(scene);
  Workspace& ws = sim.ws;
  State& state = sim.state;
  // The speed of the very first substep: the springs' full pull against an undeformed body.
  State probe = state;
  int evaluations = 0;
  advance_substep(sim.world, sim.inputs, probe, scene.solver.dt, ws, evaluations);
  const Real first_speed = probe.v.norm();
  ASSERT_GT(first_speed, 1.0);
  for (int frame = 0; frame < 30; ++frame) ASSERT_TRUE(advance_frame(sim).ok);
  // q-dot = (nu M)^+ (f_q - K q) has fallen by more than 1e4: the forces balance. (What remains,
  // ~1e-3 m/s and decaying, is the slow exchange between q_s and the part of q_d that looks like
  // a global deformation, whose velocity the mean-axis split holds at zero.)
  EXPECT_LT(state.v.norm(), 1e-4 * first_speed);
  // And the poles were really pulled apart (the springs did work against K).
  FrameStats stats;
  measure_state(sim.world, sim.inputs, state, ws, stats);
  const Real height = ws.bodies[0].x[north.node].z() - ws.bodies[0].x[0].z();
  EXPECT_GT(height, 2.05);
  EXPECT_LT(height, 3.0);
}

}  // namespace
}  // namespace pbm
