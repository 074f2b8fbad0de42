// Motion capture (figure/mocap_clip.h, figure/mocap_retarget.h): the clip of scenes/mocap/wave.bvh
// (written by tools/gen-wave-bvh, whose channels are closed forms) read through assimp, its
// forward kinematics, its angles retargeted onto revolute and universal joints through the
// placement rotation (a Y-up clip stood up in a Z-up world), its rotations onto spherical joints'
// rotation vectors, its markers onto site paths, the refusals naming the key, and the mocap-wave
// scene's servos following the clip, on a universal shoulder or on a ball.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "control/ball_coordinates.h"
#include "core/error.h"
#include "core/keyframes.h"
#include "figure/figure_build.h"
#include "figure/mocap_retarget.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

constexpr Real kPi = std::numbers::pi_v<Real>;
const std::string kClip = std::string(PBM_SOURCE_DIR) + "/scenes/mocap/wave.bvh";
const std::string kScene = std::string(PBM_SOURCE_DIR) + "/scenes/mocap-wave.json";

// The channels of tools/gen-wave-bvh, in degrees.
Real smoothstep(Real x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}
Real abduction(Real t) {
  return 80 * (smoothstep((t - 0.3) / 0.7) - smoothstep((t - 3.2) / 0.6));
}
Real wave(Real t) {
  return 35 * std::sin(2 * kPi * 1.5 * (t - 1.0)) *
         (smoothstep((t - 1.0) / 0.3) - smoothstep((t - 2.9) / 0.3));
}
Real swing(Real t) {
  return 15 * std::sin(2 * kPi * 0.5 * t);
}
Real radians(Real degrees) {
  return degrees * kPi / 180;
}

Mat3 about_z(Real degrees) {
  return Eigen::AngleAxis<Real>(radians(degrees), Vec3::UnitZ()).toRotationMatrix();
}

TEST(Mocap, ClipReadsTheSkeletonAndItsFrames) {
  const MocapClip clip = load_mocap_clip(kClip, kMaxMocapFrames);
  EXPECT_NEAR(clip.frame_time, 1.0 / 30, 1e-7);  // the file says 0.03333333, assimp a float
  EXPECT_EQ(clip.frames, 121);
  for (const char* name : {"Hips", "Chest", "RightArm", "RightForeArm", "EndSite_RightForeArm",
                           "LeftArm", "LeftForeArm", "EndSite_LeftForeArm"}) {
    EXPECT_GE(clip.find(name), 0) << name;
  }
  const int hand = clip.find("EndSite_RightForeArm");
  std::vector<Mat3> R;
  std::vector<Vec3> x;
  for (int k : {0, 20, 45, 77, 120}) {
    mocap_pose(clip, k, R, x);
    const Real t = k / 30.0;
    // The hips 1 m up; the chest 12 cm above; the right shoulder 20 cm to the side, 36 up; the
    // arm turned about z by -abduction, the forearm by -wave more (BVH: Z X Y, intrinsic).
    const Vec3 shoulder(-20, 148, 0);
    const Mat3 arm = about_z(-abduction(t)), forearm = arm * about_z(-wave(t));
    const Vec3 expected = shoulder + arm * Vec3(0, -30, 0) + forearm * Vec3(0, -28, 0);
    EXPECT_LT((x[hand] - expected).norm(), 1e-4) << "frame " << k;  // the file's 6 decimals
    EXPECT_LT((R[clip.find("RightForeArm")] - forearm).norm(), 1e-6) << "frame " << k;
  }
}

TEST(Mocap, AnglesRetargetThroughThePlacement) {
  const Scene scene = load_scene(kScene);
  const CompiledFigure f = build_figure_model(scene.figures[0], kScene, "figures[0]");
  // The stood-up clip turns about world +y by abduction (BVH z is world -y): the universal
  // shoulder's first axis; the elbow about +y by wave; the left shoulder about +x by swing.
  const auto controller = [&](const std::string& joint, int dof) -> const ControllerDef& {
    for (const JointController& c : f.controllers) {
      if (c.def.joint == joint && c.def.dof == dof) return c.def;
    }
    throw std::runtime_error("no controller of " + joint);
  };
  struct Expected {
    const char* joint;
    int dof;
    Real (*angle)(Real);
  };
  const Expected cases[] = {{"upper_arm_r", 0, abduction},
                            {"upper_arm_r", 1, [](Real) { return 0.0; }},
                            {"forearm_r", 0, wave},
                            {"upper_arm_l", 0, swing},
                            {"forearm_l", 0, [](Real) { return 0.0; }}};
  for (const Expected& e : cases) {
    const ControllerDef& c = controller(e.joint, e.dof);
    EXPECT_EQ(c.kind, ControllerKind::stable_pd);
    EXPECT_EQ(c.kp, 400);
    ASSERT_EQ(c.keys.size(), 121u);
    Real worst = 0;
    for (const Keyframe& key : c.keys) {
      worst = std::max(worst, std::abs(key.value - radians(e.angle(key.time))));
    }
    EXPECT_LT(worst, 1e-6) << e.joint << " dof " << e.dof;
    EXPECT_NEAR(c.keys[30].time, 1.0, 1e-6);
  }
}

TEST(Mocap, MarkersBecomeSitePathsPlacedAndScaled) {
  const Scene scene = load_scene(kScene);
  const CompiledFigure f = build_figure_model(scene.figures[1], kScene, "figures[1]");
  ASSERT_EQ(f.site_actuators.size(), 1u);
  const SiteActuatorDef& a = f.site_actuators[0].def;
  EXPECT_EQ(a.stiffness, 400);
  EXPECT_EQ(a.damping, 20);
  const MocapClip clip = load_mocap_clip(kClip, kMaxMocapFrames);
  std::vector<Mat3> R;
  std::vector<Vec3> x;
  const Mat3 up = Eigen::AngleAxis<Real>(kPi / 2, Vec3::UnitX()).toRotationMatrix();
  for (int k = 0; k < clip.frames; k += 7) {
    mocap_pose(clip, k, R, x);
    const Vec3 expected = Vec3(1.2, 0, 0) + up * (0.01 * x[clip.find("EndSite_RightForeArm")]);
    const Vec3 got(a.x[k].value, a.y[k].value, a.z[k].value);
    EXPECT_LT((got - expected).norm(), 1e-9) << "frame " << k;
  }
  // At rest the hand hangs 0.9 m up, beside the figure by the placement's 1.2 m.
  EXPECT_LT((Vec3(a.x[0].value, a.y[0].value, a.z[0].value) - Vec3(1.0, 0, 0.9)).norm(), 1e-9);
}

void expect_mocap_error(const std::string& mocap, const std::string& path,
                        const std::string& message) {
  const std::string text =
      R"({"figures": [{"segments": [{"name": "a", "joint": {"axis": [0, 1, 0]},
          "sites": [{"name": "tip"}]}, {"name": "b", "parent": "a",
          "joint": {"kind": "fixed"}}], "mocap": )" +
      mocap + "}]}";
  try {
    parse_scene(text, std::string(PBM_SOURCE_DIR) + "/scenes/x.json");
    ADD_FAILURE() << "expected an error at " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.path(), path) << e.what();
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(Mocap, RefusalsNameTheKey) {
  expect_mocap_error(R"({"file": "mocap/none.bvh"})", "figures[0].mocap.file",
                     "cannot use motion capture");
  expect_mocap_error(R"({"file": "mocap/wave.bvh", "joints": [{"bvh": "Tail", "joint": "a"}]})",
                     "figures[0].mocap.joints[0].bvh", "'Tail' names no joint");
  expect_mocap_error(R"({"file": "mocap/wave.bvh", "joints": [{"bvh": "Chest", "joint": "c"}]})",
                     "figures[0].mocap.joints[0].joint", "names no segment");
  expect_mocap_error(R"({"file": "mocap/wave.bvh", "joints": [{"bvh": "Chest", "joint": "b"}]})",
                     "figures[0].mocap.joints[0].joint", "not revolute, universal or spherical");
  expect_mocap_error(R"({"file": "mocap/wave.bvh", "joints": [{"bvh": "Chest", "joint": "a"},
                         {"bvh": "Hips", "joint": "a"}]})",
                     "figures[0].mocap.joints[1].joint", "already mapped");
  expect_mocap_error(
      R"({"file": "mocap/wave.bvh", "sites": [{"bvh": "Chest", "segment": "a", "site": "toe"}]})",
      "figures[0].mocap.sites[0].site", "names no site");
  expect_mocap_error(R"({"file": "mocap/wave.bvh", "scale": 0})", "figures[0].mocap.scale",
                     "must be > 0");
  // Not a motion file at all: the schema is not a clip.
  expect_mocap_error(R"({"file": "scene.schema.json"})", "figures[0].mocap.file",
                     "cannot use motion capture");
}

TEST(Mocap, ServosFollowTheClip) {
  Simulation sim(load_scene(kScene));
  const CompiledFigure& f = sim.model.figures[0];
  int elbow = -1;
  for (int i = 0; i < f.model.size(); ++i) {
    if (f.model.segments[i].name == "forearm_r") elbow = f.model.segments[i].q_offset;
  }
  ASSERT_GE(elbow, 0);
  Real sum = 0, worst = 0;
  int n = 0;
  while (sim.state.time < sim.model.solver.duration - 1e-9) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    const Real error = sim.state.q[f.model.state_q_offset + elbow] - radians(wave(sim.state.time));
    sum += error * error;
    worst = std::max(worst, std::abs(error));
    ++n;
  }
  const Real rms = std::sqrt(sum / n);
  // The wave spans 70 degrees (1.22 rad).
  EXPECT_LT(rms, 0.02 * radians(70)) << "worst " << worst;
  std::printf("elbow follows the clip: RMS %.4f rad, worst %.4f rad\n", rms, worst);
}

// The mocap-wave scene with its right shoulder a spherical joint in place of the universal one:
// its three servos (the scene's stable PD) get the clip's rotation vector, abduction about +y,
// and the shoulder steps as the universal one does, the arm swinging in the xz plane with the
// ball's x and z components at rest (gravity and the clip turn it about y alone).
TEST(Mocap, ABallShoulderFollowsTheClipAsTheUniversalOne) {
  std::ifstream in(kScene);
  nlohmann::json j = nlohmann::json::parse(in);
  const Real duration = 2;
  j["solver"]["duration"] = duration;
  Simulation universal(parse_scene(j.dump(), kScene));
  nlohmann::json& shoulder = j["figures"][0]["segments"][3];
  ASSERT_EQ(shoulder["name"], "upper_arm_r");
  shoulder["joint"] = {{"kind", "spherical"}, {"position", {-0.2, 0, 0.36}}, {"damping", 0.5}};
  Simulation ball(parse_scene(j.dump(), kScene));
  const CompiledFigure& f = ball.model.figures[0];
  int at = -1;
  for (int i = 0; i < f.model.size(); ++i) {
    if (f.model.segments[i].name == "upper_arm_r") at = f.model.segments[i].q_offset;
  }
  ASSERT_GE(at, 0);
  for (int dof = 0; dof < 3; ++dof) {
    const JointController* c = nullptr;
    for (const JointController& k : f.controllers) {
      if (k.def.joint == "upper_arm_r" && k.def.dof == dof) c = &k;
    }
    ASSERT_NE(c, nullptr) << dof;
    EXPECT_TRUE(c->ball);
    EXPECT_EQ(c->def.kind, ControllerKind::stable_pd);
    Real worst = 0;
    for (const Keyframe& key : c->def.keys) {
      worst = std::max(worst, std::abs(key.value - (dof == 1 ? radians(abduction(key.time)) : 0)));
    }
    EXPECT_LT(worst, 1e-6) << "dof " << dof;
  }
  Real worst = 0, off_axis = 0, largest = 0;
  while (ball.state.time < duration - 1e-9) {
    const FrameResult a = advance_frame(universal), b = advance_frame(ball);
    ASSERT_TRUE(a.ok && b.ok) << a.message << b.message;
    const Vec3 r = ball_rotation_vector(ball.state.q.data() + f.model.state_q_offset + at);
    worst = std::max(worst, std::abs(r.y() - universal.state.q[f.model.state_q_offset + at]));
    off_axis = std::max({off_axis, std::abs(r.x()), std::abs(r.z())});
    largest = std::max(largest, r.y());
  }
  std::printf(
      "ball shoulder: abducts to %.3f rad; |r_y - q_universal| at most %.1e rad, "
      "|r_x|, |r_z| %.1e rad\n",
      largest, worst, off_axis);
  EXPECT_GT(largest, 1.2);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(off_axis, 1e-9);
}

}  // namespace
}  // namespace pbm
