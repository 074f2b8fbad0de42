// The measured trade (engine/sim/tradeoff.h, issue 12): a sweep's errors against its reference
// behave as the integrators' orders say, its costs count the substeps, the Pareto front is the
// set of undominated points, cancelling stops it, and the plot draws what it is given.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/error.h"
#include "plot_png.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/model.h"
#include "sim/tradeoff.h"

namespace pbm {
namespace {

Scene spinning_ball() {
  BodyDef b = test::ball(DeformLevel::local, 8);
  b.material.damping = 0.5;
  b.angular_velocity = Vec3(0.3, 1.0, 2.0);
  b.velocity = Vec3(0.5, 0, 0);
  b.q_s[1] = 1.2;  // released from an ellipsoid toward its sphere at rest
  Scene s = test::free_space(b);
  s.solver.fps = 10;
  s.solver.dt = 0.01;
  return s;
}

const TradeoffPoint& find(const TradeoffReport& r, IntegratorKind kind, Real dt) {
  for (const TradeoffPoint& p : r.points) {
    if (p.setting.integrator == kind && p.setting.dt == dt) return p;
  }
  ADD_FAILURE() << "no point at dt " << dt;
  return r.points.front();
}

// A figure's segments are measured like bodies' centres: a 3-link chain converges at Euler's
// first order as dt halves, and RK4 at the same step is far closer.
TEST(Tradeoff, AFiguresSegmentsConvergeAsTheIntegratorsOrderSays) {
  const Scene scene = parse_scene(
      R"({"solver": {"dt": 0.004, "fps": 25}, "figures": [{"segments": [
          {"name": "a", "joint": {"axis": [0, 1, 0], "position": [0, 0, 2], "q0": [1.2]},
           "shape": {"kind": "capsule", "size": [0.04, 0.04, 0.2], "center": [0, 0, -0.25]}},
          {"name": "b", "parent": "a", "joint": {"axis": [0, 1, 0], "position": [0, 0, -0.5]},
           "shape": {"kind": "capsule", "size": [0.04, 0.04, 0.2], "center": [0, 0, -0.25]}},
          {"name": "c", "parent": "b", "joint": {"kind": "spherical", "position": [0, 0, -0.5],
           "v0": [0, 0, 2]},
           "shape": {"kind": "box", "size": [0.1, 0.05, 0.05], "center": [0, 0, -0.1]}}]}]})",
      "chain.json");
  TradeoffOptions options;
  options.seconds = 1;
  options.reference_tolerance = 1e-10;
  options.knobs.dt = {0.004, 0.002, 0.001};
  options.knobs.integrators = {IntegratorKind::euler, IntegratorKind::rk4};
  options.knobs.tolerances = {1e-6};
  options.knobs.resolutions = {1.0};
  auto progress = [](int, int, const std::string&) {};
  const TradeoffReport r = run_tradeoff(scene, options, progress);
  for (const TradeoffPoint& p : r.points) ASSERT_TRUE(p.ok) << p.message;
  for (Real dt : {0.004, 0.002}) {
    const TradeoffPoint& coarse = find(r, IntegratorKind::euler, dt);
    const TradeoffPoint& fine = find(r, IntegratorKind::euler, dt / 2);
    const Real order = std::log2(coarse.centre_error / fine.centre_error);
    const Real joint_order = std::log2(coarse.joint_error / fine.joint_error);
    std::printf(
        "figure, euler dt %.3f -> %.4f: segments %.3e -> %.3e m, order %.2f; joints "
        "%.3e -> %.3e rad, order %.2f; rk4 %.3e m, %.3e rad\n",
        dt, dt / 2, coarse.centre_error, fine.centre_error, order, coarse.joint_error,
        fine.joint_error, joint_order, find(r, IntegratorKind::rk4, dt).centre_error,
        find(r, IntegratorKind::rk4, dt).joint_error);
    EXPECT_NEAR(order, 1.0, 0.3);
    EXPECT_NEAR(joint_order, 1.0, 0.3);
    EXPECT_LT(find(r, IntegratorKind::rk4, dt).centre_error, 1e-3 * coarse.centre_error);
    EXPECT_LT(find(r, IntegratorKind::rk4, dt).joint_error, 1e-3 * coarse.joint_error);
  }
  // The joint error is an angle: below pi, and at least the segments' error over 3 x 1.5 m (each
  // of the 3 joints, off by at most e rad, moves a segment origin within 1.5 m of it by at most
  // 1.5 e).
  for (const TradeoffPoint& p : r.points) {
    EXPECT_LT(p.joint_error, std::numbers::pi);
    EXPECT_GT(p.joint_error, p.centre_error / 1.5 / 3);
  }
  // RK4's fourth order (the reference, rk45 at 1e-10, is far below both).
  const Real rk4_order = std::log2(find(r, IntegratorKind::rk4, 0.004).centre_error /
                                   find(r, IntegratorKind::rk4, 0.002).centre_error);
  EXPECT_NEAR(rk4_order, 4.0, 0.5);
  const Real rk4_joint_order = std::log2(find(r, IntegratorKind::rk4, 0.004).joint_error /
                                         find(r, IntegratorKind::rk4, 0.002).joint_error);
  EXPECT_NEAR(rk4_joint_order, 4.0, 0.5);
}

// The contact stiffness knob: a box let down onto the ground on its four bottom corners sinks
// like a mass-spring-damper, m/4 on each corner's spring k and damper c. The knob scales k by f
// and c by sqrt(f), so the damping ratio zeta = c / (2 sqrt(k m/4)) = 0.5 stays and the deepest
// sink is the static one, m g / (4 k f), times 1 + exp(-pi zeta / sqrt(1 - zeta^2)). Each
// stiffness has its own converged reference, and its answer's distance from the scene's lies
// between the settled sinks' difference and the deeper peak.
TEST(Tradeoff, AStifferContactSinksLessAsTheSpringLawSaysAgainstItsOwnReference) {
  const Scene scene = parse_scene(
      R"({"solver": {"dt": 0.0005, "fps": 1000, "integrator": "rk4"},
          "obstacles": [{"name": "ground", "kind": "plane", "point": [0, 0, 0],
                         "normal": [0, 0, 1], "size": [5, 5]}],
          "figures": [{"impact_speed": 10, "contact_stiffness": 20000, "contact_damping": 200,
            "segments": [{"name": "box", "joint": {"kind": "free", "q0": [0, 0, 0.1, 1, 0, 0, 0]},
              "shape": {"kind": "box", "size": [0.1, 0.1, 0.1]}, "density": 1000}]}]})",
      "box.json");
  TradeoffOptions options;
  options.seconds = 0.15;  // the sink's decay time 1 / (zeta omega) is 40 ms at the softest
  options.reference_tolerance = 1e-11;
  options.knobs.dt = {0.0005};
  options.knobs.integrators = {IntegratorKind::rk4};
  options.knobs.tolerances = {1e-6};
  options.knobs.resolutions = {1.0};
  options.knobs.stiffness = {0.25, 1.0, 4.0};
  auto progress = [](int, int, const std::string&) {};
  const TradeoffReport r = run_tradeoff(scene, options, progress);
  ASSERT_EQ(r.references, 3);
  ASSERT_EQ(r.points.size(), 3u);
  const Real m = 8, g = 9.81, k = 2e4, zeta = 200 / (2 * std::sqrt(k * m / 4));
  ASSERT_NEAR(zeta, 0.5, 1e-12);
  const Real overshoot = 1 + std::exp(-std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta));
  const Real settled = m * g / (4 * k);  // the scene's own
  for (const TradeoffPoint& p : r.points) {
    ASSERT_TRUE(p.ok) << p.message;
    const Real f = p.setting.stiffness;
    std::printf(
        "contact stiffness %gx: deepest %.6e m (spring law %.6e), rk4 error %.3e m, "
        "answer off the scene's by %.3e m\n",
        f, p.depth, overshoot * settled / f, p.centre_error, p.physics_centre);
    EXPECT_NEAR(p.depth, overshoot * settled / f, 0.01 * settled / f);
    // Against its own reference, RK4 at 0.5 ms is far inside the scene's sink. (The contact's
    // onset at t = 0, a kink in the force, keeps RK4 at second order here: 2.2e-7 m.)
    EXPECT_LT(p.centre_error, 1e-3 * settled);
    if (f == 1) {
      EXPECT_TRUE(p.setting.current);
      EXPECT_EQ(p.physics_centre, 0);
      EXPECT_EQ(p.physics_joint, 0);
    } else {
      EXPECT_FALSE(p.setting.current);
      // The softer and the stiffer of this run and the scene's: their settled sinks.
      const Real soft = settled / std::min(f, 1.0), stiff = settled / std::max(f, 1.0);
      EXPECT_GT(p.physics_centre, (soft - stiff) * 0.999);
      // The stiffer one may be up to 10% below its settled sink when the softer peaks.
      EXPECT_LT(p.physics_centre, overshoot * soft - 0.9 * stiff);
      EXPECT_NE(p.setting.label().find("k "), std::string::npos);
    }
  }
}

TEST(Tradeoff, ErrorsFollowTheIntegratorsOrderAndCostCountsTheSubsteps) {
  const Scene scene = spinning_ball();
  TradeoffOptions options;
  options.seconds = 0.5;
  options.reference_tolerance = 1e-9;
  options.knobs.dt = {0.02, 0.01, 0.005};
  options.knobs.integrators = {IntegratorKind::euler, IntegratorKind::rk4};
  options.knobs.tolerances = {1e-6};
  options.knobs.resolutions = {1.0};
  int calls = 0;
  auto progress = [&](int done, int total, const std::string&) {
    EXPECT_EQ(done, calls);
    EXPECT_EQ(total, 7);
    ++calls;
  };
  const TradeoffReport r = run_tradeoff(scene, options, progress);
  ASSERT_EQ(r.points.size(), 6u);
  EXPECT_EQ(calls, 7);
  EXPECT_EQ(r.reference.integrator, IntegratorKind::rk45);
  EXPECT_EQ(r.reference.dt, 0.005);
  int current = 0;
  for (const TradeoffPoint& p : r.points) {
    ASSERT_TRUE(p.ok) << p.message;
    current += p.setting.current;
    // Past 2 tau the shape parameters' floor limits Euler (RK4: 2.78 tau; deform/
    // stability_limit.h): the substep is shortened, and the cost says so.
    if (p.setting.dt <= 0.01 || p.setting.integrator == IntegratorKind::rk4) {
      EXPECT_EQ(p.substeps, std::lround(0.5 / p.setting.dt)) << p.setting.label();
    } else {
      EXPECT_GT(p.substeps, std::lround(0.5 / p.setting.dt)) << p.setting.label();
    }
    EXPECT_GE(p.node_rms, 0);  // the reference's node count
  }
  EXPECT_EQ(current, 1);
  EXPECT_TRUE(find(r, IntegratorKind::euler, 0.01).setting.current);
  for (Real dt : {0.02, 0.01}) {
    const TradeoffPoint& coarse = find(r, IntegratorKind::euler, dt);
    const TradeoffPoint& fine = find(r, IntegratorKind::euler, dt / 2);
    const Real order = std::log2(coarse.node_rms / fine.node_rms);
    std::printf(
        "euler dt %.3f -> %.4f: centre %.3e -> %.3e m, nodes rms %.3e -> %.3e m, order "
        "%.2f\n",
        dt, dt / 2, coarse.centre_error, fine.centre_error, coarse.node_rms, fine.node_rms, order);
    EXPECT_NEAR(order, 1.0, 0.3);
    EXPECT_LT(fine.centre_error, coarse.centre_error);
    // RK4 at the same step is far more accurate (a local body converges at order ~1 with RK4
    // too, test_convergence, so not by its fourth order).
    EXPECT_LT(find(r, IntegratorKind::rk4, dt).node_rms, 0.5 * coarse.node_rms);
    EXPECT_GT(find(r, IntegratorKind::rk4, dt).evaluations, 3 * coarse.evaluations);
  }
  // The front: no point on it is beaten in both cost and error, every point off it is.
  int on_front = 0;
  for (const TradeoffPoint& p : r.points) {
    bool dominated = false;
    for (const TradeoffPoint& q : r.points) {
      dominated |= &q != &p && q.wall_seconds <= p.wall_seconds &&
                   q.centre_error <= p.centre_error &&
                   (q.wall_seconds < p.wall_seconds || q.centre_error < p.centre_error);
    }
    EXPECT_EQ(p.pareto, !dominated) << p.setting.label();
    on_front += p.pareto;
  }
  EXPECT_GE(on_front, 1);
  // The most accurate point is always on it.
  const TradeoffPoint* best = &r.points.front();
  for (const TradeoffPoint& p : r.points)
    if (p.centre_error < best->centre_error) best = &p;
  EXPECT_TRUE(best->pareto);
}

TEST(Tradeoff, ParetoFrontOfKnownPoints) {
  std::vector<TradeoffPoint> points(5);
  const double cost[] = {1, 2, 3, 2, 5};
  const double error[] = {5, 3, 1, 4, 1};
  for (int i = 0; i < 5; ++i) {
    points[i].ok = true;
    points[i].wall_seconds = cost[i];
    points[i].centre_error = error[i];
  }
  points[4].ok = false;  // a failed run is never on it
  points[4].centre_error = 0;
  mark_pareto_front(points);
  EXPECT_TRUE(points[0].pareto);
  EXPECT_TRUE(points[1].pareto);
  EXPECT_TRUE(points[2].pareto);
  EXPECT_FALSE(points[3].pareto);  // (2, 4) is beaten by (2, 3)
  EXPECT_FALSE(points[4].pareto);
}

TEST(Tradeoff, CancelStopsTheSweep) {
  const Scene scene = spinning_ball();
  TradeoffOptions options;
  options.seconds = 0.5;
  std::vector<std::string> notes;
  options.knobs = default_knobs(scene, {"dt", "integrator"}, notes);
  std::atomic<bool> cancel{false};
  int calls = 0;
  auto progress = [&](int, int, const std::string&) {
    if (++calls == 3) cancel = true;  // during the second setting
  };
  const TradeoffReport r = run_tradeoff(scene, options, progress, &cancel);
  EXPECT_TRUE(r.cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_LE(r.points.size(), 2u);
}

TEST(Tradeoff, KnobsAroundTheScenesSetting) {
  Scene scene = spinning_ball();
  std::vector<std::string> notes;
  const TradeoffKnobs knobs =
      default_knobs(scene, {"dt", "integrator", "tolerance", "resolution"}, notes);
  // 2x and 1x of 0.01 s, 1/2, 1/4; capped at the frame (0.1 s) where it applies.
  EXPECT_EQ(knobs.dt, (std::vector<Real>{0.02, 0.01, 0.005, 0.0025}));
  EXPECT_EQ(knobs.integrators.size(), 4u);  // euler, rk4, implicit, and rk45 for the tolerance
  EXPECT_EQ(knobs.tolerances.size(), 3u);
  // The ball's mass is given per node: refining the mesh adds mass, so resolution is left out.
  EXPECT_EQ(knobs.resolutions, std::vector<Real>{1.0});
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("nodal_mass"), std::string::npos);
  scene.bodies[0].material.nodal_mass = 0;
  scene.bodies[0].material.mass = 10;
  notes.clear();
  EXPECT_EQ(default_knobs(scene, {"resolution"}, notes).resolutions,
            (std::vector<Real>{0.5, 1.0, 2.0}));
  EXPECT_TRUE(notes.empty());
  TradeoffSetting twice;
  twice.dt = 0.01;
  twice.tolerance = 1e-6;
  twice.resolution = 2.0;
  const Scene refined = apply_setting(scene, twice);
  EXPECT_EQ(refined.bodies[0].tessellation.rings, 16);
  EXPECT_EQ(refined.bodies[0].tessellation.segments, 16);
  EXPECT_THROW(default_knobs(scene, {"speed"}, notes), Error);

  // contact: both rules of a local body's push points, one point per triangle for "centroid".
  notes.clear();
  const TradeoffKnobs rules = default_knobs(scene, {"contact"}, notes);
  ASSERT_EQ(rules.contacts.size(), 2u);
  EXPECT_EQ(rules.contacts[1], ContactQuadrature::centroid);
  TradeoffSetting coarse;
  coarse.dt = 0.01;
  coarse.tolerance = 1e-6;
  coarse.contact = ContactQuadrature::centroid;
  EXPECT_NE(coarse.label().find("centroid"), std::string::npos);
  const Model three = build_model(scene);
  const Model one = build_model(apply_setting(scene, coarse));
  const std::size_t triangles = three.bodies[0].tessellation.triangles.size();
  EXPECT_EQ(three.bodies[0].contact_samples.size(), 3 * triangles);
  EXPECT_EQ(one.bodies[0].contact_samples.size(), triangles);
  // A rigid body has no push points: the knob is left out with a note.
  Scene rigid = scene;
  rigid.bodies[0].level = DeformLevel::rigid;
  notes.clear();
  EXPECT_EQ(default_knobs(rigid, {"contact"}, notes).contacts.size(), 1u);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("contact left out"), std::string::npos);
}

// The figures' physics knobs: around the scene's values, left out with a note where nothing
// has what they act on, and applied as their comments say (dampers by the square root).
TEST(Tradeoff, TheFiguresPhysicsKnobs) {
  Scene scene = parse_scene(
      R"({"figures": [{"restitution": 0.5, "segments": [{"name": "arm",
          "joint": {"axis": [0, 1, 0]},
          "shape": {"kind": "capsule", "size": [0.04, 0.04, 0.2], "center": [0, 0, -0.25]}}]}]})",
      "arm.json");
  std::vector<std::string> notes;
  TradeoffKnobs knobs =
      default_knobs(scene, {"stiffness", "restitution", "gains", "settling"}, notes);
  EXPECT_EQ(knobs.stiffness, (std::vector<Real>{0.25, 1.0, 4.0}));
  // The scene's own e (0.5) first, then the usual ones it does not have.
  EXPECT_EQ(knobs.restitution, (std::vector<std::optional<Real>>{std::nullopt, 0.0, 1.0}));
  EXPECT_TRUE(knobs.gains.empty());
  EXPECT_TRUE(knobs.settling.empty());
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("gains left out"), std::string::npos);
  EXPECT_NE(notes[1].find("settling left out"), std::string::npos);

  ControllerDef pd;
  pd.kind = ControllerKind::stable_pd;
  pd.joint = "arm";
  pd.kp = 100;
  pd.kd = 10;
  pd.keys = {{0, 0.1}};
  ControllerDef mrac = pd;
  mrac.kind = ControllerKind::mrac;
  scene.figures[0].controllers = {pd};
  notes.clear();
  knobs = default_knobs(scene, {"gains", "settling"}, notes);
  EXPECT_EQ(knobs.gains, (std::vector<Real>{0.5, 1.0, 2.0}));
  EXPECT_TRUE(knobs.settling.empty());  // t_s is MRAC's
  ASSERT_EQ(notes.size(), 1u);
  scene.figures[0].controllers = {pd, mrac};
  notes.clear();
  knobs = default_knobs(scene, {"settling"}, notes);
  EXPECT_EQ(knobs.settling, (std::vector<Real>{0.5, 1.0, 2.0}));
  EXPECT_TRUE(notes.empty());

  TradeoffSetting s;
  s.stiffness = 4;
  s.restitution = 1;
  s.gains = 9;
  s.settling = 0.5;
  EXPECT_FALSE(s.scenes_physics());
  EXPECT_TRUE(TradeoffSetting{}.scenes_physics());
  const Scene changed = apply_setting(scene, s);
  const FigureDef& a = scene.figures[0];
  const FigureDef& b = changed.figures[0];
  EXPECT_EQ(b.contact_stiffness, 4 * a.contact_stiffness);
  EXPECT_EQ(b.contact_damping, 2 * a.contact_damping);
  EXPECT_EQ(b.restitution, 1);
  EXPECT_EQ(b.controllers[0].kp, 900);
  EXPECT_EQ(b.controllers[0].kd, 30);
  EXPECT_EQ(b.controllers[1].alpha, 9 * a.controllers[1].alpha);
  EXPECT_EQ(b.controllers[1].beta, 9 * a.controllers[1].beta);
  EXPECT_EQ(b.controllers[1].settling_time, 0.5 * a.controllers[1].settling_time);
  EXPECT_EQ(s.label(), "euler dt 0 res 1x k 4x e 1 gains 9x t_s 0.5x");

  // Without figures, each is left out with a note.
  notes.clear();
  knobs = default_knobs(spinning_ball(), {"stiffness", "restitution", "gains", "settling"}, notes);
  EXPECT_TRUE(knobs.stiffness.empty() && knobs.restitution.empty() && knobs.gains.empty() &&
              knobs.settling.empty());
  EXPECT_EQ(notes.size(), 4u);
}

// The liquids' knobs, each swept alone around the scene's setting against a reference at the
// converged end of each (the finest grid and the smallest CFL number): a 2D tank released from a
// step in its surface approaches the reference's volume, front and centre of mass as its grid
// refines, and its centre as its CFL number falls (16.3); a knob without a liquid is left out.
Scene released_step() {
  Scene s;
  s.name = "step";
  s.solver.fps = 30;
  LiquidDef liquid;
  liquid.name = "step";
  const Real thin = 1.0 / 32;
  liquid.domain = {Vec3(0, 0, 0), Vec3(1, thin, 0.5)};
  liquid.resolution = Eigen::Vector3i(32, 1, 16);
  liquid.fluid.push_back({{Vec3(0, 0, 0), Vec3(0.5, thin, 0.3)}, Vec3::Zero()});
  liquid.fluid.push_back({{Vec3(0.5, 0, 0), Vec3(1, thin, 0.2)}, Vec3::Zero()});
  liquid.volume_correction = 0.2;
  s.liquids.push_back(liquid);
  return s;
}

TEST(Tradeoff, ALiquidConvergesAsItsGridRefinesAndItsCflFalls) {
  const Scene scene = released_step();
  std::vector<std::string> notes;
  TradeoffOptions options;
  options.seconds = 1;
  options.knobs = default_knobs(scene, {"liquid_resolution", "cfl"}, notes);
  EXPECT_TRUE(notes.empty());
  const TradeoffReport report = run_tradeoff(scene, options, [](int, int, const std::string&) {});
  EXPECT_EQ(report.reference.liquid_resolution, 2.0);
  EXPECT_EQ(report.reference.cfl, 0.25);
  // The scene's own CFL (0.5) is not run twice.
  EXPECT_EQ(report.points.size(), 5u);
  auto point = [&](Real resolution, Real cfl) -> const TradeoffPoint& {
    for (const TradeoffPoint& p : report.points) {
      if (p.setting.liquid_resolution == resolution && p.setting.cfl == cfl) return p;
    }
    ADD_FAILURE() << "no point at resolution " << resolution << " cfl " << cfl;
    return report.points.front();
  };
  const TradeoffPoint& half = point(0.5, 0);
  const TradeoffPoint& own = point(1, 0);
  const TradeoffPoint& twice = point(2, 0);
  const TradeoffPoint& cfl1 = point(1, 1.0);
  const TradeoffPoint& cfl_quarter = point(1, 0.25);
  for (const TradeoffPoint* p : {&half, &own, &twice, &cfl1, &cfl_quarter}) {
    ASSERT_TRUE(p->ok) << p->setting.label() << ": " << p->message;
    std::printf("%-40s volume %.4f, front %.4f m, centre %.4f m, top %.4f m, %.3f s\n",
                p->setting.label().c_str(), p->liquid_volume, p->liquid_front, p->liquid_centre,
                p->liquid_height, p->wall_seconds);
  }
  EXPECT_LT(own.liquid_volume, half.liquid_volume);
  EXPECT_LT(twice.liquid_volume, own.liquid_volume);
  EXPECT_LT(own.liquid_front, half.liquid_front);
  EXPECT_LT(twice.liquid_front, own.liquid_front);
  EXPECT_LT(own.liquid_centre, half.liquid_centre);
  EXPECT_LT(twice.liquid_centre, own.liquid_centre);
  EXPECT_LT(cfl_quarter.liquid_centre, own.liquid_centre);
  EXPECT_LT(own.liquid_centre, cfl1.liquid_centre);
  // The knob applied: cells per axis doubled, the thin axis left one cell thick.
  TradeoffSetting doubled;
  doubled.liquid_resolution = 2;
  EXPECT_EQ(apply_setting(scene, doubled).liquids[0].resolution, Eigen::Vector3i(64, 1, 32));
  EXPECT_NE(doubled.label().find("cells 2x"), std::string::npos);
  // Without a liquid: left out with a note.
  notes.clear();
  EXPECT_TRUE(default_knobs(spinning_ball(), {"cfl"}, notes).cfl.empty());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("no liquid"), std::string::npos);
}

TEST(Tradeoff, PlotDrawsItsPointsFrontAndHighlight) {
  LogLogPlot plot;
  plot.title = "title";
  plot.x_label = "x";
  plot.y_label = "y";
  PlotSeries s;
  s.name = "series";
  s.color = {40, 100, 200};
  s.points = {{1e-3, 1e-1}, {1e-2, 1e-2}, {1e-1, 1e-4}};
  plot.series.push_back(s);
  plot.line = s.points;
  plot.line_name = "front";
  plot.highlight = {s.points[1]};
  plot.highlight_name = "current";
  const RgbImage image = render_plot(plot);
  ASSERT_EQ(image.width, plot.width);
  ASSERT_EQ(image.height, plot.height);
  int series = 0, red = 0, dark = 0;
  for (std::size_t i = 0; i < image.pixels.size(); i += 3) {
    const int r = image.pixels[i], g = image.pixels[i + 1], b = image.pixels[i + 2];
    series += r == 40 && g == 100 && b == 200;
    red += r > 200 && g < 60 && b < 60;
    dark += r < 30 && g < 30 && b < 30;
  }
  std::printf("plot: %d series pixels, %d red, %d dark\n", series, red, dark);
  EXPECT_GT(series, 4 * 40);  // three markers and the legend's, ~60 px each
  EXPECT_GT(red, 100);        // the highlight ring and its legend
  EXPECT_GT(dark, 1000);      // the front, the text
}

}  // namespace
}  // namespace pbm
