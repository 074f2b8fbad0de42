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
  TradeoffSetting twice{0.01, IntegratorKind::euler, 1e-6, 2.0, false, std::nullopt};
  const Scene refined = apply_setting(scene, twice);
  EXPECT_EQ(refined.bodies[0].tessellation.rings, 16);
  EXPECT_EQ(refined.bodies[0].tessellation.segments, 16);
  EXPECT_THROW(default_knobs(scene, {"speed"}, notes), Error);

  // contact: both rules of a local body's push points, one point per triangle for "centroid".
  notes.clear();
  const TradeoffKnobs rules = default_knobs(scene, {"contact"}, notes);
  ASSERT_EQ(rules.contacts.size(), 2u);
  EXPECT_EQ(rules.contacts[1], ContactQuadrature::centroid);
  TradeoffSetting coarse{0.01,  IntegratorKind::euler,      1e-6, 1.0,
                         false, ContactQuadrature::centroid};
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
