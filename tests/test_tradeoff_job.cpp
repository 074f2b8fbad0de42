// The studio's trade job (app/studio/tradeoff_job.h): the sweep runs on its own thread, its
// progress is readable while it runs, cancel stops it with a message and no report, and a point
// is applied as one scene whose solver and mesh are the point's.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "scene/scene_json.h"
#include "scene_builders.h"
#include "tradeoff_job.h"

namespace pbm {
namespace {

Scene ball_scene() {
  BodyDef b = test::ball(DeformLevel::local, 8);
  b.material.damping = 0.5;
  b.angular_velocity = Vec3(0.3, 1.0, 2.0);
  Scene s = test::free_space(b);
  s.solver.fps = 10;
  s.solver.dt = 0.01;
  return s;
}

TEST(TradeoffJob, RunsInTheBackgroundAndReportsOnce) {
  TradeoffJob job;
  job.start(ball_scene(), {"dt", "integrator"}, 0.5);
  int polls = 0;
  while (job.progress().running) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ++polls;
  }
  std::optional<TradeoffReport> report = job.take_report();
  ASSERT_TRUE(report) << job.error();
  EXPECT_EQ(report->points.size(), 12u);  // 4 dt x 3 integrators
  EXPECT_EQ(job.progress().done, 12);     // the last run's index (the reference is 0)
  EXPECT_EQ(job.progress().total, 13);
  EXPECT_FALSE(job.take_report());  // taken once
  EXPECT_TRUE(job.error().empty());
  std::printf("sweep of 12 runs in the background: %d polls\n", polls);
}

TEST(TradeoffJob, CancelStopsWithoutAReport) {
  TradeoffJob job;
  job.start(ball_scene(), {"dt", "integrator", "tolerance"}, 2.0);
  job.cancel();
  while (job.progress().running) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_FALSE(job.take_report());
  EXPECT_EQ(job.error(), "cancelled");
}

TEST(TradeoffJob, AnUnknownKnobIsAnErrorNotACrash) {
  TradeoffJob job;
  job.start(ball_scene(), {"speed"}, 0.5);
  while (job.progress().running) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_NE(job.error().find("unknown knob 'speed'"), std::string::npos) << job.error();
}

TEST(TradeoffJob, ApplyingAPointSetsTheSolverAndMesh) {
  Scene scene = ball_scene();
  scene.bodies[0].material.nodal_mass = 0;
  scene.bodies[0].material.mass = 10;
  TradeoffSetting point;
  point.dt = 0.0025;
  point.integrator = IntegratorKind::implicit;
  point.tolerance = 1e-6;
  point.resolution = 2.0;
  const Scene applied = parse_scene(scene_with_setting(scene, point).dump(), "applied");
  EXPECT_EQ(applied.solver.dt, 0.0025);
  EXPECT_EQ(applied.solver.integrator, IntegratorKind::implicit);
  EXPECT_EQ(applied.solver.shape_inertia_time.value_or(0), 0.01);  // the model that was measured
  EXPECT_EQ(applied.bodies[0].tessellation.rings, 16);
  EXPECT_EQ(applied.bodies[0].material.mass, 10);
}

}  // namespace
}  // namespace pbm
