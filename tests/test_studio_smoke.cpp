// The studio's scripted smoke mode, the real window under Xvfb (PLATFORM.md: Qt's offscreen
// platform has no OpenGL): a drag from the window centre pulls the `interactive` scene's body
// toward the drag, and the screenshot shows the viewport and the panels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "png_io.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

struct SmokeResult {
  int code = -1;
  std::string output;
  nlohmann::json report;
};

SmokeResult smoke(const std::string& name, const std::string& extra,
                  const std::string& scene = std::string(PBM_SOURCE_DIR) +
                                             "/scenes/interactive.json") {
  const fs::path dir = fs::path(PBM_BINARY_DIR) / "tests" / "smoke";
  fs::create_directories(dir);
  const std::string png = (dir / (name + ".png")).string();
  const std::string report = (dir / (name + ".json")).string();
  fs::remove(png);
  fs::remove(report);
  const std::string cmd = "xvfb-run -a -s '-screen 0 1600x1000x24' " + std::string(PBM_BINARY_DIR) +
                          "/app/pbm-studio --smoke " + scene + " --frames 24 --screenshot " + png +
                          " --report " + report + " " + extra;
  const test::CliResult run = test::run_command(cmd);
  SmokeResult r;
  r.code = run.code;
  r.output = run.output;
  if (fs::exists(report)) r.report = nlohmann::json::parse(std::ifstream(report));
  return r;
}

TEST(StudioSmoke, DragPullsTheBodyAndTheScreenshotShowsPanels) {
  const SmokeResult still = smoke("still", "");
  ASSERT_EQ(still.code, 0) << still.output;
  const SmokeResult dragged = smoke("dragged", "--drag 640,400:1000,400");
  ASSERT_EQ(dragged.code, 0) << dragged.output;
  ASSERT_EQ(still.report["frame"], 24);
  ASSERT_EQ(dragged.report["frame"], 24);
  // The camera looks along +y with z up, so a drag to the right of the screen is +x.
  const double x_still = still.report["bodies"][0]["center"][0];
  const double x_dragged = dragged.report["bodies"][0]["center"][0];
  std::printf("body centre x: %.4f without the drag, %.4f with it\n", x_still, x_dragged);
  EXPECT_GT(x_dragged - x_still, 0.05);

  const RgbImage image = read_png((fs::path(PBM_BINARY_DIR) / "tests/smoke/dragged.png").string());
  ASSERT_EQ(image.width, 1280);
  ASSERT_EQ(image.height, 800);
  auto pixel = [&](int x, int y) {
    const unsigned char* p = &image.pixels[3 * (static_cast<std::size_t>(y) * image.width + x)];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  // An empty part of the inspector (ImGui's dark theme: a neutral dark grey) at the left, the
  // sky of the viewport (a light blue-grey) at the top middle.
  const auto panel = pixel(170, 600), sky = pixel(800, 60);
  std::printf("panel pixel (%d, %d, %d), sky pixel (%d, %d, %d)\n", panel[0], panel[1], panel[2],
              sky[0], sky[1], sky[2]);
  EXPECT_LT(panel[0] + panel[1] + panel[2], 300) << "no dark panel at the left";
  EXPECT_LT(std::max({panel[0], panel[1], panel[2]}) - std::min({panel[0], panel[1], panel[2]}),
            12);
  EXPECT_GT(sky[0] + sky[1] + sky[2], 400) << "no lit viewport";
  EXPECT_GT(sky[2], sky[0]) << "the sky is bluish";
}

// The same drag on a figure's segment: pendulum-chain.json's chain lies nearly level toward -x
// at frame 6, its second link under window pixel (556, 170). Pulled up from there, the chain
// hangs differently at frame 24 from the undragged run, and the scene has gained the drag's site
// actuator.
TEST(StudioSmoke, DragOnAFiguresSegmentPullsTheFigure) {
  const std::string scene = std::string(PBM_SOURCE_DIR) + "/scenes/pendulum-chain.json";
  const SmokeResult still = smoke("chain-still", "", scene);
  ASSERT_EQ(still.code, 0) << still.output;
  const SmokeResult dragged = smoke("chain-dragged", "--drag 556,170:556,40", scene);
  ASSERT_EQ(dragged.code, 0) << dragged.output;
  ASSERT_EQ(still.report["figures"][0]["site_actuators"], 0);
  ASSERT_EQ(dragged.report["figures"][0]["site_actuators"], 1);
  const auto& a = still.report["figures"][0]["segments"][1];
  const auto& b = dragged.report["figures"][0]["segments"][1];
  const double moved = std::hypot(double(a[0]) - double(b[0]), double(a[2]) - double(b[2]));
  std::printf("second link's centre moved %.4f m by the drag\n", moved);
  EXPECT_GT(moved, 0.05);
}

// Pixels within 20 per channel of the spring colour (0.95, 0.85, 0.2): closer than the yellow
// fringes of ImGui's antialiased arrows.
long spring_yellow(const RgbImage& image) {
  long n = 0;
  for (std::size_t k = 0; k + 2 < image.pixels.size(); k += 3) {
    n += std::abs(image.pixels[k] - 242) < 20 && std::abs(image.pixels[k + 1] - 217) < 20 &&
         std::abs(image.pixels[k + 2] - 51) < 20;
  }
  return n;
}

// The viewport draws the overlay layer only when View > Overlays is on, as `pbm render` does
// with --overlays: interactive.json's spring is active at frame 24.
TEST(StudioSmoke, OverlaysAreDrawnOnlyFromTheViewMenu) {
  const SmokeResult clean = smoke("clean", "");
  ASSERT_EQ(clean.code, 0) << clean.output;
  const SmokeResult overlays = smoke("overlays", "--overlays");
  ASSERT_EQ(overlays.code, 0) << overlays.output;
  const fs::path dir = fs::path(PBM_BINARY_DIR) / "tests/smoke";
  const long without = spring_yellow(read_png((dir / "clean.png").string()));
  const long with = spring_yellow(read_png((dir / "overlays.png").string()));
  std::printf("spring-yellow pixels: %ld without overlays, %ld with\n", without, with);
  EXPECT_EQ(without, 0);
  EXPECT_GT(with, 20);
}

// "View from scene camera" (on at start) plays the scene's camera tracks: the viewport's camera
// at frame 24 is where the track puts the camera at that frame's time.
TEST(StudioSmoke, TheSceneCameraPlaysItsTrack) {
  const fs::path dir = fs::path(PBM_BINARY_DIR) / "tests/smoke";
  fs::create_directories(dir);
  nlohmann::json scene = nlohmann::json::parse(
      std::ifstream(std::string(PBM_SOURCE_DIR) + "/scenes/interactive.json"));
  scene["tracks"].push_back({{"target", "camera.position[0]"}, {"keys", {{0, 0}, {2, -20}}}});
  const fs::path file = dir / "camera-track-scene.json";  // not the report
  std::ofstream(file) << scene.dump(2);
  const SmokeResult r = smoke("camera-track", "", file.string());
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_EQ(r.report["frame"], 24);
  const double t = r.report["time"];
  EXPECT_NEAR(t, 0.8, 1e-9);
  EXPECT_NEAR(r.report["camera"][0].get<double>(), -10.0 * t, 1e-4);
  EXPECT_NEAR(r.report["camera"][1].get<double>(), -30.0, 1e-4);  // the scene's, untracked
}

// The speed-vs-accuracy panel in the real window: Measure runs the sweep beside the playing
// engine thread, and Apply on the front's most accurate point sets the scene's solver, keeping
// the model the sweep measured (shape_inertia_time at the scene's dt).
TEST(StudioSmoke, TheTradePanelMeasuresTheSceneAndAppliesAPointOfItsFront) {
  const SmokeResult r =
      smoke("tradeoff", "--tradeoff 0.5", std::string(PBM_SOURCE_DIR) + "/scenes/jello-ball.json");
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json& t = r.report["tradeoff"];
  std::printf("trade panel: %s\n", t.dump().c_str());
  EXPECT_EQ(t["points"], 9);  // dt 0.031, 0.0155, 0.00775 (2x is past the frame) x 3 integrators
  EXPECT_EQ(t["ok"], 9);
  EXPECT_GE(t["front"].get<int>(), 2);
  EXPECT_LT(t["solver_dt"].get<double>(), 0.031);  // the most accurate point is not the scene's
  EXPECT_DOUBLE_EQ(t["shape_inertia_time"].get<double>(), 0.031);
}

// A one-link arm under a stable PD servo whose target is 0.1 rad (its one key).
std::string lever_arm_scene() {
  const fs::path file = fs::path(PBM_BINARY_DIR) / "tests/smoke/lever-arm.json";
  fs::create_directories(file.parent_path());
  std::ofstream(file) << R"({"name": "lever-arm", "solver": {"dt": 0.001, "fps": 30},
      "figures": [{"name": "arm", "segments": [{"name": "arm", "joint": {"axis": [0, 1, 0]},
        "shape": {"kind": "capsule", "size": [0.04, 0.04, 0.2], "center": [0, 0, -0.25]}}],
      "controllers": [{"kind": "stable_pd", "joint": "arm", "kp": 200, "kd": 20,
                       "keys": [[0, 0.1]]}]}]})";
  return file.string();
}

// The keyboard lever of the Controllers panel, held as a user holds Page Up: the jog starts from
// the controller's desired position (0.1 rad, its one key), records [t0, 0.1, speed] and, at the
// release, [t1, 0.1 + speed (t1 - t0), 0], and the hold is one undo step. (This test found Page
// Up jogging down: ImGui 1.86's IsKeyDown takes a key index, not an ImGuiKey.)
TEST(StudioSmoke, PageUpJogsTheKeyboardLeversControllerAndRecordsIt) {
  const SmokeResult r = smoke("lever", "--keys 6:18", lever_arm_scene());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json& live = r.report["figures"][0]["live"][0];
  std::printf("keyboard lever: live keys %s, undo '%s'\n", live.dump().c_str(),
              r.report["undo"].get<std::string>().c_str());
  ASSERT_EQ(live.size(), 2u);
  const double speed = 0.2;  // the panel's default keyboard lever speed [/s]
  const double t0 = live[0][0], t1 = live[1][0];
  // Pressed once frame 6 is shown and released once frame 18 is: each end lands at its frame or
  // the next (the panel reads the key at its next draw and the engine thread takes the post at
  // its own pace, so on a loaded machine the two ends need not lag alike), on a frame's time.
  EXPECT_GE(t0, 6.0 / 30 - 1e-9);
  EXPECT_LE(t0, 7.0 / 30 + 1e-9);
  EXPECT_GE(t1, 18.0 / 30 - 1e-9);
  EXPECT_LE(t1, 19.0 / 30 + 1e-9);
  for (const double t : {t0, t1}) EXPECT_NEAR(t * 30, std::round(t * 30), 1e-9);
  EXPECT_NEAR(live[0][1].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(live[0][2].get<double>(), speed, 1e-12);
  EXPECT_NEAR(live[1][1].get<double>(), 0.1 + speed * (t1 - t0), 1e-9);
  EXPECT_EQ(live[1][2].get<double>(), 0.0);
  EXPECT_EQ(r.report["undo"], "lever");
}

// The jog lever of the Controllers panel dragged with the mouse as a user drags it (pressed at
// frame 6, pushed 4 px right a frame, let go at frame 18): each change of its speed is a live key
// starting where the last one's motion got to, from the desired 0.1 rad; the speed only grows
// while it is pushed (0.002 /s a pixel, the panel's scale for a target under 1), is back to 0 at
// the end, and the hold is one undo step.
TEST(StudioSmoke, DraggingTheJogLeverMovesTheTargetAtItsSpeedAndRecordsIt) {
  const SmokeResult r = smoke("jog", "--jog 6:18", lever_arm_scene());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json& live = r.report["figures"][0]["live"][0];
  std::printf("jog lever: live keys %s, undo '%s'\n", live.dump().c_str(),
              r.report["undo"].get<std::string>().c_str());
  ASSERT_GE(live.size(), 3u);
  EXPECT_NEAR(live[0][1].get<double>(), 0.1, 1e-12);
  EXPECT_GT(live[0][2].get<double>(), 0.0);
  const double most = 0.002 * 4 * 11;  // 11 pushes of 4 px
  for (std::size_t k = 0; k + 1 < live.size(); ++k) {
    const double t = live[k][0], value = live[k][1], rate = live[k][2];
    const double t_next = live[k + 1][0], value_next = live[k + 1][1];
    EXPECT_GT(t_next, t);
    EXPECT_NEAR(value_next, value + rate * (t_next - t), 1e-9) << "key " << k;
    if (k + 2 < live.size()) {
      EXPECT_GE(live[k + 1][2].get<double>(), rate) << "key " << k;
    }
    EXPECT_LE(rate, most + 1e-12);
  }
  EXPECT_EQ(live.back()[2].get<double>(), 0.0);
  EXPECT_GT(live.back()[1].get<double>(), 0.1);
  EXPECT_EQ(r.report["undo"], "jog");
}

}  // namespace
}  // namespace pbm
