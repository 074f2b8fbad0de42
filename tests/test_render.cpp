// The headless renderer as `pbm render` drives it: golden frames within 35 dB (regenerate with
// tools/regen-golden), a frame rendered alone equals the same frame of a sequence, the picture
// follows the physics, the editor's overlays appear only when asked (--overlays), and bad input
// stops before any work with exit 2 and nothing left behind.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "cli_runner.h"
#include "colour_bar.h"
#include "core/error.h"
#include "osmesa_context.h"
#include "png_io.h"
#include "renderer.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;
using Vec3f = Eigen::Vector3f;

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

Mask ball_mask(Renderer& renderer, draw::Snapshot snapshot, const Camera& camera,
               const RenderOptions& options) {
  std::vector<unsigned char> with, without;
  renderer.render(snapshot, camera, options);
  renderer.read_rgb(with);
  std::erase_if(snapshot.meshes, [](const draw::Mesh& m) { return m.pick >= 0; });  // the bodies
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
  const Camera camera = camera_from_view(*make_snapshot(sim).camera);
  RenderOptions options;
  options.width = 320;
  options.height = 240;
  options.shadows = false;
  const Mask at_0 = ball_mask(renderer, make_snapshot(sim), camera, options);
  for (int f = 0; f < 15; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  const Mask at_15 = ball_mask(renderer, make_snapshot(sim), camera, options);
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

const int kYellow[3] = {242, 217, 51};  // springs: (0.95, 0.85, 0.2)
const int kGreen[3] = {64, 230, 89};    // a held constraint: (0.25, 0.9, 0.35)
const int kRed[3] = {242, 51, 51};      // a constraint violated by 1 cm or more
const int kWire[3] = {20, 20, 26};      // the finite elements' edges

long count_colour(const std::vector<unsigned char>& rgb, const int (&c)[3]) {
  return count_colour(rgb, c[0], c[1], c[2]);
}

// The jello-ball with a spring pulling its top node and two point constraints on it: one held
// (a front node to a world anchor where the node is) and one from the top node to an anchor
// 1 m beside it.
Scene jello_with_overlays() {
  Scene scene = load_scene(scene_path("jello-ball"));
  Simulation plain(scene);
  const int top = plain.model.bodies[0].tessellation.north_pole;
  const draw::Snapshot first = make_snapshot(plain);
  const std::vector<Vec3f>& x = *first.meshes[0].positions;
  const Vec3 pole = x[top].cast<double>();
  // The node nearest the camera (the scene's looks along +y), away from the spring's.
  const int front = static_cast<int>(
      std::min_element(x.begin(), x.end(), [](auto& a, auto& b) { return a.y() < b.y(); }) -
      x.begin());
  ConstraintDef held;
  held.a.body = 0;
  held.a.node = front;
  held.b.world = x[front].cast<double>();
  ConstraintDef off;
  off.a.body = 0;
  off.a.node = top;
  off.b.world = pole + Vec3(-1.0, 0, 0.3);
  scene.constraints = {held, off};
  SpringDef spring;
  spring.body = 0;
  spring.node = top;
  spring.target = pole + Vec3(1.0, 0, 0.5);
  spring.stiffness = 10;
  scene.springs = {spring};
  return scene;
}

// jello_with_overlays at frame 0 from its scene camera, at 320x240: what the overlay tests draw.
struct JelloView {
  OsmesaContext context;
  Renderer renderer{context.functions()};
  Simulation sim{jello_with_overlays()};
  Camera camera;
  RenderOptions options;
  JelloView() {
    camera = camera_from_view(*snapshot().camera);
    options.width = 320;
    options.height = 240;
  }
  draw::Snapshot snapshot() {
    return make_snapshot(sim.world, sim.inputs, initial_state(sim.model), sim.ws);
  }
  std::vector<unsigned char> draw(const draw::Snapshot& snap) {
    renderer.render(snap, camera, options);
    std::vector<unsigned char> rgb;
    renderer.read_rgb(rgb);
    return rgb;
  }
};

// A clean picture by default: the springs, constraints and wireframe of the snapshot are its
// overlay layer, drawn only with RenderOptions::overlays.
TEST(Render, OverlaysAreDrawnOnlyWhenAsked) {
  JelloView view;
  const draw::Snapshot snap = view.snapshot();
  ASSERT_EQ(snap.lines.size(), 2u);  // the spring, the constraints
  const auto clean = view.draw(snap);
  view.options.overlays = true;
  const auto overlays = view.draw(snap);
  std::printf("clean: %ld yellow, %ld green, %ld red, %ld wire; overlays: %ld, %ld, %ld, %ld\n",
              count_colour(clean, kYellow), count_colour(clean, kGreen), count_colour(clean, kRed),
              count_colour(clean, kWire), count_colour(overlays, kYellow),
              count_colour(overlays, kGreen), count_colour(overlays, kRed),
              count_colour(overlays, kWire));
  EXPECT_EQ(count_colour(clean, kYellow), 0);
  EXPECT_EQ(count_colour(clean, kGreen), 0);
  EXPECT_EQ(count_colour(clean, kRed), 0);
  EXPECT_GT(count_colour(overlays, kYellow), 20);  // the spring's line and end points
  EXPECT_GE(count_colour(overlays, kGreen), 9);    // the held constraint's dot (5 pixels wide)
  EXPECT_GT(count_colour(overlays, kRed), 20);     // the broken one's line
  // The element edges darken part of the ball.
  EXPECT_GT(count_colour(overlays, kWire) - count_colour(clean, kWire), 100);
  // Without the overlay layer the picture is the scene's alone: the same as with no overlays
  // in the snapshot at all.
  draw::Snapshot bare = snap;
  bare.lines.clear();
  view.options.overlays = false;
  EXPECT_EQ(view.draw(bare), clean);
}

// Line colours are the snapshot's: a segment drawn green, then red, shows that colour (the
// engine maps |C| to it, tests/test_snapshot.cpp).
TEST(Render, LinesTakeTheirSegmentsColours) {
  JelloView view;
  view.options.overlays = true;
  draw::Snapshot snap = view.snapshot();
  snap.lines = {{.points = {Vec3f(-1.0f, 0.0f, 4.0f), Vec3f(1.0f, 0.0f, 5.0f)},
                 .colors = {Vec3f(0.25f, 0.9f, 0.35f)},
                 .end_points = true,
                 .end_point_size = 5}};
  const auto green = view.draw(snap);
  snap.lines[0].colors[0] = Vec3f(0.95f, 0.2f, 0.2f);
  const auto red = view.draw(snap);
  EXPECT_GT(count_colour(green, kGreen), 20);
  EXPECT_LT(count_colour(green, kRed), 5);
  EXPECT_GT(count_colour(red, kRed), 20);
  EXPECT_LT(count_colour(red, kGreen), 5);
  // A scene-layer line is drawn without --overlays; an overlay one is not.
  view.options.overlays = false;
  EXPECT_LT(count_colour(view.draw(snap), kRed), 5);
  snap.lines[0].layer = draw::Layer::scene;
  EXPECT_GT(count_colour(view.draw(snap), kRed), 20);
}

TEST(Render, OverlaysFlagOfTheCommandLine) {
  const fs::path clean = temp_dir("clean"), overlays = temp_dir("overlays");
  const std::string common =
      "render " + scene_path("interactive") + " --frames 3:3 --size 320x240 ";
  ASSERT_EQ(pbm_cli(common + "--out " + clean.string()).code, 0);
  ASSERT_EQ(pbm_cli(common + "--overlays --out " + overlays.string()).code, 0);
  const RgbImage a = read_png((clean / "frame_0003.png").string());
  const RgbImage b = read_png((overlays / "frame_0003.png").string());
  // The scene's spring (its mouse spring, sec. 6.4) is yellow only with --overlays.
  EXPECT_EQ(count_colour(a.pixels, kYellow), 0);
  EXPECT_GT(count_colour(b.pixels, kYellow), 10);
  // --wireframe is gone: --overlays draws the element edges.
  const Result old = pbm_cli(common + "--wireframe --out " + temp_dir("wire").string());
  EXPECT_EQ(old.code, 2) << old.output;
  EXPECT_NE(old.output.find("--wireframe"), std::string::npos) << old.output;
}

TEST(Render, CameraTracksNeedACamera) {
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

// `pbm render` draws each frame from the snapshot's camera, its tracks applied at the frame's
// time (what the studio's "View from scene camera" shows): frame 16 of a scene whose camera
// moves is the in-process render of that frame's snapshot from snapshot.camera, bit for bit,
// and not the picture from where the scene's camera starts.
TEST(Render, TheCommandLineDrawsFromTheSnapshotsCamera) {
  const fs::path dir = temp_dir("camera_track");
  fs::create_directories(dir);
  Scene scene = load_scene(scene_path("jello-ball"));
  scene.tracks.push_back({.target = "camera.position[0]", .keys = {{0.0, 1.0}, {1.0, -9.0}}});
  const fs::path file = dir / "moving-camera.json";
  std::ofstream(file) << scene_to_json(scene);
  const Result r = pbm_cli("render " + file.string() + " --frames 16:16 --size 160x120 --out " +
                           (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const RgbImage rendered = read_png((dir / "out" / "frame_0016.png").string());

  Simulation sim(load_scene(file.string()));
  const draw::Snapshot start = make_snapshot(sim);
  for (int f = 0; f < 16; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  const draw::Snapshot snap = make_snapshot(sim);
  ASSERT_TRUE(snap.camera);
  EXPECT_NEAR(snap.camera->position.x(), 1.0 - 10.0 * snap.time, 1e-5);
  EXPECT_LT(snap.camera->position.x(), -3.0f);
  OsmesaContext context;
  Renderer renderer(context.functions());
  RenderOptions options;
  options.width = 160;
  options.height = 120;
  std::vector<unsigned char> from_snapshot, from_start;
  renderer.render(snap, camera_from_view(*snap.camera), options);
  renderer.read_rgb(from_snapshot);
  renderer.render(snap, camera_from_view(*start.camera), options);
  renderer.read_rgb(from_start);
  EXPECT_EQ(rendered.pixels, from_snapshot);
  EXPECT_NE(rendered.pixels, from_start);
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

namespace pbm {
namespace {

// A translucent solid (Material::opacity < 1, a liquid's surface) shows what lies behind it,
// blended by its opacity; at opacity 1 it hides it.
// Options without shadows, width x height, and a camera 5 m down -y looking at the origin.
RenderOptions plain_options(int width, int height) {
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.shadows = false;
  return options;
}
Camera front_camera() {
  return camera_from_view(
      {.position = {0, -5, 0}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov = 30});
}

TEST(Render, ATranslucentSolidShowsWhatIsBehindIt) {
  OsmesaContext context;
  Renderer renderer(context.functions());
  const RenderOptions options = plain_options(64, 64);
  const Camera camera = front_camera();
  // opacity < 0: no front box.
  auto centre_pixel = [&](float opacity) {
    draw::Snapshot snap;
    snap.primitives.push_back(
        {.center = {0, 1, 0}, .half_size = {1, 0.1f, 1}, .material = {{0.9f, 0.05f, 0.05f}, 1.0f}});
    if (opacity >= 0) {
      snap.primitives.push_back({.center = {0, -1, 0},
                                 .half_size = {0.5f, 0.1f, 0.5f},
                                 .material = {{0.05f, 0.05f, 0.9f}, 1.0f, opacity}});
    }
    renderer.render(snap, camera, options);
    std::vector<unsigned char> rgb;
    renderer.read_rgb(rgb);
    const std::size_t k = 3 * (32 * 64 + 32);
    return std::array<int, 3>{rgb[k], rgb[k + 1], rgb[k + 2]};
  };
  const std::array<int, 3> back = centre_pixel(-1), opaque = centre_pixel(1.0f),
                           half = centre_pixel(0.5f);
  std::printf(
      "centre pixel: back alone (%d, %d, %d), opaque front (%d, %d, %d), "
      "half-transparent front (%d, %d, %d)\n",
      back[0], back[1], back[2], opaque[0], opaque[1], opaque[2], half[0], half[1], half[2]);
  EXPECT_GT(opaque[2], 3 * opaque[0]);  // the blue front box hides the red one
  EXPECT_GT(back[0], 3 * back[2]);
  // The ray crosses the front box's two faces (no culling), each blending half: a quarter of the
  // back box shows through, in display values.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(half[c], 0.25 * back[c] + 0.75 * opaque[c], 2.0) << c;
}

TEST(Render, AFieldSectionIsDrawnInItsFalseColoursWithAColourBar) {
  OsmesaContext context;
  Renderer renderer(context.functions());
  RenderOptions options = plain_options(800, 320);
  options.samples = 1;
  const Camera camera = front_camera();
  // A 2 x 2 m section facing the camera in 2 x 2 cells: low, high; NaN, mid.
  draw::Snapshot snap;
  snap.sections.push_back({.label = "pressure [Pa]",
                           .corner = {-1, 0, -1},
                           .u = {2, 0, 0},
                           .v = {0, 0, 2},
                           .nu = 2,
                           .nv = 2,
                           .values = {0, 100, std::numeric_limits<float>::quiet_NaN(), 50},
                           .low = 0,
                           .high = 100});
  renderer.render(snap, camera, options);
  std::vector<unsigned char> rgb;
  renderer.read_rgb(rgb);
  // Rows top to bottom: the bottom row of cells (j = 0) is in the lower half of the image.
  auto pixel = [&](int x, int y) {
    const std::size_t k = 3 * (static_cast<std::size_t>(y) * 800 + static_cast<std::size_t>(x));
    return Eigen::Vector3f(rgb[k] / 255.0f, rgb[k + 1] / 255.0f, rgb[k + 2] / 255.0f);
  };
  const Eigen::Vector3f low = pixel(370, 190), high = pixel(430, 190), mid = pixel(430, 130),
                        none = pixel(370, 130);
  std::printf("cells: low (%.3f %.3f %.3f), high (%.3f %.3f %.3f), mid (%.3f %.3f %.3f)\n", low.x(),
              low.y(), low.z(), high.x(), high.y(), high.z(), mid.x(), mid.y(), mid.z());
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(low[c], section_colour(0)[c], 0.01) << c;
    EXPECT_NEAR(high[c], section_colour(1)[c], 0.01) << c;
    EXPECT_NEAR(mid[c], section_colour(0.5f)[c], 0.01) << c;
  }
  // No liquid there: the sky, not a colour of the map.
  EXPECT_GT((none - section_colour(0)).norm(), 0.2);
  EXPECT_GT((none - section_colour(0.5f)).norm(), 0.2);
  // The colour bar at the top right: its gradient, yellow at the top, purple at the bottom, in a
  // dark panel. Its bar's left edge is 12 + 240 - 8 pixels from the right edge.
  const int bar_x = 800 - 12 - 240 + 8 + 9;
  const int bar_top = 12 + 8 + 20, bar_bottom = bar_top + 180;
  // Up the bar the colour of t = (bottom - y) / height, in steps of 1/32.
  for (const int y : {bar_top + 3, bar_top + 60, bar_top + 120, bar_bottom - 3}) {
    const float t = static_cast<float>(bar_bottom - y) / 180;
    const Eigen::Vector3f seen = pixel(bar_x, y);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], section_colour(t)[c], 0.03) << c << " " << y;
  }
  EXPECT_GT(pixel(bar_x, bar_top + 3).x(), 0.9f);      // yellow at the top
  EXPECT_LT(pixel(bar_x, bar_bottom - 3).y(), 0.05f);  // purple at the bottom
  EXPECT_NEAR(pixel(800 - 14, 14).x(), 0.12, 0.01);    // the panel's corner
  // The label's glyphs: white pixels in the panel's top line.
  int white = 0;
  for (int y = 12 + 8; y < 12 + 8 + 14; ++y) {
    for (int x = 800 - 12 - 240 + 8; x < 800 - 12 - 8; ++x) white += pixel(x, y).minCoeff() > 0.9f;
  }
  EXPECT_GT(white, 30);
}

}  // namespace
}  // namespace pbm
