// What a constraint's own settings do, measured on the motion against closed forms: per-constraint
// Baumgarte gains (7.14) override the solver's, each joint of one scene decaying at its own rate;
// a hinge's rotational damper decays the swing at c / (2 I); and an end given by material
// coordinates (u, v) acts exactly as an end at the node nearest to that surface point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "constrain/hinge_spring.h"
#include "constraint_scenes.h"
#include "deform/tessellation.h"
#include "sim/state.h"

namespace pbm {
namespace {

using namespace test::constraints;
using test::Simulation;

// |C(t)| / |C(0)| of C'' + 2 alpha C' + beta^2 C = 0 (7.14) from rest (C'(0) = 0).
Real baumgarte_decay(Real alpha, Real beta, Real t) {
  if (alpha == beta) return (1 + alpha * t) * std::exp(-alpha * t);
  const Real root = std::sqrt(alpha * alpha - beta * beta);  // overdamped: alpha > beta here
  const Real r1 = -alpha + root, r2 = -alpha - root;
  return (r2 * std::exp(r1 * t) - r1 * std::exp(r2 * t)) / (r2 - r1);
}

// Two separate assemblies in one scene, the solver's gains 1 / s, each joint with its own: the
// first critically damped (alpha = beta = 8), the second overdamped (alpha = 5, beta = 3, slow
// rate alpha - sqrt(alpha^2 - beta^2) = 1 / s). Each |C| follows its own closed form frame by
// frame; with the solver's gains both would decay at 1 / s.
TEST(ConstraintParameters, EachJointDecaysAtItsOwnAlphaAndBeta) {
  Scene s = assembly_scene(DynamicsOrder::second, 1.0);
  s.solver.constraint_beta = 1.0;
  s.bodies.push_back(part("c", DeformLevel::rigid, Vec3(-0.5, 2, 0)));
  s.bodies.push_back(part("d", DeformLevel::rigid, Vec3(0.5, 2.3, -0.1)));
  s.constraints.push_back(joint(body_point(2, Vec3(0.2, 0, 0)), body_point(3, Vec3(-0.2, 0, 0))));
  s.constraints[0].alpha = 8.0;
  s.constraints[0].beta = 8.0;
  s.constraints[1].alpha = 5.0;
  s.constraints[1].beta = 3.0;
  Simulation sim(s);
  const VecX c0 = sim.stats.constraint_violations;
  ASSERT_EQ(c0.size(), 2);
  const Real gains[2][2] = {{8, 8}, {5, 3}};
  Real worst[2] = {0, 0};
  while (sim.state.time < 1.5 - 1e-9) {
    ASSERT_TRUE(advance_frame(sim).ok);
    for (int j = 0; j < 2; ++j) {
      const Real exact = c0[j] * baumgarte_decay(gains[j][0], gains[j][1], sim.state.time);
      worst[j] = std::max(worst[j], std::abs(sim.stats.constraint_violations[j] - exact) / c0[j]);
    }
  }
  const VecX& c1 = sim.stats.constraint_violations;
  std::printf(
      "per-constraint gains: |C| %.3f -> %.3g m (alpha = beta = 8), %.3f -> %.3g m (alpha 5, "
      "beta 3); worst deviation from the closed forms %.2g, %.2g of |C(0)|\n",
      c0[0], c1[0], c0[1], c1[1], worst[0], worst[1]);
  EXPECT_LT(worst[0], 1e-6);
  EXPECT_LT(worst[1], 1e-6);
  // At 1.5 s the solver's gains would have left e^(-1.5) (1 + 1.5) = 0.56 of |C(0)|.
  EXPECT_LT(c1[0], 1e-3 * c0[0]);
  EXPECT_NEAR(c1[1] / c0[1], baumgarte_decay(5, 3, 1.5), 1e-4);
}

// The plank of Constraints.HingeSpringOscillatesAboutItsAxis with a damper c on its hinge:
// I theta'' = -k (theta - theta_0) - c theta', released at rest 0.3 rad from theta_0. The angle
// follows the damped oscillator's closed form, decay rate c / (2 I).
TEST(ConstraintParameters, HingeDamperDecaysTheSwingAtCOverTwoI) {
  Scene s = hinged_plank_scene(100);
  const Real inertia = inertia_about_y(Simulation(s).model.bodies[0]);
  const Real omega0 = std::sqrt(50 / inertia);
  s.constraints[0].damping = 0.6 * inertia * omega0;  // gamma = 0.3 omega0
  Simulation sim(s);
  const Real gamma = s.constraints[0].damping / (2 * inertia);
  const Real omega = std::sqrt(omega0 * omega0 - gamma * gamma);
  Real worst = 0;
  while (sim.state.time < 3 * 2 * std::numbers::pi / omega) {
    ASSERT_TRUE(advance_frame(sim).ok);
    const Real t = sim.state.time;
    const Real exact = 0.3 - 0.3 * std::exp(-gamma * t) *
                                 (std::cos(omega * t) + gamma / omega * std::sin(omega * t));
    const Real theta = hinge_angle(sim.model.constraints.hinges[0], sim.ws.bodies);
    worst = std::max(worst, std::abs(theta - exact));
  }
  const Real theta_end = hinge_angle(sim.model.constraints.hinges[0], sim.ws.bodies);
  std::printf(
      "hinge damper: gamma %.3f 1/s, omega %.3f rad/s; after three periods theta %.5f "
      "(rest 0.3); worst |theta - closed form| %.2g rad\n",
      gamma, omega, theta_end, worst);
  EXPECT_LT(worst, 1e-6);
  // Inside the envelope 0.3 e^(-gamma t) sqrt(1 + (gamma / omega)^2) of the closed form.
  EXPECT_NEAR(theta_end, 0.3,
              0.3 * std::exp(-gamma * sim.state.time) * std::hypot(1.0, gamma / omega) + 1e-6);
}

// Where (u, v) lands on the unit sphere x = (cos u cos v, cos u sin v, sin u).
Vec3 sphere_point(const Vec2& uv) {
  return Vec3(std::cos(uv.x()) * std::cos(uv.y()), std::cos(uv.x()) * std::sin(uv.y()),
              std::sin(uv.x()));
}

// A local ball hung from a world anchor by a constraint, and pulled sideways by a spring, both
// given by material points: the run is bit-identical to the one with the nearest nodes' indices,
// and the node taken is the nearest to the surface point on the sphere (chord distance, an
// independent measure from the (u, v) metric the engine uses).
TEST(ConstraintParameters, MaterialPointEndsActAtTheNearestNode) {
  Scene s;
  s.solver.dt = 2e-3;
  BodyDef ball = test::ball(DeformLevel::local, 8);
  ball.position = Vec3(0, 0, 2);
  s.bodies.push_back(ball);
  const Vec2 top(1.2, 0.4), side(0.1, -2.0);
  ConstraintEndDef end;
  end.body = 0;
  end.material_point = top;
  s.constraints.push_back(joint(end, world(Vec3(0, 0, 2) + sphere_point(top))));
  SpringDef spring;
  spring.body = 0;
  spring.material_point = side;
  spring.target = Vec3(2, -2, 2);
  spring.stiffness = 30;
  s.springs.push_back(spring);
  Simulation by_point(s);
  const Tessellation& t = by_point.model.bodies[0].tessellation;
  auto nearest_on_sphere = [&](const Vec2& uv) {
    int best = 0;
    for (int i = 1; i < t.node_count(); ++i) {
      if ((sphere_point(t.uv[i]) - sphere_point(uv)).norm() <
          (sphere_point(t.uv[best]) - sphere_point(uv)).norm()) {
        best = i;
      }
    }
    return best;
  };
  const int top_node = by_point.model.constraints.points[0].ends[0].node;
  const int side_node = by_point.model.springs[0].node;
  EXPECT_EQ(top_node, nearest_on_sphere(top));
  EXPECT_EQ(side_node, nearest_on_sphere(side));
  s.constraints[0].a.material_point.reset();
  s.constraints[0].a.node = top_node;
  s.springs[0].material_point.reset();
  s.springs[0].node = side_node;
  Simulation by_node(s);
  for (int f = 0; f < 15; ++f) {
    ASSERT_TRUE(advance_frame(by_point).ok);
    ASSERT_TRUE(advance_frame(by_node).ok);
  }
  EXPECT_EQ(hash_state(by_point.state), hash_state(by_node.state));
  // And the pull acted: the ball swung toward the spring's target.
  EXPECT_GT((by_point.state.q.segment<3>(0) - Vec3(0, 0, 2)).norm(), 0.01);
}

}  // namespace
}  // namespace pbm
