// What a scene file can cost the reader (scenes/README.md, "Limits"): hostile files built in
// memory, each refused by its limit with the file, the JSON path and the reason. How fast they are
// refused is for benchmarks; these tests check that the limit is what refuses them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "scene/scene_format.h"
#include "scene_json_support.h"

namespace pbm::scene_test {
namespace {

const std::string kBody = R"({"material": {"mass": 1}})";

// `n` copies of `item`, comma-separated.
std::string repeated(const std::string& item, std::size_t n) {
  std::string text;
  text.reserve(n * (item.size() + 1));
  for (std::size_t i = 0; i < n; ++i) text += (i ? "," : "") + item;
  return text;
}

std::string scene_with(const std::string& key, const std::string& list) {
  return R"({"bodies": [)" + kBody + "], \"" + key + "\": [" + list + "]}";
}

TEST(SceneLimits, DeepNestingIsRefusedAtTheLevelPastTheLimit) {
  const int depth = 10000;
  const std::string text =
      R"({"bodies": )" + std::string(depth, '[') + std::string(depth, ']') + "}";
  // The root object is level 1 and "bodies" level 2: level 33, the first past the limit, is
  // "bodies" and 31 more.
  std::string path = "bodies";
  for (int level = 2; level <= kMaxNestingDepth; ++level) path += "[0]";
  expect_text_error(text, path, "nested deeper than 32 objects and arrays");
}

TEST(SceneLimits, ATextOrFileTooLargeIsRefusedBeforeParsing) {
  const std::string text = R"({"bodies": [)" + kBody + "]}" + std::string(kMaxSceneFileBytes, ' ');
  expect_text_error(text, "", "a scene file may have at most 33554432 bytes (32 MiB)");
  // A file is refused by its size, before it is read: a sparse file costs no disk.
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("pbm_huge_scene_" + std::to_string(::getpid()) + ".json");
  {
    std::ofstream out(path);
    out << R"({"bodies": [)" << kBody << "]}";
  }
  std::filesystem::resize_file(path, kMaxSceneFileBytes + 1);
  try {
    load_scene(path.string());
    ADD_FAILURE() << "expected pbm::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_EQ(e.path(), "");
    EXPECT_NE(std::string(e.what()).find("is 33554433 bytes"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(SceneLimits, AnArrayOfTenMillionIsRefusedAtTheValuePastTheLimit) {
  const std::string text = R"({"bodies": [)" + kBody +
                           R"(], "tracks": [{"target": "gravity[2]", "keys": [)" +
                           repeated("0", 10'000'000) + "]}]}";
  ASSERT_LT(text.size(), kMaxSceneFileBytes);
  // Before the keys: the root, "bodies", the body, its material, the mass (5 values), "tracks",
  // the track, its target and its keys (4 more).
  const std::size_t index = kMaxJsonValues - 9;
  expect_text_error(text, "tracks[0].keys[" + std::to_string(index) + "]",
                    "the file has more than 1000000 JSON values");
}

TEST(SceneLimits, HugeStringsAndKeysAreRefused) {
  expect_text_error(R"({"name": ")" + std::string(5000, 'x') + R"(", "bodies": [)" + kBody + "]}",
                    "name", "is a string of 5000 bytes; at most 4096 are allowed");
  expect_text_error(R"({"bodies": [{")" + std::string(5000, 'k') + R"(": 1}]})", "bodies[0]",
                    "has a key of 5000 bytes");
}

TEST(SceneLimits, TessellationIsBoundedPerFieldAndPerScene) {
  expect_text_error(
      R"({"bodies": [{"tessellation": {"rings": 1000000000}, "material": {"mass": 1}}]})",
      "bodies[0].tessellation.rings", "bodies[0].tessellation.rings: must be <= 4096");
  expect_text_error(
      R"({"bodies": [{"tessellation": {"segments": 5000}, "material": {"mass": 1}}]})",
      "bodies[0].tessellation.segments", "must be <= 4096");
  // 1001 x 1000 was refused by the old limit of 1,000,000 nodes a body; a body of a million nodes
  // cost 3.3 s and 1.4 GB to validate, so the whole scene now has at most 100,000.
  expect_text_error(
      R"({"bodies": [{"tessellation": {"rings": 1001, "segments": 1000}, "material": {"mass": 1}}]})",
      "bodies[0].tessellation", "rings * segments must be <= 99998 (got 1001000)");
  // The budget is the scene's: the second body gets what the first left.
  const std::string body =
      R"({"tessellation": {"rings": 300, "segments": 200}, "material": {"mass": 1}})";
  expect_text_error(R"({"bodies": [)" + body + "," + body + "]}", "bodies[1].tessellation",
                    "rings * segments must be <= 39996 (got 60000)");
  // A body without a tessellation has 2 + 16 * 16 nodes, and counts.
  const std::string plain = R"({"material": {"mass": 1}})";
  const std::string big =
      R"({"tessellation": {"rings": 400, "segments": 250}, "material": {"mass": 1}})";
  expect_text_error(R"({"bodies": [)" + plain + "," + big + "]}", "bodies[1].tessellation",
                    "rings * segments must be <= 99740 (got 100000)");
}

TEST(SceneLimits, ListLengthsAreRefusedBeforeTheirItemsAreRead) {
  expect_text_error(R"({"bodies": [)" + repeated(kBody, 1025) + "]}", "bodies",
                    "must have at most 1024 entries (got 1025)");
  expect_text_error(scene_with("obstacles", repeated("{}", 257)), "obstacles",
                    "must have at most 256 entries (got 257)");
  // The items are not read: these would each be an error.
  expect_text_error(scene_with("constraints", repeated("{}", 1025)), "constraints",
                    "must have at most 1024 entries (got 1025)");
  expect_text_error(scene_with("tracks", repeated("{}", 4097)), "tracks",
                    "must have at most 4096 entries (got 4097)");
  expect_text_error(scene_with("springs", repeated("{}", 4097)), "springs",
                    "must have at most 4096 entries (got 4097)");
  expect_text_error(scene_with("force_fields", repeated("{}", 257)), "force_fields",
                    "must have at most 256 entries (got 257)");
  expect_text_error(scene_with("tracks", R"({"target": "gravity[2]", "keys": [)" +
                                             repeated("[0, 0]", 100001) + "]}"),
                    "tracks[0].keys", "must have at most 100000 keys (got 100001)");
}

}  // namespace
}  // namespace pbm::scene_test
