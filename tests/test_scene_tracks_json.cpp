// The "tracks[i]" section of scene files and the table of track targets (scene/track_targets.h):
// every target's forms, stored in index form, the keys' order, and errors at the target's path.
#include <gtest/gtest.h>

#include <regex>

#include "scene/track_targets.h"
#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

TEST(SceneTracksJson, TargetsInIndexFormAndKeys) {
  const Scene s = parse_scene(full_scene().dump(), kFile);
  ASSERT_EQ(s.tracks.size(), 4u);
  EXPECT_EQ(s.tracks[0].target, "bodies[0].q_s0[6]");  // t1 is entry 6 of (2.11)
  EXPECT_EQ(s.tracks[0].interpolation, Interpolation::smooth);
  ASSERT_EQ(s.tracks[0].keys.size(), 2u);
  EXPECT_EQ(s.tracks[0].keys[1].time, 1);
  EXPECT_EQ(s.tracks[0].keys[1].value, 0.5);
  EXPECT_EQ(s.tracks[1].target, "gravity[2]");
  EXPECT_EQ(s.tracks[1].interpolation, Interpolation::linear);
  EXPECT_EQ(s.tracks[2].interpolation, Interpolation::step);
  EXPECT_EQ(s.tracks[3].target, "springs[1].stiffness");
}

TEST(SceneTracksJsonErrors, KeysMustIncreaseAndTargetsResolve) {
  json j = full_scene();
  j["tracks"][3]["keys"] = {{0, 1}, {0.5, 2}, {0.5, 3}};  // equal times are not increasing
  expect_error(j, "tracks[3].keys[2]", "must be greater than the previous key's time 0.5");
  j["tracks"][3]["keys"] = {{1, 1}, {0, 2}};
  expect_error(j, "tracks[3].keys[1]", "must be greater than");
  j["tracks"][3]["keys"] = json::array();
  expect_error(j, "tracks[3].keys", "at least one key");
  j["tracks"][3]["keys"] = {{1, 1, 1}};
  expect_error(j, "tracks[3].keys[0]", "[time, value] pair");
  j = full_scene();
  j["tracks"][0]["target"] = "bodies[2].q_s0[0]";  // only 2 bodies
  expect_error(j, "tracks[0].target", "body index 2 is out of range");
  j["tracks"][0]["target"] = "bodies[0].q_s0[11]";  // taper_bend has 11 parameters: 0..10
  expect_error(j, "tracks[0].target", "shape parameter index 11 is out of range");
  j["tracks"][0]["target"] = "bodies[0].q_s0[10]";
  EXPECT_NO_THROW(parse_scene(j.dump(), kFile));
  j["tracks"][0]["target"] = "bodies[0].q_s0.tau1";
  expect_error(j, "tracks[0].target", "unknown shape parameter 'tau1'");
  j["tracks"][0]["target"] = "gravity[3]";
  expect_error(j, "tracks[0].target", "out of range");
  j["tracks"][0]["target"] = "springs[2].stiffness";
  expect_error(j, "tracks[0].target", "spring index 2 is out of range");
  // An item's unknown target names the item and the targets it has.
  j["tracks"][0]["target"] = "bodies[0].position[0]";
  expect_error(j, "tracks[0].target",
               "unknown body track target 'bodies[0].position[0]' for body 'jello' (expected "
               "bodies[i].q_s0[k] or bodies[i].q_s0.<name>)");
  j["tracks"][0]["target"] = "lights[0].power";
  expect_error(j, "tracks[0].target", "unknown track target 'lights[0].power' (expected");
  j["tracks"][0]["target"] = "gravity[2]";  // tracks[1] already drives it
  expect_error(j, "tracks[1].target", "already driven by tracks[0]");
}

TEST(SceneTracks, TheTargetTableFormatsParsesAndMapsTheStudiosKeys) {
  for (const TrackTargetFormat& row : kTrackTargets) {
    const std::string text = format_track_target(row.target, 1, 2);
    const std::optional<TrackTargetRef> ref = parse_track_target(text);
    ASSERT_TRUE(ref.has_value()) << text;
    EXPECT_EQ(ref->target, row.target) << text;
    EXPECT_EQ(ref->object, row.owner.empty() || row.owner == "camera" ? 0 : 1) << text;
    EXPECT_EQ(ref->index, row.components == 0 ? 0 : 2) << text;
  }
  EXPECT_EQ(format_track_target(TrackTarget::spring_target, 3, 1), "springs[3].target[1]");
  // Only index forms are stored.
  EXPECT_FALSE(parse_track_target("bodies[0].q_s0.t1").has_value());
  EXPECT_FALSE(parse_track_target("obstacles[0].center[1]").has_value());
  EXPECT_FALSE(parse_track_target("gravity[2] ").has_value());
  EXPECT_FALSE(parse_track_target("gravity[1234567890]").has_value());

  const Scene s = parse_scene(full_scene().dump(), kFile);
  EXPECT_EQ(track_target_of_key(s, "/bodies/0/shape/rest/t1"), "bodies[0].q_s0[6]");
  EXPECT_EQ(track_target_of_key(s, "/bodies/1/shape/rest/t1"), "");  // a superquadric has no t1
  EXPECT_EQ(track_target_of_key(s, "/obstacles/1/center/2"), "obstacles[1].point[2]");
  EXPECT_EQ(track_target_of_key(s, "/obstacles/2/position/0"), "obstacles[2].point[0]");
  EXPECT_EQ(track_target_of_key(s, "/obstacles/0/point/1"), "obstacles[0].point[1]");
  EXPECT_EQ(track_target_of_key(s, "/obstacles/0/center/1"), "");  // a plane has no centre
  EXPECT_EQ(track_target_of_key(s, "/springs/1/stiffness"), "springs[1].stiffness");
  EXPECT_EQ(track_target_of_key(s, "/springs/0/target/2"), "springs[0].target[2]");
  EXPECT_EQ(track_target_of_key(s, "/camera/position/0"), "camera.position[0]");
  EXPECT_EQ(track_target_of_key(s, "/camera/fov"), "camera.fov");
  EXPECT_EQ(track_target_of_key(s, "/gravity/3"), "");
  EXPECT_EQ(track_target_of_key(s, "/bodies/0/material/w1"), "");
}

TEST(SceneTracks, TheSchemasPatternIsEveryAcceptedForm) {
  const std::regex pattern(track_target_pattern());
  for (const char* accepted :
       {"bodies[0].q_s0[6]", "bodies[12].q_s0.t1^2", "gravity[2]", "springs[1].target[0]",
        "springs[1].stiffness", "camera.position[2]", "camera.target[0]", "camera.fov",
        "obstacles[1].point[2]", "obstacles[1].center[2]", "obstacles[1].position[2]",
        "obstacles[0].rotation[1]"}) {
    EXPECT_TRUE(std::regex_match(accepted, pattern)) << accepted;
  }
  for (const char* refused : {"bodies[0].position[0]", "gravity", "camera.up[0]", "springs[x]"}) {
    EXPECT_FALSE(std::regex_match(refused, pattern)) << refused;
  }
}

TEST(SceneTracksJson, TargetsAreStoredInTheirOneIndexForm) {
  json j = full_scene();
  j["tracks"][1]["target"] = "gravity[02]";
  EXPECT_EQ(parse_scene(j.dump(), kFile).tracks[1].target, "gravity[2]");
  // So two spellings of one value are one target.
  j["tracks"][0]["target"] = "gravity[2]";
  expect_error(j, "tracks[1].target", "'gravity[2]' is already driven by tracks[0]");
}

}  // namespace
}  // namespace pbm::scene_test
