// Live control of figures from the studio (issue 13, fig. 15.11's crane panel): targets set on a
// joint controller during play, and the mouse spring on a figure's segment, act from the moment
// they are given, are recorded into the scene, and the saved scene plays them back bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "control/joint_trajectory.h"
#include "core/error.h"
#include "scene/scene_json.h"
#include "sim/runner.h"

namespace pbm {
namespace {

// A 1 kg ball on a 0.5 m arm hinged about +y at (0, 0, 1): q = 0 is horizontal along +x, and a
// positive q turns it down (toward -z). `controllers` is the JSON list's contents.
Scene arm(const std::string& controllers) {
  return parse_scene(R"({"solver": {"dt": 0.005, "fps": 50, "integrator": "euler", "duration": 4},
    "figures": [{"name": "arm", "segments": [{"name": "link", "joint": {"axis": [0, 1, 0],
      "position": [0, 0, 1]}, "shape": {"kind": "sphere", "size": [0.15811388300841897, 0.1, 0.1],
      "center": [0.5, 0, 0]}, "mass": 1}], "controllers": [)" +
                         controllers + "]}]}",
                     "arm.json");
}

const std::string kServo =
    R"({"kind": "stable_pd", "joint": "link", "keys": [[0, 0], [1, 0.4]], "kp": 200, "kd": 15})";

bool same_state(const State& a, const State& b) {
  return a.time == b.time && a.q == b.q && a.v == b.v && hash_state(a) == hash_state(b);
}

void step(RunnerCore& core, int frames) {
  for (int k = 0; k < frames; ++k) ASSERT_EQ(core.apply(StepFrame{}), "") << core.message();
}

// Where a servo of stiffness kp holds the arm against gravity: kp (q - target) = m g l cos(q).
Real servo_rest(Real target, Real kp) {
  Real q = target;
  for (int k = 0; k < 100; ++k) q = target + 9.81 * 0.5 * std::cos(q) / kp;
  return q;
}

TEST(LiveControl, TargetsSetDuringPlayAreRecordedAndTheSavedScenePlaysThemBackBitForBit) {
  RunnerCore live(arm(kServo));
  step(live, 25);  // 0.5 s along the keyed trajectory
  EXPECT_EQ(live.apply(ControlSet{0, 0, 1.0}), "");
  EXPECT_EQ(live.apply(ControlSet{0, 0, 0.9}), "");  // the same instant: replaces the key
  step(live, 10);
  EXPECT_EQ(live.apply(ControlSet{0, 0, -0.3}), "");
  const std::vector<LiveKey>& keys = live.scene().figures[0].controllers[0].live;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].time, 0.5);
  EXPECT_EQ(keys[0].value, 0.9);
  EXPECT_EQ(keys[1].time, 0.7);
  EXPECT_EQ(keys[1].value, -0.3);
  step(live, 115);  // to 3 s
  const ControlSample& now = live.last_stats().figures[0].controllers[0];
  EXPECT_EQ(now.desired, -0.3);  // the input, not the keys' 0.4
  // 2.3 s after the last setting the servo (near critical damping) holds the arm where its
  // spring balances gravity.
  const Real rest = servo_rest(-0.3, 200);
  std::printf("live target -0.3 rad: arm at %.6f rad after 2.3 s (static balance %.6f)\n",
              live.state().q[0], rest);
  EXPECT_NEAR(live.state().q[0], rest, 1e-4);
  // Saved, read back and played from the start: the same states bit for bit.
  RunnerCore replayed(parse_scene(scene_to_json(live.scene()), "arm.json"));
  EXPECT_EQ(replayed.scene().figures[0].controllers[0].live.size(), 2u);
  EXPECT_EQ(replayed.apply(Seek{150}), "");
  EXPECT_TRUE(same_state(replayed.state(), live.state()));
  // Before the first setting the keys still drive it: at 0.4 s both runs agree with an
  // untouched one.
  RunnerCore untouched(arm(kServo));
  EXPECT_EQ(untouched.apply(Seek{20}), "");
  EXPECT_EQ(replayed.apply(Seek{20}), "");
  EXPECT_TRUE(same_state(replayed.state(), untouched.state()));
}

TEST(LiveControl, ASeekAfterSeveralSettingsResimulatesThemAll) {
  // A cache too small for any frame but the first forces every seek to simulate again: the
  // settings made since the last compile must be in the Model by then.
  RunnerCore live(arm(kServo), 1);
  step(live, 10);
  EXPECT_EQ(live.apply(ControlSet{0, 0, 1.0}), "");
  step(live, 10);
  EXPECT_EQ(live.apply(ControlSet{0, 0, -0.3}), "");
  step(live, 9);
  const State end = live.state();
  step(live, 1);  // frame 29 leaves the cache
  ASSERT_EQ(live.timeline().find(29), nullptr);
  EXPECT_EQ(live.apply(Seek{29}), "");
  EXPECT_TRUE(same_state(live.state(), end));
  // The first setting mattered: without it the arm is elsewhere.
  RunnerCore second_only(arm(kServo));
  step(second_only, 20);
  second_only.apply(ControlSet{0, 0, -0.3});
  step(second_only, 10);
  EXPECT_GT(std::abs(second_only.state().q[0] - end.q[0]), 1e-3);
}

TEST(LiveControl, AJogMovesTheTargetAtItsSpeedFromWhereItIsAndReleasingItStopsThere) {
  RunnerCore live(arm(kServo));
  step(live, 25);  // 0.5 s along the keyed trajectory
  const Real t0 = live.state().time;
  const Real d0 = desired_motion(Interpolation::smooth, {{0, 0}, {1, 0.4}}, t0).q;
  // The lever held at -0.5 rad/s: the target continues from the trajectory's position.
  EXPECT_EQ(live.apply(ControlSet{0, 0, 0, -0.5, true}), "");
  step(live, 10);
  const Real t1 = live.state().time;
  EXPECT_NEAR(live.last_stats().figures[0].controllers[0].desired, d0 - 0.5 * (t1 - t0), 1e-12);
  step(live, 10);
  // Released: the target stops where the jog had taken it.
  const Real t2 = live.state().time;
  EXPECT_EQ(live.apply(ControlSet{0, 0, 0, 0, true}), "");
  const std::vector<LiveKey>& keys = live.scene().figures[0].controllers[0].live;
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].time, t0);
  EXPECT_EQ(keys[0].value, d0);
  EXPECT_EQ(keys[0].rate, -0.5);
  EXPECT_EQ(keys[1].time, t2);
  EXPECT_NEAR(keys[1].value, d0 - 0.5 * (t2 - t0), 1e-12);
  EXPECT_EQ(keys[1].rate, 0);
  const Real stop = keys[1].value;
  step(live, 100);  // 2 s later the servo holds the arm at the stopped target
  EXPECT_EQ(live.last_stats().figures[0].controllers[0].desired, stop);
  const Real rest = servo_rest(stop, 200);
  std::printf(
      "jog -0.5 rad/s for %.2f s from %.6f: target stopped at %.6f, arm at %.6f rad "
      "(static balance %.6f)\n",
      t2 - t0, d0, stop, live.state().q[0], rest);
  EXPECT_NEAR(live.state().q[0], rest, 1e-4);
  // The jog is in the saved scene ([time, value, rate]) and replays bit for bit.
  const std::string text = scene_to_json(live.scene());
  RunnerCore replayed(parse_scene(text, "arm.json"));
  ASSERT_EQ(replayed.scene().figures[0].controllers[0].live.size(), 2u);
  EXPECT_EQ(replayed.scene().figures[0].controllers[0].live[0].rate, -0.5);
  EXPECT_EQ(replayed.apply(Seek{145}), "");
  EXPECT_TRUE(same_state(replayed.state(), live.state()));
}

TEST(LiveControl, BadSettingsAreRefusedWithTheReason) {
  RunnerCore core(arm(kServo));
  EXPECT_NE(core.apply(ControlSet{1, 0, 0.5}).find("no figure 1"), std::string::npos);
  EXPECT_NE(core.apply(ControlSet{0, 1, 0.5}).find("has no controller 1"), std::string::npos);
  EXPECT_NE(core.apply(ControlSet{0, 0, std::nan("")}).find("not finite"), std::string::npos);
  EXPECT_NE(core.apply(ControlSet{0, 0, 0, std::nan(""), true}).find("rate is not finite"),
            std::string::npos);
  EXPECT_TRUE(core.scene().figures[0].controllers[0].live.empty());
  // A live key out of order in a file names its field.
  std::string text = scene_to_json(arm(kServo));
  const std::string keys = R"("keys":)";
  text.insert(text.find(keys), R"("live": [[0.5, 1], [0.2, 0]], )");
  try {
    parse_scene(text, "arm.json");
    ADD_FAILURE() << "accepted live keys out of order";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("figures[0].controllers[0].live"), std::string::npos)
        << e.what();
  }
  // So does a key of four numbers.
  text = scene_to_json(arm(kServo));
  text.insert(text.find(keys), R"("live": [[0.5, 1, 0.1, 2]], )");
  try {
    parse_scene(text, "arm.json");
    ADD_FAILURE() << "accepted a live key of four numbers";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("figures[0].controllers[0].live[0]"), std::string::npos)
        << e.what();
  }
}

TEST(FigureMouseSpring, HoldsTheArmWhereItsSpringBalancesGravityAndReplaysFromTheSavedScene) {
  RunnerCore dragged(arm(""));
  // Grab the ball's centre at the start and hold it there: the arm sags until the spring's
  // torque k l^2 sin(q) balances gravity's m g l cos(q), tan(q) = m g / (k l).
  const Vec3 centre(0.5, 0, 1);
  EXPECT_EQ(dragged.apply(FigureSpringBegin{0, 0, centre, centre}), "");
  const FigureDef& def = dragged.scene().figures[0];
  ASSERT_EQ(def.site_actuators.size(), 1u);
  EXPECT_EQ(def.segments[0].sites.back().name, "drag 1");
  EXPECT_LT((def.segments[0].sites.back().position - Vec3(0.5, 0, 0)).norm(), 1e-15);
  const MouseSpringParameters p = figure_spring_parameters(dragged.model(), 0, 0);
  const Real omega = 2 * std::numbers::pi * 1.5;
  EXPECT_NEAR(p.stiffness, omega * omega, 1e-9);  // 1 kg: the hand's 1.5 Hz
  for (int f = 1; f <= 150; ++f) {
    step(dragged, 1);
    if (f % 5 == 0) {
      EXPECT_EQ(dragged.apply(SpringMove{centre}), "");
    }
  }
  const Real expected = std::atan(9.81 / (p.stiffness * 0.5));
  std::printf("held at its centre by the mouse spring (k %.4g N/m): q %.6f rad, balance %.6f\n",
              p.stiffness, dragged.state().q[0], expected);
  EXPECT_NEAR(dragged.state().q[0], expected, 1e-3);
  const SitePull& pull = dragged.last_stats().figures[0].site_actuators[0];
  EXPECT_TRUE(pull.active);
  EXPECT_LE(pull.force.norm(), p.max_force);
  EXPECT_EQ(dragged.apply(SpringEnd{}), "");
  EXPECT_EQ(*dragged.scene().figures[0].site_actuators[0].t_end, 3.0);
  step(dragged, 25);  // let go: it swings down freely
  EXPECT_FALSE(dragged.last_stats().figures[0].site_actuators[0].active);
  EXPECT_GT(dragged.state().q[0], expected + 0.3);
  EXPECT_NE(dragged.apply(SpringMove{centre}), "");
  RunnerCore replayed(parse_scene(scene_to_json(dragged.scene()), "arm.json"));
  EXPECT_EQ(replayed.apply(Seek{175}), "");
  EXPECT_TRUE(same_state(replayed.state(), dragged.state()));
  // A grab while another drag is under way releases that one first (recompiling the scene) and
  // takes the new one on the new Model.
  EXPECT_EQ(dragged.apply(FigureSpringBegin{0, 0, centre, centre}), "");
  EXPECT_EQ(dragged.apply(FigureSpringBegin{0, 0, centre, centre + Vec3(0, 0, 0.1)}), "");
  ASSERT_EQ(dragged.scene().figures[0].site_actuators.size(), 3u);
  EXPECT_EQ(*dragged.scene().figures[0].site_actuators[1].t_end, dragged.state().time);
  EXPECT_EQ(dragged.scene().figures[0].segments[0].sites.back().name, "drag 3");
  EXPECT_EQ(dragged.apply(SpringEnd{}), "");
  // Bad grabs are refused.
  EXPECT_NE(dragged.apply(FigureSpringBegin{1, 0, centre, centre}), "");
  EXPECT_NE(dragged.apply(FigureSpringBegin{0, 1, centre, centre}), "");
  EXPECT_NE(dragged.apply(FigureSpringBegin{0, 0, Vec3(NAN, 0, 0), centre}), "");
}

}  // namespace
}  // namespace pbm
