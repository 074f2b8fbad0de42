// Point-to-point constraints with Baumgarte stabilization (ch. 7): the point Jacobian against
// finite differences, the decay rate of self-assembly (7.16), conservation of momentum and energy
// through the constraint forces (7.9), the solver choices of sec. 7.3.2 agreeing, loops and stiff
// gains reported, and the extremes (a 1,000-link chain, alpha = 0, coincident anchors).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "constrain/constraint_projection.h"
#include "constrain/hinge_spring.h"
#include "constrain/point_constraint.h"
#include "constraint_scenes.h"
#include "core/bits.h"
#include "core/quaternion.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/state.h"
#include "snapshot_penetration.h"

namespace pbm {
namespace {

using test::Simulation;
using namespace test::constraints;

TEST(Constraints, JacobianMatchesFiniteDifferences) {
  // A globally deforming part with a node end and a frame point end: x-dot = L q-dot must be the
  // derivative of x along q-dot, and G^T nu_g (G = L^T) the same velocity.
  Scene s = assembly_scene(DynamicsOrder::second, 10);
  s.bodies[0] = part("a", DeformLevel::global, Vec3(0.1, -0.2, 0.3));
  s.bodies[0].orientation = Vec4(0.9, 0.1, -0.3, 0.2).normalized();
  s.constraints[0].a = body_node(0, 7);
  s.constraints.push_back(joint(body_point(0, Vec3(0.1, 0.2, -0.3)), world(Vec3(1, 1, 1))));
  Simulation sim(s);
  const BodyModel& body = sim.model.bodies[0];
  VecX v = VecX::Zero(sim.model.n_v);
  for (int i = 0; i < body.v_size; ++i) v[i] = std::sin(1.7 * i + 0.3);
  VecX q = sim.state.q;
  std::vector<BodyWorkspace>& bw = sim.ws.bodies;
  auto kinematics = [&](const VecX& qq, const VecX& vv) {
    compute_body_kinematics(body, qq.segment(0, body.q_size), vv.segment(0, body.v_size), bw[0]);
  };
  kinematics(q, v);
  VecX q_dot = VecX::Zero(sim.model.n_q);
  q_dot.segment<3>(0) = v.segment<3>(0);
  q_dot.segment<4>(3) = quaternion_rate(q.segment<4>(3), v.segment<3>(3));
  q_dot.segment(7, body.n_s) = v.segment(6, body.n_s);
  const VecX nu_g = [&] {
    VecX g = v.head(body.n_generalized());
    g.segment<3>(0) = bw[0].R.transpose() * v.segment<3>(0);
    return g;
  }();
  for (const PointConstraintModel& c : sim.model.constraints.points) {
    kinematics(q, v);
    const Vec3 velocity =
        constraint_end_velocity(c.ends[0], bw, {sim.model.constraints, sim.model.bodies}, v);
    MatX G(body.n_generalized(), 3);
    constraint_end_jacobian_transpose(c.ends[0], body, bw[0], G);
    const Vec3 from_G = G.transpose() * nu_g;
    const Real h = 1e-6;
    VecX qp = q + h * q_dot, qm = q - h * q_dot;
    kinematics(qp, v);
    const Vec3 xp =
        constraint_end_position(c.ends[0], bw, {sim.model.constraints, sim.model.bodies}, qp);
    kinematics(qm, v);
    const Vec3 xm =
        constraint_end_position(c.ends[0], bw, {sim.model.constraints, sim.model.bodies}, qm);
    const Vec3 fd = (xp - xm) / (2 * h);
    std::printf("end %s: |L q-dot - finite difference| = %.3g, |G^T nu - L q-dot| = %.3g\n",
                c.ends[0].node >= 0 ? "node" : "point", (velocity - fd).norm(),
                (from_G - velocity).norm());
    EXPECT_LT((velocity - fd).norm(), 1e-7 * velocity.norm());
    EXPECT_LT((from_G - velocity).norm(), 1e-12 * velocity.norm());
  }
}

TEST(Constraints, SelfAssemblyDecaysAtAlpha) {
  // Second order, alpha = beta, C-dot(0) = 0: every component of C obeys
  // C'' + 2 alpha C' + alpha^2 C = 0 (7.14), so |C| = C0 (1 + alpha t) e^(-alpha t), critically
  // damped. The same log-slope fit of that closed form at the same frames is the expected rate
  // (0.935 alpha over alpha t in [10, 20]); |C| follows the closed form frame by frame too.
  const Real alpha = 5;
  Simulation second(assembly_scene(DynamicsOrder::second, alpha));
  const Real c0 = violation(second);
  const auto samples = violation_samples(second, 10 / alpha, 20 / alpha);
  std::vector<std::pair<Real, Real>> closed_form;
  Real worst = 0;
  for (const auto& [t, value] : samples) {
    const Real exact = c0 * (1 + alpha * t) * std::exp(-alpha * t);
    closed_form.emplace_back(t, exact);
    worst = std::max(worst, std::abs(value / exact - 1));
  }
  const Real rate = log_decay_rate(samples), expected = log_decay_rate(closed_form);
  std::printf(
      "second order: |C(0)| = %.3f m, decay rate %.4f 1/s, closed form %.4f 1/s (%.4f alpha); "
      "worst |C| / closed form - 1 = %.3g over %zu frames\n",
      c0, rate, expected, expected / alpha, worst, samples.size());
  EXPECT_NEAR(rate, expected, 1e-3 * expected);
  EXPECT_LT(worst, 1e-3);
  // First order (7.16): C-dot = -alpha C, exactly e^(-alpha t).
  Simulation first(assembly_scene(DynamicsOrder::first, alpha));
  const Real rate1 = measured_decay_rate(first, 0.2, 3.0);
  std::printf("first order: decay rate %.4f 1/s for alpha %.1f (%.4f alpha)\n", rate1, alpha,
              rate1 / alpha);
  EXPECT_NEAR(rate1, alpha, 0.01 * alpha);
  EXPECT_LT(violation(first), 1e-4);
}

// sum m x-dot over every body of the simulation's state.
Vec3 linear_momentum(Simulation& sim) {
  Vec3 p = Vec3::Zero();
  for (std::size_t b = 0; b < sim.model.bodies.size(); ++b) {
    const BodyModel& body = sim.model.bodies[b];
    const auto q = sim.state.q.segment(body.q_offset, body.q_size);
    const auto v = sim.state.v.segment(body.v_offset, body.v_size);
    compute_body_kinematics(body, q, v, sim.ws.bodies[b]);
    p += compute_body_energy(body, q, v, Vec3::Zero(), sim.ws.bodies[b]).linear_momentum;
  }
  return p;
}

TEST(Constraints, TwoFreeRigidBodiesConserveLinearMomentum) {
  Scene s = assembly_scene(DynamicsOrder::second, 8);
  s.bodies[0].velocity = Vec3(1, -0.5, 0.2);
  s.bodies[0].angular_velocity = Vec3(0.3, 2, -1);
  s.bodies[1].velocity = Vec3(-0.2, 0.4, 1);
  test::set_uniform_mass(s.bodies[1], 3.0);
  Simulation sim(s);
  auto momentum = [&] { return linear_momentum(sim); };
  const Vec3 p0 = momentum();
  advance_to(sim, 3.0);
  const Vec3 p1 = momentum();
  const Real relative = (p1 - p0).norm() / p0.norm();
  std::printf("linear momentum drift over 3 s of assembly and tumbling: %.3g relative\n", relative);
  EXPECT_LT(relative, 1e-9);
  EXPECT_LT(violation(sim), 1e-4);
}

// The projection after collisions (constrain/constraint_projection.h) on its own: two parts, one
// of them global (its q_s in the metric) and a node end, joined and tumbling; a collision is
// stood in for by a jump of body a's position, rotation and velocity. The projection must give
// back C and C-dot as they were before the jump, and, its impulses being internal (equal and
// opposite at the two ends), leave the linear momentum the jump gave.
TEST(Constraints, ProjectionAfterACollisionRestoresCAndItsRateWithInternalImpulses) {
  Scene s = assembly_scene(DynamicsOrder::second, 8);
  s.bodies[0] = part("a", DeformLevel::global, Vec3(-0.5, 0, 0));
  s.bodies[0].velocity = Vec3(1, -0.5, 0.2);
  s.bodies[0].angular_velocity = Vec3(0.3, 2, -1);
  s.bodies[1].velocity = Vec3(-0.2, 0.4, 1);
  test::set_uniform_mass(s.bodies[1], 3.0);
  s.constraints.push_back(joint(body_node(0, 5), body_point(1, Vec3(0, 0.2, 0))));
  Simulation sim(s);
  advance_to(sim, 0.5);
  const ConstrainedSystem system{sim.model.constraints, sim.model.bodies};
  ConstraintProjectionWorkspace pw;
  init_constraint_projection(system, pw);
  record_constraints_before_collisions(system, sim.state.q, sim.state.v, sim.ws.bodies, pw);
  const VecX C_before = pw.C_before, C_dot_before = pw.C_dot_before;
  auto momentum = [&] { return linear_momentum(sim); };
  // The jump: 2 mm and 0.02 rad of position, 0.5 m/s and 1 rad/s of velocity.
  const BodyModel& a = sim.model.bodies[0];
  auto qa = body_q(a, sim.state.q);
  auto va = body_v(a, sim.state.v);
  position_of(qa) += Vec3(2e-3, -1e-3, 1e-3);
  quaternion_of(qa) =
      quaternion_product(quaternion_of(qa), quaternion_from_axis_angle(Vec3(1, 2, 3), 0.02));
  velocity_of(va) += Vec3(0.3, -0.4, 0.0);
  omega_of(va) += Vec3(0, 0, 1);
  const Vec3 p_jump = momentum();
  const ConstraintProjection done = project_constraints_after_collisions(
      system, sim.state.q, sim.state.v, sim.ws.bodies, *sim.ws.constraints, pw, s.solver.dt);
  const Vec3 p_after = momentum();
  record_constraints_before_collisions(system, sim.state.q, sim.state.v, sim.ws.bodies, pw);
  const Real dC = (pw.C_before - C_before).cwiseAbs().maxCoeff();
  const Real dC_dot = (pw.C_dot_before - C_dot_before).cwiseAbs().maxCoeff();
  std::printf(
      "projection: the jump opened |C| by %.3g m and |C-dot| by %.3g m/s; after it %.3g m, "
      "%.3g m/s from the values before; linear momentum changed by %.3g (of %.3g)\n",
      done.opened, done.opened_rate, dC, dC_dot, (p_after - p_jump).norm(), p_jump.norm());
  EXPECT_TRUE(done.ran);
  EXPECT_GT(done.opened, 1e-3);
  EXPECT_GT(done.opened_rate, 0.3);
  EXPECT_LT(dC, 1e-9);
  EXPECT_LT(dC_dot, 1e-9);
  EXPECT_LT((p_after - p_jump).norm(), 1e-10 * p_jump.norm());
  // Unchanged constraints are left alone, bit for bit.
  const VecX q = sim.state.q, v = sim.state.v;
  EXPECT_FALSE(project_constraints_after_collisions(system, sim.state.q, sim.state.v, sim.ws.bodies,
                                                    *sim.ws.constraints, pw, s.solver.dt)
                   .ran);
  EXPECT_TRUE(same_bits(q, sim.state.q) && same_bits(v, sim.state.v));
}

// Two rigid parts hanging from a world anchor by massless links through points fixed in their
// frames, released horizontally.
Scene double_pendulum(IntegratorKind integrator, Real dt) {
  Scene s;
  s.solver.dt = dt;
  s.solver.integrator = integrator;
  s.solver.fps = 50;
  s.solver.constraint_alpha = 10;
  s.bodies.push_back(part("upper", DeformLevel::rigid, Vec3(0.5, 0, 2), 0.1));
  s.bodies.push_back(part("lower", DeformLevel::rigid, Vec3(1.0, 0, 2), 0.1));
  for (BodyDef& b : s.bodies) b.material.damping = 0;
  s.constraints.push_back(joint(body_point(0, Vec3(-0.5, 0, 0)), world(Vec3(0, 0, 2))));
  s.constraints.push_back(joint(body_point(0, Vec3(0.25, 0, 0)), body_point(1, Vec3(-0.25, 0, 0))));
  return s;
}

TEST(Constraints, UndampedDoublePendulumConservesEnergy) {
  // rk4, dt = 1 ms, alpha = 10: the energy scale is the drop of both parts by their link
  // lengths, m g (0.5 + 1.0) per part summed.
  Simulation sim(double_pendulum(IntegratorKind::rk4, 1e-3));
  FrameStats s0;
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, s0);
  const Real scale = 9.81 * (1.0 * 0.5 + 1.0 * 1.0) + 9.81 * 1.0 * 0.5;
  Real worst = 0, worst_c = 0;
  while (sim.state.time < 10.0 - 1e-9) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    const Real e = sim.stats.kinetic + sim.stats.potential - s0.kinetic - s0.potential;
    worst = std::max(worst, std::abs(e) / scale);
    worst_c = std::max(worst_c, sim.stats.constraint_violation);
  }
  std::printf(
      "double pendulum, rk4 dt 1 ms, 10 s: max |E - E0| / (m g L) = %.3g, max |C| = %.3g m\n",
      worst, worst_c);
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst_c, 1e-4);
}

TEST(Constraints, DenseAndSparseSolversAgreeAndRunsAreBitIdentical) {
  Scene s = double_pendulum(IntegratorKind::euler, 1e-3);
  s.bodies[1].level = DeformLevel::local;  // a deformable part too
  s.constraints[1].b = body_node(1, 3);
  Simulation dense(s);
  s.solver.constraint_solver = ConstraintSolverKind::sparse;
  Simulation sparse(s);
  Simulation again(s);
  advance_to(dense, 1.0);
  advance_to(sparse, 1.0);
  advance_to(again, 1.0);
  EXPECT_EQ(hash_state(sparse.state), hash_state(again.state));
  const Real difference = (dense.state.q - sparse.state.q).cwiseAbs().maxCoeff();
  std::printf("dense vs sparse after 1 s: max |q difference| = %.3g\n", difference);
  EXPECT_LT(difference, 1e-9);
  EXPECT_TRUE(sparse.ws.constraints->sparse);
  EXPECT_FALSE(dense.ws.constraints->sparse);
}

TEST(Constraints, LoopFallsBackToDenseAndStiffGainsAreReported) {
  Scene s;
  s.gravity = Vec3::Zero();
  s.solver.constraint_solver = ConstraintSolverKind::sparse;
  for (int i = 0; i < 3; ++i)
    s.bodies.push_back(part("p" + std::to_string(i), DeformLevel::rigid, Vec3(i, 0, 0)));
  s.constraints.push_back(joint(body_point(0, Vec3(0.5, 0, 0)), body_point(1, Vec3(-0.5, 0, 0))));
  s.constraints.push_back(joint(body_point(1, Vec3(0.5, 0, 0)), body_point(2, Vec3(-0.5, 0, 0))));
  const Model tree = build_model(s);
  EXPECT_EQ(tree.constraints.solver, ConstraintSolverKind::sparse);
  EXPECT_FALSE(tree.constraints.has_loop);
  EXPECT_TRUE(tree.constraints.notes.empty());
  s.constraints.push_back(joint(body_point(2, Vec3(0, 0.2, 0)), body_point(0, Vec3(0, 0.2, 0))));
  s.solver.constraint_alpha = 600;  // alpha dt = 0.6 with Euler at 1 ms
  Simulation loop(s);
  EXPECT_TRUE(loop.model.constraints.has_loop);
  EXPECT_EQ(loop.model.constraints.solver, ConstraintSolverKind::dense);
  const FrameResult r = advance_frame(loop);
  EXPECT_NE(loop.stats.notes.find("closes a loop"), std::string::npos) << loop.stats.notes;
  EXPECT_NE(loop.stats.notes.find("stiff"), std::string::npos) << loop.stats.notes;
}

TEST(Constraints, ThousandLinkChainRunsAndStaysBounded) {
  // 1,000 constraints: a chain of 1,000 small rigid parts hanging from a world anchor, swinging
  // under gravity from horizontal, solved by the sparse LDL^T.
  Scene s;
  s.solver.dt = 1e-3;
  s.solver.fps = 50;
  s.solver.constraint_solver = ConstraintSolverKind::sparse;
  const int n = 1000;
  const Real link = 0.01;
  for (int i = 0; i < n; ++i) {
    BodyDef b =
        part("link" + std::to_string(i), DeformLevel::rigid, Vec3((i + 0.5) * link, 0, 0), 0.004);
    b.tessellation.rings = 2;
    b.tessellation.segments = 3;
    test::set_uniform_mass(b, 0.01);
    s.bodies.push_back(b);
  }
  s.constraints.push_back(joint(body_point(0, Vec3(-0.5 * link, 0, 0)), world(Vec3::Zero())));
  for (int i = 0; i + 1 < n; ++i) {
    s.constraints.push_back(
        joint(body_point(i, Vec3(0.5 * link, 0, 0)), body_point(i + 1, Vec3(-0.5 * link, 0, 0))));
  }
  Simulation sim(s);
  Real worst = 0;
  for (int f = 0; f < 10; ++f) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    worst = std::max(worst, sim.stats.constraint_violation);
    EXPECT_TRUE(sim.state.q.allFinite());
  }
  std::printf("1000-link chain, 0.2 s: max |C| = %.3g m, lowest link at z = %.3f m\n", worst,
              sim.state.q[sim.model.bodies[n - 1].q_offset + 2]);
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(sim.state.q[sim.model.bodies[n - 1].q_offset + 2], -0.05);  // it fell
}

TEST(Constraints, AlphaZeroReportsTheDriftWithoutFailing) {
  // Without stabilization (alpha = beta = 0) C-ddot = 0 is enforced: an open joint stays open
  // and the stats say by how much.
  Simulation sim(assembly_scene(DynamicsOrder::second, 0));
  const Real c0 = violation(sim);
  advance_to(sim, 1.0);
  const Real c1 = violation(sim);
  std::printf("alpha = 0: |C| %.6f m -> %.6f m after 1 s\n", c0, c1);
  EXPECT_TRUE(sim.state.q.allFinite());
  EXPECT_NEAR(c1, c0, 1e-6);
}

TEST(Constraints, CoincidentAnchorsStartSatisfiedWithoutNaN) {
  Scene s;
  s.solver.dt = 1e-3;
  s.bodies.push_back(part("a", DeformLevel::rigid, Vec3(0, 0, 1)));
  s.bodies.push_back(part("b", DeformLevel::local, Vec3(0, 0, 1)));
  // Both ends at the same world point from the start: C = 0, C-dot = 0; and a body point pinned
  // at its own position.
  s.constraints.push_back(joint(body_point(0, Vec3::Zero()), body_point(1, Vec3::Zero())));
  s.constraints.push_back(joint(body_point(0, Vec3::Zero()), world(Vec3(0, 0, 1))));
  Simulation sim(s);
  EXPECT_EQ(violation(sim), 0.0);
  advance_to(sim, 0.5);
  EXPECT_TRUE(sim.state.q.allFinite());
  EXPECT_TRUE(sim.ws.constraints->f_c.allFinite());
  EXPECT_LT(violation(sim), 1e-6);
}

TEST(Constraints, HingeSpringOscillatesAboutItsAxis) {
  // A rigid plank hinged to the world about y with a rotational spring k, twisted by 0.3 rad from
  // rest: it swings about the axis at omega^2 = k / I_yy, the pivot stays put.
  Simulation sim(hinged_plank_scene(1000));
  ASSERT_EQ(sim.model.constraints.points.size(), 2u);
  const Real inertia = inertia_about_y(sim.model.bodies[0]);
  const Real period = 2 * std::acos(-1.0) * std::sqrt(inertia / 50);
  FrameStats s0;
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, s0);
  Real lowest = 1e300, highest = -1e300;
  while (sim.state.time < period - 1e-9) {
    advance_to(sim, sim.state.time + 1e-3);
    const Real theta = hinge_angle(sim.model.constraints.hinges[0], sim.ws.bodies);
    lowest = std::min(lowest, theta);
    highest = std::max(highest, theta);
  }
  FrameStats s1;
  measure_state(sim.world, sim.inputs, sim.state, sim.ws, s1);
  std::printf("hinge: theta in [%.4f, %.4f] over one period %.3f s, energy %.5f -> %.5f J\n",
              lowest, highest, period, s0.elastic + s0.kinetic, s1.elastic + s1.kinetic);
  EXPECT_NEAR(highest, 0.6, 1e-3);
  EXPECT_NEAR(lowest, 0.0, 1e-3);
  EXPECT_LT((sim.state.q.segment<3>(0) - Vec3(0, 0, 1)).norm(), 1e-4);
  EXPECT_NEAR(s1.elastic + s1.kinetic, s0.elastic + s0.kinetic, 1e-3 * s0.elastic);
}

}  // namespace
}  // namespace pbm

namespace pbm {
namespace {

// The book's self-assembly experiments (sec. 7.4): the parts start apart and, once assembled,
// every constraint holds to 0.1 mm.
TEST(ConstraintScenes, SnowmanAndDragonflyAssemble) {
  for (const auto& [name, assembled] : {std::pair{"snowman", 1.5}, {"dragonfly", 2.0}}) {
    const Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json");
    test::Simulation sim(scene);
    const Real c0 = violation(sim);
    advance_to(sim, assembled);
    const Real c1 = violation(sim);
    std::printf("%s: %zu point constraints, |C| %.3f m -> %.3g m at t = %.2f s\n", name,
                sim.model.constraints.points.size(), c0, c1, sim.state.time);
    EXPECT_GT(c0, 0.1) << name;
    EXPECT_LT(c1, 1e-4) << name;
  }
}

// The see-saw (6.10): two heavy balls land on a plank hinged to the world. Body collisions must
// not translate a constrained part: the plank's centre stays at its pivot (it sank 0.8 m when
// the mid-plane projection moved it).
TEST(ConstraintScenes, SeesawPlankStaysOnItsHingeWhenTheBallsLand) {
  const Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/seesaw.json");
  test::Simulation sim(scene);
  Real worst = 0;
  while (sim.state.time < 3.0) {
    ASSERT_TRUE(advance_frame(sim).ok);
    worst = std::max(worst, (sim.state.q.segment<3>(0) - Vec3(0, 0, 1)).norm());
  }
  std::printf("plank centre: at most %.3f m from its pivot over 3 s\n", worst);
  EXPECT_LT(worst, 0.1);
}

// The balls land on the plank and stay on it: no ball node is inside the plank's surface by more
// than 1 cm, and no ball's centre gets below the plank's top while fully over it. Heavy soft balls
// (830 kg each at the book's nodal mass) went through it while only their touching nodes were
// stopped; the push between bodies (body_elasticity, the scene's plane elasticity 5000) holds their
// frames on top. Once they roll to the ends they drape over them, as soft bags do.
TEST(ConstraintScenes, SeesawBallsDoNotGoThroughThePlank) {
  const Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/seesaw.json");
  test::Simulation sim(scene);
  ASSERT_EQ(sim.model.bodies[0].name, "plank");
  const BodyModel& plank = sim.model.bodies[0];
  const VecX& q_s = scene.bodies[0].q_s;
  const Vec3 half = q_s[0] * Vec3(q_s[1], q_s[2], q_s[3]);  // the plank's half sizes
  Real deepest = 0, lowest_centre = 1e300;
  int frames_inside = 0;
  while (sim.state.time < 3.0) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const Snapshot snap = make_snapshot(sim);
    Real depth = 0;
    for (std::size_t b = 1; b < sim.model.bodies.size(); ++b) {  // body b's mesh is meshes[b]
      depth = std::max(depth, test::penetration_depth(snap.meshes[b], snap.meshes[0]));
    }
    deepest = std::max(deepest, depth);
    frames_inside += depth > 0.01;
    // A ball's centre over the plank (in the plank's frame), a radius or more from its ends, is
    // above its top face; nearer the end it may drape over it.
    const Vec3 c = sim.state.q.segment<3>(plank.q_offset);
    const Vec4 qt = sim.state.q.segment<4>(plank.q_offset + 3);
    const Mat3 R = Eigen::Quaternion<Real>(qt[0], qt[1], qt[2], qt[3]).normalized().matrix();
    for (std::size_t b = 1; b < sim.model.bodies.size(); ++b) {
      const Vec3 p = R.transpose() * (sim.state.q.segment<3>(sim.model.bodies[b].q_offset) - c);
      const Real radius = scene.bodies[b].q_s[0];
      if (std::abs(p.x()) < half.x() - radius && std::abs(p.y()) < half.y()) {
        lowest_centre = std::min(lowest_centre, p.z() - half.z());
      }
    }
  }
  std::printf(
      "see-saw: deepest ball node inside the plank %.4f m, %d frames beyond 1 cm; a ball centre "
      "fully over the plank at least %.3f m above its top\n",
      deepest, frames_inside, lowest_centre);
  EXPECT_LT(deepest, 0.01);
  EXPECT_GT(lowest_centre, 0.0);
}

// The snowman (fig. 7.5) after assembly drops to the floor and hops along a path by timed
// forces (keyframed gravity pulses: up for 0.12 s, with a sideways part). It must stay standing:
// a stack of soft balls on a floor is an inverted pendulum, and with the parts started off the
// vertical (net angular momentum from the assembly forces, 19 degrees at landing) it toppled
// after the first hops. Measured: the tilt of the bottom-to-head line, the bottom's hops and
// path, and |C| from the first landing on (1.5 s: assembled, falling). With the constraints
// left to Baumgarte's feedback after each collision (solver.constraint_projection false) the
// landings open them by about a centimetre (1.2 cm at the first, issue 12); restored after the
// collisions they stay under 1 mm at every landing.
struct SnowmanRun {
  Real worst_tilt = 0, worst_violation = 0, lowest = 1e300, highest = -1e300, path = 0;
  Vec3 end = Vec3::Zero();
};

SnowmanRun run_snowman(bool projection) {
  Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/snowman.json");
  scene.solver.constraint_projection = projection;
  test::Simulation sim(scene);
  int bottom = -1, head = -1;
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
    if (scene.bodies[b].name == "bottom") bottom = b;
    if (scene.bodies[b].name == "head") head = b;
  }
  EXPECT_GE(bottom, 0);
  EXPECT_GE(head, 0);
  SnowmanRun run;
  Vec3 landed = Vec3::Zero();
  while (sim.state.time < scene.solver.duration - 1e-9) {
    const FrameResult r = advance_frame(sim);
    EXPECT_TRUE(r.ok) << r.message;
    if (!r.ok) break;
    if (sim.state.time > 1.5) {
      run.worst_violation = std::max(run.worst_violation, sim.stats.constraint_violation);
    }
    const Vec3 c_bottom = sim.stats.bodies[bottom].position;
    const Vec3 up = sim.stats.bodies[head].position - c_bottom;
    const Real tilt = std::atan2(std::hypot(up.x(), up.y()), up.z()) * 180 / std::numbers::pi;
    if (sim.state.time < 2.45) continue;  // assembled, dropped, settled before the first hop
    if (landed.isZero()) landed = c_bottom;
    run.worst_tilt = std::max(run.worst_tilt, tilt);
    run.lowest = std::min(run.lowest, c_bottom.z());
    run.highest = std::max(run.highest, c_bottom.z());
  }
  run.end = sim.state.q.segment<3>(sim.model.bodies[bottom].q_offset);
  run.path = std::hypot(run.end.x() - landed.x(), run.end.y() - landed.y());
  return run;
}

TEST(ConstraintScenes, SnowmanHopsAlongItsPathStanding) {
  const SnowmanRun run = run_snowman(true);
  const SnowmanRun feedback_only = run_snowman(false);
  std::printf(
      "snowman: tilt at most %.2f deg after 2.45 s, bottom centre z %.3f..%.3f m, moved %.3f m "
      "(to %.3f, %.3f); |C| at most %.3g m from 1.5 s on (Baumgarte's feedback alone after "
      "collisions: %.3g m)\n",
      run.worst_tilt, run.lowest, run.highest, run.path, run.end.x(), run.end.y(),
      run.worst_violation, feedback_only.worst_violation);
  EXPECT_LT(run.worst_tilt, 8.0);
  EXPECT_GT(run.highest - run.lowest, 0.15);  // it hops
  EXPECT_GT(run.path, 0.1);                   // along its path
  EXPECT_LT(run.worst_violation, 1e-3);       // issue 12: under 1 mm at every landing
  EXPECT_GT(feedback_only.worst_violation, 5e-3);
}

}  // namespace
}  // namespace pbm
