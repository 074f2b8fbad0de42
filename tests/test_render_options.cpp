// `pbm render` without a scene camera and with --samples: a scene with no camera is framed on its
// bodies at frame 0 (every body pixel inside the picture, the bodies filling a good part of it),
// exactly as the in-process renderer frames the snapshot's focus; --samples 4 anti-aliases the
// silhouettes that --samples 1 leaves hard, and changes nothing else of the picture.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "camera.h"
#include "cli_runner.h"
#include "osmesa_context.h"
#include "png_io.h"
#include "renderer.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("pbm_render_options_" + std::to_string(getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The jello-ball scene with its camera removed, written to `dir`.
fs::path scene_without_camera(const fs::path& dir) {
  Scene scene = load_scene(std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
  scene.camera.reset();
  std::erase_if(scene.tracks, [](const TrackDef& t) { return t.target.starts_with("camera"); });
  const fs::path file = dir / "no-camera.json";
  std::ofstream(file) << scene_to_json(scene);
  return file;
}

struct Box {
  int count = 0, x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
};

// Pixels that differ between two images of one size, and their bounding box.
Box differing_pixels(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                     int width, int height) {
  Box box;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t k = 3 * (static_cast<std::size_t>(y) * width + x);
      if (a[k] == b[k] && a[k + 1] == b[k + 1] && a[k + 2] == b[k + 2]) continue;
      ++box.count;
      box.x0 = std::min(box.x0, x);
      box.y0 = std::min(box.y0, y);
      box.x1 = std::max(box.x1, x);
      box.y1 = std::max(box.y1, y);
    }
  }
  return box;
}

TEST(RenderOptions, WithoutACameraTheBodiesOfFrameZeroAreFramed) {
  const fs::path dir = temp_dir("framing");
  const fs::path file = scene_without_camera(dir);
  constexpr int kWidth = 320, kHeight = 240;
  const test::CliResult r = test::run_pbm(
      "render " + file.string() + " --frames 0:0 --size 320x240 --out " + (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const RgbImage rendered = read_png((dir / "out" / "frame_0000.png").string());

  Simulation sim(load_scene(file.string()));
  draw::Snapshot snap = make_snapshot(sim);
  ASSERT_FALSE(snap.camera);
  const Camera camera = frame_focus(snap, static_cast<float>(kWidth) / kHeight);
  OsmesaContext context;
  Renderer renderer(context.functions());
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  std::vector<unsigned char> framed, shadowless, without_bodies;
  renderer.render(snap, camera, options);
  renderer.read_rgb(framed);
  EXPECT_EQ(rendered.pixels, framed);  // the command line frames as the renderer does
  // Where the bodies are: the pixels that change when they are removed (shadows off).
  options.shadows = false;
  renderer.render(snap, camera, options);
  renderer.read_rgb(shadowless);
  std::erase_if(snap.meshes, [](const draw::Mesh& m) { return m.pick >= 0; });
  renderer.render(snap, camera, options);
  renderer.read_rgb(without_bodies);
  const Box box = differing_pixels(shadowless, without_bodies, kWidth, kHeight);
  std::printf("framed without a camera: %d body pixels in x [%d, %d], y [%d, %d] of %dx%d\n",
              box.count, box.x0, box.x1, box.y0, box.y1, kWidth, kHeight);
  // All of the body is in the picture, none of it cut by the border...
  EXPECT_GT(box.x0, 0);
  EXPECT_GT(box.y0, 0);
  EXPECT_LT(box.x1, kWidth - 1);
  EXPECT_LT(box.y1, kHeight - 1);
  // ... and it is not a speck: it spans a fifth of the picture's height or more.
  EXPECT_GT(box.y1 - box.y0, kHeight / 5);
  EXPECT_GT(box.count, kWidth * kHeight / 50);
}

// Colours present in an image.
std::size_t distinct_colours(const std::vector<unsigned char>& rgb) {
  std::set<unsigned> colours;
  for (std::size_t k = 0; k + 2 < rgb.size(); k += 3) {
    colours.insert(unsigned{rgb[k]} << 16 | unsigned{rgb[k + 1]} << 8 | rgb[k + 2]);
  }
  return colours.size();
}

TEST(RenderOptions, SamplesAntiAliasTheSilhouettes) {
  const fs::path dir = temp_dir("samples");
  const std::string common = "render " + std::string(PBM_SOURCE_DIR) +
                             "/scenes/jello-ball.json --frames 0:0 --size 320x240 ";
  ASSERT_EQ(test::run_pbm(common + "--samples 1 --out " + (dir / "one").string()).code, 0);
  ASSERT_EQ(test::run_pbm(common + "--samples 4 --out " + (dir / "four").string()).code, 0);
  const RgbImage one = read_png((dir / "one" / "frame_0000.png").string());
  const RgbImage four = read_png((dir / "four" / "frame_0000.png").string());
  ASSERT_EQ(one.pixels.size(), four.pixels.size());
  const Box changed = differing_pixels(one.pixels, four.pixels, one.width, one.height);
  const std::size_t n = static_cast<std::size_t>(one.width) * one.height;
  std::printf("--samples 1 vs 4: %d of %zu pixels differ; %zu vs %zu distinct colours\n",
              changed.count, n, distinct_colours(one.pixels), distinct_colours(four.pixels));
  // Edges gain intermediate shades; the interiors (most of the picture) keep theirs.
  EXPECT_GT(changed.count, 100);
  EXPECT_LT(changed.count, static_cast<int>(n / 4));
  EXPECT_GT(distinct_colours(four.pixels), distinct_colours(one.pixels));
}

}  // namespace
}  // namespace pbm
