// Collisions with rigid obstacles (sec. 5.2.1): no node ever ends a step inside an obstacle, for
// every deformation level; friction makes a ball roll, no friction lets it slide.
#include <gtest/gtest.h>

#include <cmath>

#include "collide/rigid_contact.h"
#include "deform/body_dynamics.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/world.h"

namespace pbm {
namespace {

struct RunResult {
  Real min_distance = 1e300;
  Real max_omega = 0;       // largest |omega| seen after the first contact [rad/s]
  Real final_rotation = 0;  // rotation angle of the frame at the end [rad]
  Vec3 final_position = Vec3::Zero();
  Real final_speed = 0;  // centre-of-mass speed at the end [m/s]
  bool ok = true;
  std::string message;
};

RunResult simulate(const Scene& scene, int frames) {
  test::Simulation sim(scene);
  State& state = sim.state;
  RunResult run;
  bool touched = false;
  for (int f = 0; f < frames; ++f) {
    const FrameResult r = advance_frame(sim);
    if (!r.ok) {
      run.ok = false;
      run.message = r.message;
      break;
    }
    run.min_distance = std::min(run.min_distance, sim.stats.min_distance);
    touched = touched || sim.stats.min_distance < 1e-6;
    if (touched) run.max_omega = std::max(run.max_omega, state.v.segment<3>(3).norm());
  }
  const Vec4 quat = state.q.segment<4>(3);
  run.final_rotation = 2 * std::acos(std::min(1.0, std::abs(quat[0])));
  run.final_position = state.q.segment<3>(0);
  // c is the centre of mass and its velocity the momentum's (sum m_i d-dot_i = 0, mean-axis).
  run.final_speed = state.v.segment<3>(0).norm();
  return run;
}

Scene jello() {
  return load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
}

// Every step is one frame in this scene (fps = 1 / dt), so this checks every step.
TEST(Contact, JelloBallNeverEndsAStepBelowEitherPlaneAndRollsDownTheSlope) {
  const Scene scene = jello();
  const RunResult run = simulate(scene, 323);  // 10.01 s
  ASSERT_TRUE(run.ok) << run.message;
  EXPECT_GE(run.min_distance, 0.0);
  // It left the slope (x from 2.5 to beyond the crease at 0) and turned like a rolling ball.
  EXPECT_LT(run.final_position.x(), -0.3);
  EXPECT_GT(run.final_rotation, 0.5);
}

// The book's jello-ball "rolls on the ground until it comes to rest" (sec. 6.4).
TEST(Contact, JelloBallComesToRestOnTheGround) {
  const RunResult run = simulate(jello(), 323);  // 10.01 s
  ASSERT_TRUE(run.ok) << run.message;
  EXPECT_LT(run.final_speed, 1e-3);
  EXPECT_GE(run.min_distance, 0.0);
  EXPECT_LT(run.final_position.x(), -0.3);  // on the ground, past the crease
}

TEST(Contact, FrictionlessJelloBallSlidesWithoutSpinningUp) {
  Scene rough = jello();
  Scene smooth = jello();
  for (ObstacleDef& o : smooth.obstacles) o.friction = 0;
  const RunResult with_friction = simulate(rough, 100);
  const RunResult without = simulate(smooth, 100);
  ASSERT_TRUE(with_friction.ok && without.ok);
  EXPECT_GE(without.min_distance, 0.0);
  // The normal forces (5.11) act along the plane's normal on the global surface around the
  // contact point, whose resultant passes through the centre: alone they barely turn the ball;
  // friction (5.12) rolls it.
  EXPECT_LT(without.final_rotation, 0.05 * with_friction.final_rotation)
      << without.final_rotation << " vs " << with_friction.final_rotation;
}

// At rest and without friction, the push (5.11) on a local body is the gradient of the energy it
// reports, 0.5 a K phi^2 over the global surface: it can only return what it stored. Checked on
// the rows of c (translation) and theta (rotation) against central differences of that energy.
TEST(Contact, ObstaclePushIsTheGradientOfItsEnergy) {
  BodyDef body = test::ball(DeformLevel::local, 12);
  body.position = Vec3(0.1, -0.05, 0.93);  // 7 cm into the ground, off-centre
  Scene scene = test::free_space(body);
  ObstacleDef ground;
  ground.name = "ground";
  ground.kind = ObstacleKind::plane;
  ground.normal = Vec3(0.2, 0, 1).normalized();
  ground.elasticity = 670;
  ground.friction = 0;
  scene.obstacles.push_back(ground);
  test::Simulation sim(scene);
  const BodyModel& model_body = sim.model.bodies[0];
  BodyWorkspace& bw = sim.ws.bodies[0];
  bw.dt = 0;  // no stability clamp: the bare (5.11)
  auto energy = [&](const VecX& q) {
    compute_body_kinematics(model_body, q, sim.state.v, bw, false);
    return contact_potential_energy(sim.model.obstacles, model_body, bw);
  };
  const VecX q0 = sim.state.q;
  compute_body_kinematics(model_body, q0, sim.state.v, bw);
  factor_generalized_mass(model_body, q0, bw);
  add_contact_forces(sim.model.obstacles, model_body, bw);
  const Vec3 force = bw.R * bw.contact_generalized.segment<3>(0);   // world frame
  const Vec3 torque = bw.R * bw.contact_generalized.segment<3>(3);  // about c, world frame
  ASSERT_GT(force.norm(), 1.0);
  const Real h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    VecX plus = q0, minus = q0;
    plus[k] += h;
    minus[k] -= h;
    const Real dU = (energy(plus) - energy(minus)) / (2 * h);
    EXPECT_NEAR(force[k], -dU, 1e-5 * force.norm()) << "c" << k;
    // A small rotation about world axis k: q_theta <- exp(+-h e_k / 2) q_theta.
    const Vec4 rot = q0.segment<4>(3);
    auto turned = [&](Real angle) {
      VecX q = q0;
      Eigen::Quaterniond r(Eigen::AngleAxisd(angle, Vec3::Unit(k)));
      Eigen::Quaterniond base(rot[0], rot[1], rot[2], rot[3]);
      Eigen::Quaterniond out = r * base;
      q.segment<4>(3) = Vec4(out.w(), out.x(), out.y(), out.z());
      return q;
    };
    const Real dUr = (energy(turned(h)) - energy(turned(-h))) / (2 * h);
    EXPECT_NEAR(torque[k], -dUr, 1e-5 * force.norm()) << "theta" << k;
  }
}

// The obstacle's constants at their extremes: a = 0 (no push, the projection alone holds the
// nodes), a = 1e7 (a spring far stiffer than the step resolves, clamped), beta_f in {0, 1}. No
// node ends a step inside, nothing diverges, the kinetic energy never exceeds the fall's.
TEST(Contact, ExtremeElasticityAndFrictionStayOutsideAndBounded) {
  for (const Real a : {0.0, 1e7}) {
    for (const Real beta : {0.0, 1.0}) {
      Scene scene = jello();
      for (ObstacleDef& o : scene.obstacles) {
        o.elasticity = a;
        o.friction = beta;
      }
      test::Simulation sim(scene);
      Real lowest = 1e300, fastest = 0;
      for (int f = 0; f < 150; ++f) {
        const FrameResult r = advance_frame(sim);
        ASSERT_TRUE(r.ok) << "a " << a << " beta " << beta << ": " << r.message;
        lowest = std::min(lowest, sim.stats.min_distance);
        fastest = std::max(fastest, sim.stats.kinetic);
      }
      EXPECT_GE(lowest, 0.0) << "a " << a << " beta " << beta;
      // Falling 2.8 m (centre 4 m to 1.2 m above the slope) at most: m g h = 2064 * 9.81 * 2.8.
      EXPECT_LT(fastest, 2064 * 9.81 * 2.8) << "a " << a << " beta " << beta;
    }
  }
}

// Rigid and global bodies resolve contact through their generalized coordinates (impulses mapped
// by L^T and a translation of c): the same guarantee, and they come to rest on the ground.
class LevelContact : public testing::TestWithParam<DeformLevel> {};

TEST_P(LevelContact, BallDroppedOnABoxAndTheGroundStaysOutside) {
  BodyDef body = test::ball(GetParam(), 8);
  body.position = Vec3(0.3, 0, 3.0);
  body.material.damping = 0.5;
  body.k_s = VecX::Constant(6, 5e4);
  Scene scene = test::free_space(body);
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solver.dt = 2e-3;
  scene.solver.fps = 50;
  ObstacleDef ground;
  ground.kind = ObstacleKind::plane;
  ground.friction = 0.4;
  ground.elasticity = 500;
  ObstacleDef box;
  box.kind = ObstacleKind::box;
  box.point = Vec3(0, 0, 0.25);
  box.half_extents = Vec3(0.5, 0.5, 0.25);
  box.friction = 0.4;
  box.elasticity = 500;
  scene.obstacles = {ground, box};
  const RunResult run = simulate(scene, 150);
  ASSERT_TRUE(run.ok) << run.message;
  EXPECT_GE(run.min_distance, 0.0);
  // It landed (on the box top at z = 0.5 or beside it on the ground), not below either surface.
  EXPECT_LT(run.final_position.z(), 2.0);
  EXPECT_GT(run.final_position.z(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(AllLevels, LevelContact,
                         testing::Values(DeformLevel::rigid, DeformLevel::global,
                                         DeformLevel::local));

}  // namespace
}  // namespace pbm
