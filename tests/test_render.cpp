// The headless renderer as `pbm render` drives it: golden frames within 35 dB (regenerate with
// tools/regen-golden), a frame rendered alone equals the same frame of a sequence, the picture
// follows the physics, and bad input stops before any work with exit 2 and nothing left behind.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_runner.h"
#include "core/error.h"
#include "osmesa_context.h"
#include "png_io.h"
#include "renderer.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"
#include "sim/tracks.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

using Result = test::CliResult;

Result pbm_cli(const std::string& args) {
  return test::run_pbm(args);
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("pbm_render_test_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  return dir;
}

std::string scene_path(const std::string& name) {
  return std::string(PBM_SOURCE_DIR) + "/scenes/" + name + ".json";
}

std::string golden(const std::string& name) {
  return std::string(PBM_SOURCE_DIR) + "/tests/golden/" + name + ".png";
}

class Golden : public testing::TestWithParam<const char*> {};

TEST_P(Golden, Frames0And30MatchTheReferencesWithin35dB) {
  const std::string scene = GetParam();
  const fs::path out = temp_dir(scene);
  const Result r = pbm_cli("render " + scene_path(scene) + " --frames 0:30 --size 320x240 --out " +
                           out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* frame : {"0000", "0030"}) {
    const RgbImage image = read_png((out / ("frame_" + std::string(frame) + ".png")).string());
    const RgbImage reference = read_png(golden(scene + "_" + frame));
    ASSERT_EQ(image.width, 320);
    ASSERT_EQ(image.height, 240);
    const double db = psnr(reference, image);
    EXPECT_GE(db, 35.0) << scene << " frame " << frame << " (tools/regen-golden rewrites them)";
  }
  // Frame 30 is not frame 0: the scene moved (a golden that could not fail would not).
  EXPECT_LT(psnr(read_png(golden(scene + "_0000")), read_png(golden(scene + "_0030"))), 30.0);
}

INSTANTIATE_TEST_SUITE_P(BookScenes, Golden, testing::Values("jello-ball", "morphing-shell"));

TEST(Render, AFrameAloneIsTheSameImageAsInASequence) {
  const fs::path alone = temp_dir("alone"), sequence = temp_dir("sequence");
  const std::string common = "render " + scene_path("jello-ball") + " --size 160x120 ";
  ASSERT_EQ(pbm_cli(common + "--frames 12:12 --out " + alone.string()).code, 0);
  ASSERT_EQ(pbm_cli(common + "--frames 9:12 --out " + sequence.string()).code, 0);
  EXPECT_FALSE(fs::exists(alone / "frame_0011.png"));
  const RgbImage a = read_png((alone / "frame_0012.png").string());
  const RgbImage b = read_png((sequence / "frame_0012.png").string());
  EXPECT_TRUE(std::isinf(psnr(a, b)));
}

// Pixels where the ball is: those that change when it is removed (shadows off, so only the
// ball itself counts). Returns their count and mean row.
struct Mask {
  long count = 0;
  double mean_row = 0;
};

Mask ball_mask(Renderer& renderer, Snapshot snapshot, const Camera& camera,
               const RenderOptions& options) {
  std::vector<unsigned char> with, without;
  renderer.render(snapshot, camera, options);
  renderer.read_rgb(with);
  snapshot.bodies.clear();
  renderer.render(snapshot, camera, options);
  renderer.read_rgb(without);
  Mask mask;
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      const std::size_t k = 3 * (static_cast<std::size_t>(y) * options.width + x);
      if (with[k] != without[k] || with[k + 1] != without[k + 1] || with[k + 2] != without[k + 2]) {
        ++mask.count;
        mask.mean_row += y;
      }
    }
  }
  if (mask.count > 0) mask.mean_row /= static_cast<double>(mask.count);
  return mask;
}

TEST(Render, TheBallsPixelsFollowItDownTheImage) {
  OsmesaContext context;
  Renderer renderer(context.functions());
  Simulation sim(load_scene(scene_path("jello-ball")));
  const Model& model = sim.model;
  const Inputs& inputs = sim.inputs;
  Workspace& ws = sim.ws;
  State& state = sim.state;
  const Camera camera = camera_from_scene(*model.scene.camera);
  RenderOptions options;
  options.width = 320;
  options.height = 240;
  options.shadows = false;
  const Mask at_0 = ball_mask(renderer, make_snapshot(model, state, inputs, ws), camera, options);
  for (int f = 0; f < 15; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  const Mask at_15 = ball_mask(renderer, make_snapshot(model, state, inputs, ws), camera, options);
  // The ball is in the picture (removing it changes hundreds of pixels)...
  EXPECT_GT(at_0.count, 500);
  EXPECT_GT(at_15.count, 500);
  // ... and it fell: 2 m in 0.47 s at this camera is tens of rows (image rows grow downward).
  EXPECT_GT(at_15.mean_row, at_0.mean_row + 10.0)
      << "rows " << at_0.mean_row << " -> " << at_15.mean_row;
}

// Pixels of a colour close to c (within 40 per channel).
long count_colour(const std::vector<unsigned char>& rgb, int r, int g, int b) {
  long n = 0;
  for (std::size_t k = 0; k + 2 < rgb.size(); k += 3) {
    n +=
        std::abs(rgb[k] - r) < 40 && std::abs(rgb[k + 1] - g) < 40 && std::abs(rgb[k + 2] - b) < 40;
  }
  return n;
}

// The jello-ball at frame 0 from its scene camera, at 320x240: what the overlay tests draw on.
struct JelloView {
  explicit JelloView(const Scene& scene = load_scene(scene_path("jello-ball"))) : sim(scene) {
    options.width = 320;
    options.height = 240;
  }
  OsmesaContext context;
  Renderer renderer{context.functions()};
  Simulation sim;
  const Camera camera = camera_from_scene(*sim.model.scene.camera);
  RenderOptions options;
  Snapshot snapshot() {
    return make_snapshot(sim.model, initial_state(sim.model), sim.inputs, sim.ws);
  }
  std::vector<unsigned char> draw(const Snapshot& snap) {
    renderer.render(snap, camera, options);
    std::vector<unsigned char> rgb;
    renderer.read_rgb(rgb);
    return rgb;
  }
};

TEST(Render, SpringsAndTheWireframeAreDrawn) {
  JelloView view;
  const auto plain = view.draw(view.snapshot());
  // A spring from the top node to a point beside the ball: a yellow line with end points.
  Scene sprung = load_scene(scene_path("jello-ball"));
  SpringDef spring;
  spring.node = view.sim.model.bodies[0].tessellation.north_pole;
  spring.target = Vec3(0.5, 0, 4.5);
  spring.stiffness = 10;
  sprung.springs.push_back(spring);
  JelloView with(sprung);
  const auto with_spring = with.draw(with.snapshot());
  EXPECT_EQ(count_colour(plain, 242, 217, 51), 0);
  EXPECT_GT(count_colour(with_spring, 242, 217, 51), 20);
  view.options.wireframe = true;
  const auto wire = view.draw(view.snapshot());
  // The element edges darken part of the ball.
  EXPECT_GT(count_colour(wire, 20, 20, 26) - count_colour(plain, 20, 20, 26), 100);
}

// Constraint lines: green while held, red when violated by a centimetre or more (the studio's
// view of ch. 7's assembly).
TEST(Render, ConstraintsAreColouredByViolation) {
  JelloView view;
  Snapshot snap = view.snapshot();
  auto draw = [&](float violation) {
    snap.constraints = {{Vec3f(-1.0f, 0.0f, 4.0f), Vec3f(1.0f, 0.0f, 5.0f), violation, 0}};
    return view.draw(snap);
  };
  const auto held = draw(0.0f), broken = draw(0.05f);
  const long green_held = count_colour(held, 64, 230, 89),
             red_held = count_colour(held, 242, 51, 51);
  const long green_broken = count_colour(broken, 64, 230, 89);
  const long red_broken = count_colour(broken, 242, 51, 51);
  std::printf("held: %ld green, %ld red; broken: %ld green, %ld red\n", green_held, red_held,
              green_broken, red_broken);
  EXPECT_GT(green_held, 20);
  EXPECT_GT(red_broken, 20);
  EXPECT_LT(red_held, 5);
  EXPECT_LT(green_broken, 5);
}

TEST(Render, CameraTracksMoveTheSceneCamera) {
  Scene scene = load_scene(scene_path("jello-ball"));
  TrackDef track;
  track.target = "camera.position[0]";
  track.keys = {{0.0, 1.0}, {10.0, -6.0}};
  scene.tracks.push_back(track);
  const Model model = build_model(scene);
  Drive drive;
  evaluate_drive(model, Inputs{}, 0.0, drive);
  EXPECT_FLOAT_EQ(camera_from_drive(drive).position.x(), 1.0f);
  EXPECT_EQ(camera_from_drive(drive).target, camera_from_scene(*scene.camera).target);
  evaluate_drive(model, Inputs{}, 5.0, drive);
  EXPECT_FLOAT_EQ(camera_from_drive(drive).position.x(), -2.5f);  // halfway, linear keys
  // A camera track needs a camera to move.
  const std::string text = R"({"bodies": [{"material": {"mass": 1}}],
    "tracks": [{"target": "camera.fov", "keys": [[0, 30], [1, 40]]}]})";
  try {
    parse_scene(text, "cam.json");
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tracks[0].target"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("need a 'camera'"), std::string::npos) << e.what();
  }
}

TEST(Render, BadOutputAndOptionsExit2BeforeAnyWork) {
  const std::string scene = scene_path("jello-ball");
  const fs::path fresh = temp_dir("never_created");
  struct Case {
    std::string args, needle;
  };
  const fs::path file = temp_dir("a_file");
  fs::create_directories(file.parent_path());
  FILE* f = std::fopen(file.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);
  const Case cases[] = {
      {"--size 0x0 --out " + fresh.string(), "--size"},
      {"--size 100000x720 --out " + fresh.string(), "--size"},
      {"--size big --out " + fresh.string(), "--size"},
      {"--frames 5:2 --out " + fresh.string(), "--frames"},
      {"--frames 0:99999 --out " + fresh.string(), "--frames"},
      {"--frames 0:1 --seconds 1 --out " + fresh.string(), "--frames"},
      {"--samples 0 --out " + fresh.string(), "--samples"},
      {"--frames 0:1 --out " + file.string(), "--out"},
      {"--frames 0:1 --out /proc/pbm-cannot-write", "--out"},
  };
  for (const Case& c : cases) {
    const Result r = pbm_cli("render " + scene + " " + c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(fresh)) << c.args << " left " << fresh;
  }
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    const Result video =
        pbm_cli("render " + scene + " --frames 0:1 --video x.mp4 --out " + fresh.string());
    EXPECT_EQ(video.code, 2) << video.output;
    EXPECT_NE(video.output.find("ffmpeg"), std::string::npos) << video.output;
    EXPECT_FALSE(fs::exists(fresh));
  }
  const Result missing = pbm_cli("render /no/such/scene.json --out " + fresh.string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("/no/such/scene.json"), std::string::npos);
  EXPECT_FALSE(fs::exists(fresh));
}

}  // namespace
}  // namespace pbm
