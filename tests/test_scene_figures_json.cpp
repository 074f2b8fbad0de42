// The "figures[i]" section of scene files (ch. 15): segments, joints of every kind, shapes and
// sites with their defaults; the figure compiled as it is read, so that a bad tree, mass, axis
// or initial state is refused at the path of the key at fault.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "figure/figure_build.h"
#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneFiguresJson, SegmentsJointsShapesAndSitesWithDefaults) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.figures.size(), 1u);
  const FigureDef& arm = s.figures[0];
  EXPECT_EQ(arm.name, "arm");
  EXPECT_EQ(arm.restitution, 0.3);
  EXPECT_EQ(arm.contact_stiffness, 5e4);
  ASSERT_EQ(arm.segments.size(), 6u);
  const SegmentDef& base = arm.segments[0];
  EXPECT_EQ(base.parent, "");
  EXPECT_EQ(base.joint.kind, JointKind::free);
  EXPECT_EQ(base.joint.q0, (std::vector<Real>{0, 0, 1, 2, 0, 0, 0}));
  EXPECT_EQ(base.mass, 2);
  const SegmentDef& upper = arm.segments[1];
  EXPECT_EQ(upper.parent, "base");
  EXPECT_EQ(upper.joint.axis, Vec3(0, 1, 0));  // normalized on load
  EXPECT_EQ(upper.joint.damping, 0.1);
  EXPECT_EQ(upper.joint.stiffness, 5);
  EXPECT_EQ(upper.joint.rest, std::vector<Real>{0.1});
  EXPECT_EQ(upper.shape.kind, SegmentShapeKind::capsule);
  EXPECT_EQ(upper.mass, 0);  // from the density
  EXPECT_EQ(upper.density, 900);
  ASSERT_EQ(upper.sites.size(), 2u);
  EXPECT_EQ(upper.sites[0].name, "elbow");
  EXPECT_EQ(upper.sites[1].name, "site1");
  EXPECT_EQ(upper.sites[1].orientation, Vec4(0, 1, 0, 0));
  EXPECT_EQ(arm.segments[2].name, "segment2");
  EXPECT_EQ(arm.segments[2].joint.kind, JointKind::spherical);
  EXPECT_EQ(arm.segments[3].joint.axis2, Vec3(0, 0, 1));
  EXPECT_EQ(arm.segments[4].joint.kind, JointKind::prismatic);
  EXPECT_EQ(arm.segments[5].joint.kind, JointKind::fixed);
  EXPECT_EQ(arm.segments[5].shape.kind, SegmentShapeKind::box);
  EXPECT_EQ(arm.segments[5].density, 1000);
  ASSERT_EQ(arm.controllers.size(), 3u);
  const ControllerDef& mrac = arm.controllers[0];
  EXPECT_EQ(mrac.kind, ControllerKind::mrac);
  EXPECT_EQ(mrac.interpolation, Interpolation::smooth);  // the default
  EXPECT_EQ(mrac.keys.size(), 2u);
  EXPECT_EQ(mrac.settling_time, 0.2);
  EXPECT_EQ(mrac.max_output, 40);
  EXPECT_EQ(arm.controllers[1].dof, 1);
  EXPECT_EQ(arm.controllers[1].kp, 30);
  EXPECT_FALSE(arm.controllers[1].max_output);
  EXPECT_EQ(arm.controllers[2].kind, ControllerKind::stable_pd);
}

TEST(SceneFiguresJson, ControllersAreLaidOutInTheState) {
  Scene s = parse_scene(full_scene().dump(), kFile);
  const CompiledFigure f = build_figure_model(s.figures[0], kFile, "figures[0]");
  ASSERT_EQ(f.controllers.size(), 3u);
  // The MRAC of 'upper' (revolute, after the free base's 7 q and 6 v), the universal's second
  // DOF, the prismatic joint.
  EXPECT_EQ(f.controllers[0].q_index, 7);
  EXPECT_EQ(f.controllers[0].v_index, 6);
  EXPECT_EQ(f.controllers[0].state_offset, 1);  // after the actuators' work
  EXPECT_EQ(f.controllers[1].v_index, f.model.segments[3].v_offset + 1);
  EXPECT_EQ(f.controllers[1].state_offset, -1);
  EXPECT_EQ(f.n_control, 1 + kMracStateSize);
}

TEST(SceneFiguresJson, ImpulsesAreInTimeOrderAndSitesResolved) {
  Scene s = parse_scene(full_scene().dump(), kFile);
  const CompiledFigure f = build_figure_model(s.figures[0], kFile, "figures[0]");
  ASSERT_EQ(f.impulses.size(), 2u);
  EXPECT_EQ(f.impulses[0].time, 0.25);  // listed second
  EXPECT_EQ(f.impulses[0].site.segment, 0);
  EXPECT_EQ(f.impulses[0].site.position, Vec3::Zero());  // no site: the segment's origin
  EXPECT_EQ(f.impulses[1].site.segment, 1);
  EXPECT_EQ(f.impulses[1].site.position, Vec3(0, 0, 0.4));  // 'upper''s site 'elbow'
  EXPECT_EQ(f.impulses[1].frame, ImpulseFrame::site);
  ASSERT_EQ(f.site_actuators.size(), 3u);  // the scene's two, then the motion capture's marker
  EXPECT_EQ(f.site_actuators[0].site.segment, 1);
  EXPECT_EQ(f.site_actuators[0].site.position, Vec3(0, 0, 0.4));
  EXPECT_EQ(f.site_actuators[1].site.segment, 0);
  EXPECT_EQ(f.site_actuators[2].site.segment, 1);
  EXPECT_EQ(f.site_actuators[2].def.stiffness, 250);
  EXPECT_EQ(f.site_actuators[2].def.x.size(), 121u);
  EXPECT_EQ(f.site_actuators[2].def.x[0].time, 0.25);  // the clip starts at 0.25 s
  // Without controllers, one entry of state keeps the impulses' and the strings' work.
  s.figures[0].controllers.clear();
  EXPECT_EQ(build_figure_model(s.figures[0], kFile, "figures[0]").n_control, 1);
  s.figures[0].impulses.clear();
  s.figures[0].site_actuators.clear();
  s.figures[0].mocap.reset();
  EXPECT_EQ(build_figure_model(s.figures[0], kFile, "figures[0]").n_control, 0);
}

TEST(SceneFiguresJson, SavedElsewhereTheClipIsNamedFromTheNewFolder) {
  Scene s = parse_scene(full_scene().dump(), "/data/scenes/walk.json");
  s.figures[0].mocap->file = "clips/walk.bvh";
  EXPECT_EQ(scene_saved_as(s, "/data/backup/walk.json").figures[0].mocap->file,
            "../scenes/clips/walk.bvh");
  EXPECT_EQ(scene_saved_as(s, "/data/scenes/copy.json").figures[0].mocap->file, "clips/walk.bvh");
  EXPECT_EQ(scene_saved_as(s, "/data/backup/walk.json").file, "/data/backup/walk.json");
  s.figures[0].mocap->file = "/clips/walk.bvh";  // absolute: as it is
  EXPECT_EQ(scene_saved_as(s, "/tmp/walk.json").figures[0].mocap->file, "/clips/walk.bvh");
}

TEST(SceneFiguresJson, ASceneMayHoldOnlyFigures) {
  const Scene s = parse_scene(R"({"figures": [{"segments": [{}]}]})", kFile);
  EXPECT_TRUE(s.bodies.empty());
  ASSERT_EQ(s.figures.size(), 1u);
  EXPECT_EQ(s.figures[0].name, "figure0");
  EXPECT_EQ(s.figures[0].segments[0].name, "segment0");
  expect_text_error(R"({"figures": []})", "bodies", "is required (or 'figures' or 'liquids')");
}

TEST(SceneFiguresJsonErrors, ErrorsNameTheirPath) {
  const json joint = {{"kind", "revolute"}, {"axis", {0, 1, 0}}};
  const std::vector<std::tuple<json, std::string, std::string>> cases = {
      {{{{"name", "a"}, {"parent", "b"}}, {{"name", "b"}, {"parent", "a"}}},
       "figures[0].segments[0].parent",
       "the parents form a cycle through 'a'"},
      {{{{"name", "a"}}, {{"name", "b"}, {"parent", "c"}}},
       "figures[0].segments[1].parent",
       "no segment is named 'c'"},
      {{{{"name", "a"}, {"parent", "b"}}, {{"name", "b"}}},
       "figures[0].segments[0].parent",
       "'b' must come before its child"},
      {{{{"name", "a"}}, {{"name", "a"}}}, "figures[0].segments[1].name", "names an earlier"},
      {{{{"density", 0}}}, "figures[0].segments[0].density", "must be > 0"},
      {{{{"mass", -1}}}, "figures[0].segments[0].mass", "must be >= 0"},
      {{{{"shape", {{"size", {0.1, 0, 0.1}}}}}},
       "figures[0].segments[0].shape.size[1]",
       "must be > 0"},
      {{{{"joint", {{"axis", {0, 0, 0}}}}}}, "figures[0].segments[0].joint.axis", "nonzero"},
      {{{{"joint", {{"kind", "hinge"}}}}}, "figures[0].segments[0].joint.kind", "must be one of"},
      {{{{"joint", {{"axis2", {0, 1, 0}}}}}},
       "figures[0].segments[0].joint.axis2",
       "not valid for a revolute joint"},
      {{{{"joint", {{"kind", "spherical"}, {"axis", {0, 1, 0}}}}}},
       "figures[0].segments[0].joint.axis",
       "not valid for a spherical joint"},
      {{{{"joint", {{"q0", {0.1, 0.2}}}}}}, "figures[0].segments[0].joint.q0", "needs 1 numbers"},
      {{{{"joint", {{"kind", "spherical"}, {"q0", {0, 0, 0, 0}}}}}},
       "figures[0].segments[0].joint.q0",
       "the quaternion must be nonzero"},
      {{{{"joint", {{"v0", {0, 0, 0, 0, 0, 0, 0, 0}}}}}},
       "figures[0].segments[0].joint.v0",
       "at most 7 numbers"},
      {{{{"joint", {{"kind", "universal"}, {"v0", {1}}}}}},
       "figures[0].segments[0].joint.v0",
       "needs 2 numbers"},
      {{{{"sites", {{{"name", ""}}}}}},
       "figures[0].segments[0].sites[0].name",
       "must not be empty"},
      {{{{"joint", joint}, {"color", {1, 2, 0}}}},
       "figures[0].segments[0].color[1]",
       "must be in [0, 1]"},
      {{{{"wing", 1}}}, "figures[0].segments[0].wing", "unknown key"},
      {{{{"joint", {{"stiffness", -1}}}}},
       "figures[0].segments[0].joint.stiffness",
       "must be >= 0"},
      {{{{"joint", {{"kind", "free"}, {"stiffness", 1}}}}},
       "figures[0].segments[0].joint.stiffness",
       "not valid for a free joint"},
      {{{{"joint", {{"stiffness", 1}, {"rest", {0.1, 0.2}}}}}},
       "figures[0].segments[0].joint.rest",
       "needs 1 numbers"},
      {{{{"joint", {{"kind", "spherical"}, {"rest", {0, 0, 0, 0}}}}}},
       "figures[0].segments[0].joint.rest",
       "the quaternion must be nonzero"},
      // Joint limits: both bounds, one per DOF, upper above lower, q0 between.
      {{{{"joint", {{"lower", {-1}}}}}}, "figures[0].segments[0].joint.upper", "needs 1 number"},
      {{{{"joint", {{"kind", "universal"}, {"lower", {-1}}, {"upper", {1}}}}}},
       "figures[0].segments[0].joint.lower",
       "needs 2 numbers"},
      {{{{"joint", {{"lower", {0.5}}, {"upper", {0.5}}}}}},
       "figures[0].segments[0].joint.upper",
       "greater than lower's"},
      {{{{"joint", {{"lower", {0.1}}, {"upper", {0.5}}, {"q0", {0.6}}}}}},
       "figures[0].segments[0].joint.q0",
       "outside [lower, upper]"},
      {{{{"joint", {{"lower", {0.1}}, {"upper", {0.5}}}}}},
       "figures[0].segments[0].joint.lower",
       "outside [lower, upper]"},
      {{{{"joint", {{"kind", "spherical"}, {"upper", {1}}}}}},
       "figures[0].segments[0].joint.upper",
       "not valid for a spherical joint"},
      {{{{"joint", {{"limit_restitution", 1.5}}}}},
       "figures[0].segments[0].joint.limit_restitution",
       "must be in [0, 1]"},
      // A swing cone: spherical joints only, below pi, q0 inside it.
      {{{{"joint", {{"swing_limit", 0.5}}}}},
       "figures[0].segments[0].joint.swing_limit",
       "not valid for a revolute joint"},
      {{{{"joint", {{"kind", "spherical"}, {"swing_limit", 3.5}}}}},
       "figures[0].segments[0].joint.swing_limit",
       "must be in (0, pi)"},
      {{{{"joint", {{"kind", "spherical"}, {"swing_limit", 0.5}, {"q0", {0.9, 0.5, 0, 0}}}}}},
       "figures[0].segments[0].joint.q0",
       "swing 1.0"},
      // A twist limit: spherical joints only, below pi, q0 inside it (a twist of
      // 2 atan2(0.5, 0.9) = 1.013 rad about the child's z).
      {{{{"joint", {{"twist_limit", 0.5}}}}},
       "figures[0].segments[0].joint.twist_limit",
       "not valid for a revolute joint"},
      {{{{"joint", {{"kind", "spherical"}, {"twist_limit", 3.5}}}}},
       "figures[0].segments[0].joint.twist_limit",
       "must be in (0, pi)"},
      {{{{"joint", {{"kind", "spherical"}, {"twist_limit", 0.5}, {"q0", {0.9, 0, 0, 0.5}}}}}},
       "figures[0].segments[0].joint.q0",
       "twist 1.0"},
  };
  for (const auto& [segments, path, message] : cases) {
    expect_error(json{{"figures", {{{"segments", segments}}}}}, path, message);
  }
  expect_error(json{{"figures", {{{"restitution", 1.5}, {"segments", {json::object()}}}}}},
               "figures[0].restitution", "must be in [0, 1]");
  expect_error(json{{"figures", {{{"contact_stiffness", 0}, {"segments", {json::object()}}}}}},
               "figures[0].contact_stiffness", "must be > 0");
  expect_error(json{{"figures", {{{"segments", json::array()}}}}}, "figures[0].segments",
               "at least one segment");
  expect_error(json{{"figures", {{{"friction", -0.1}, {"segments", {json::object()}}}}}},
               "figures[0].friction", "must be >= 0");
  // Pairs that never collide name two different segments of the figure.
  const json pair_of = {{{"name", "a"}}, {{"name", "b"}, {"parent", "a"}}};
  const std::vector<std::tuple<json, std::string, std::string>> pairs = {
      {{{"a", "a"}, {"b", "c"}}, "figures[0].non_colliding[0].b", "no segment is named 'c'"},
      {{{"a", "x"}, {"b", "b"}}, "figures[0].non_colliding[0].a", "no segment is named 'x'"},
      {{{"a", "b"}, {"b", "b"}}, "figures[0].non_colliding[0].b", "names the same segment"},
      {{{"a", "b"}}, "figures[0].non_colliding[0].b", "required"},
  };
  for (const auto& [pair, path, message] : pairs) {
    expect_error(json{{"figures", {{{"segments", pair_of}, {"non_colliding", {pair}}}}}}, path,
                 message);
  }
  // Controllers: each names a DOF of a single-axis joint or a ball's rotation-vector component
  // once, with gains in range.
  const json two = {{{"name", "a"}, {"joint", joint}},
                    {{"name", "b"}, {"parent", "a"}, {"joint", {{"kind", "spherical"}}}},
                    {{"name", "c"}, {"parent", "a"}, {"joint", {{"kind", "fixed"}}}}};
  const std::vector<std::tuple<json, std::string, std::string>> controllers = {
      {{{"joint", "d"}, {"keys", {{0, 1}}}}, "figures[0].controllers[0].joint", "names no segment"},
      {{{"joint", "c"}, {"keys", {{0, 1}}}},
       "figures[0].controllers[0].joint",
       "hangs on a fixed or free joint"},
      {{{"joint", "b"}, {"dof", 3}, {"keys", {{0, 1}}}},
       "figures[0].controllers[0].dof",
       "must be <= 2"},
      {{{"joint", "a"}, {"dof", 1}, {"keys", {{0, 1}}}},
       "figures[0].controllers[0].dof",
       "must be in [0, 0]"},
      {{{"joint", "a"}, {"keys", json::array()}},
       "figures[0].controllers[0].keys",
       "at least one key"},
      {{{"joint", "a"}, {"keys", {{1, 1}, {0, 2}}}},
       "figures[0].controllers[0].keys[1]",
       "must be greater than the previous"},
      {{{"joint", "a"}, {"keys", {{0, 1}}}, {"kp", 3}},
       "figures[0].controllers[0].kp",
       "not valid for a mrac controller"},
      {{{"joint", "a"}, {"kind", "pd"}, {"keys", {{0, 1}}}},
       "figures[0].controllers[0].kp",
       "needs kp or kd > 0"},
      {{{"joint", "a"}, {"keys", {{0, 1}}}, {"settling_time", 0}},
       "figures[0].controllers[0].settling_time",
       "must be > 0"},
      {{{"joint", "a"}, {"keys", {{0, 1}}}, {"max_output", -1}},
       "figures[0].controllers[0].max_output",
       "must be > 0"},
      {{{"keys", {{0, 1}}}}, "figures[0].controllers[0].joint", "required"},
  };
  for (const auto& [controller, path, message] : controllers) {
    expect_error(json{{"figures", {{{"segments", two}, {"controllers", {controller}}}}}}, path,
                 message);
  }
  // Site actuators and impulses name a segment of the figure and one of its sites.
  const json sited = {{{"name", "a"}, {"joint", joint}, {"sites", {{{"name", "tip"}}}}}};
  const json path_keys = {{0, 1}};
  const std::vector<std::tuple<json, std::string, std::string>> actuators = {
      {{{"segment", "b"}, {"x", path_keys}, {"y", path_keys}, {"z", path_keys}},
       "figures[0].site_actuators[0].segment",
       "names no segment"},
      {{{"segment", "a"}, {"site", "toe"}, {"x", path_keys}, {"y", path_keys}, {"z", path_keys}},
       "figures[0].site_actuators[0].site",
       "names no site of segment 'a'"},
      {{{"segment", "a"}, {"x", path_keys}, {"y", path_keys}},
       "figures[0].site_actuators[0].z",
       "required"},
      {{{"segment", "a"}, {"x", path_keys}, {"y", path_keys}, {"z", {{1, 0}, {1, 2}}}},
       "figures[0].site_actuators[0].z[1]",
       "must be greater than the previous"},
      {{{"segment", "a"}, {"x", path_keys}, {"y", path_keys}, {"z", path_keys}, {"stiffness", 0}},
       "figures[0].site_actuators[0].stiffness",
       "must be > 0"},
      {{{"segment", "a"}, {"x", path_keys}, {"y", path_keys}, {"z", path_keys}, {"max_force", 0}},
       "figures[0].site_actuators[0].max_force",
       "must be > 0"},
  };
  for (const auto& [actuator, path, message] : actuators) {
    expect_error(json{{"figures", {{{"segments", sited}, {"site_actuators", {actuator}}}}}}, path,
                 message);
  }
  const std::vector<std::tuple<json, std::string, std::string>> impulses = {
      {{{"time", 1}, {"segment", "c"}, {"impulse", {1, 0, 0}}},
       "figures[0].impulses[0].segment",
       "names no segment"},
      {{{"time", 1}, {"segment", "a"}, {"site", "toe"}, {"impulse", {1, 0, 0}}},
       "figures[0].impulses[0].site",
       "names no site"},
      {{{"time", -1}, {"segment", "a"}, {"impulse", {1, 0, 0}}},
       "figures[0].impulses[0].time",
       "must be >= 0"},
      {{{"segment", "a"}, {"impulse", {1, 0, 0}}}, "figures[0].impulses[0].time", "required"},
      {{{"time", 1}, {"segment", "a"}}, "figures[0].impulses[0].impulse", "non-zero"},
      {{{"time", 1}, {"segment", "a"}, {"impulse", {1, 0, 0}}, {"frame", "body"}},
       "figures[0].impulses[0].frame",
       "world"},
  };
  for (const auto& [impulse, path, message] : impulses) {
    expect_error(json{{"figures", {{{"segments", sited}, {"impulses", {impulse}}}}}}, path,
                 message);
  }
  const json twice = {{"joint", "a"}, {"keys", {{0, 1}}}};
  expect_error(json{{"figures", {{{"segments", two}, {"controllers", {twice, twice}}}}}},
               "figures[0].controllers[1].dof", "already has a controller");
  expect_error(json{{"figures",
                     {{{"name", "x"}, {"segments", {json::object()}}},
                      {{"name", "x"}, {"segments", {json::object()}}}}}},
               "figures[1].name", "names an earlier figure");
}

TEST(SceneFiguresJson, RoundTripIsExact) {
  const Scene a = parse_scene(full_scene().dump(), kFile);
  const Scene b = parse_scene(scene_to_json(a), kFile);
  expect_same_scene(a, b);
  EXPECT_EQ(scene_to_json(a), scene_to_json(b));
}

}  // namespace
}  // namespace pbm::scene_test
