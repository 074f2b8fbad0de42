#include "render_command.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>

#include "camera.h"
#include "core/error.h"
#include "headless_renderer.h"
#include "png_io.h"
#include "progress_bar.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

constexpr int kMinSize = 16, kMaxSize = 8192;

struct Plan {
  long first = 0, last = 0;  // frames written, inclusive
  int width = 0, height = 0;
};

Plan plan_render(const RenderCommandOptions& o, const Model& model) {
  Plan plan;
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2) {
    throw Error("", "--size", "must be WxH, e.g. 1280x720 (got '" + o.size + "')");
  }
  if (w < kMinSize || h < kMinSize || w > kMaxSize || h > kMaxSize) {
    throw Error("", "--size",
                "each side must be in [" + std::to_string(kMinSize) + ", " +
                    std::to_string(kMaxSize) + "] pixels (got " + o.size + ")");
  }
  plan.width = w;
  plan.height = h;
  if (o.samples < 1 || o.samples > 16) throw Error("", "--samples", "must be in [1, 16]");
  const long scene_frames = std::lround(model.solver.duration * model.solver.fps);
  if (!o.frames.empty() && o.seconds) {
    throw Error("", "--frames", "give --frames or --seconds, not both");
  }
  if (!o.frames.empty()) {
    long a = 0, b = 0;
    if (std::sscanf(o.frames.c_str(), "%ld:%ld%c", &a, &b, &tail) != 2) {
      throw Error("", "--frames", "must be A:B (got '" + o.frames + "')");
    }
    if (a < 0 || b < a || b > scene_frames) {
      throw Error("", "--frames",
                  "A:B must satisfy 0 <= A <= B <= " + std::to_string(scene_frames) +
                      " (the scene's last frame: duration " +
                      std::to_string(model.solver.duration) + " s at " +
                      std::to_string(model.solver.fps) + " fps; got " + o.frames + ")");
    }
    plan.first = a;
    plan.last = b;
  } else {
    const double seconds = o.seconds ? *o.seconds : model.solver.duration;
    if (!(seconds >= 0) || seconds > model.solver.duration + 1e-9) {
      throw Error("", "--seconds",
                  "must be in [0, " + std::to_string(model.solver.duration) + "] (the scene's)");
    }
    plan.last = std::lround(seconds * model.solver.fps);
  }
  return plan;
}

// Creates the folder and proves it writable before any simulation, so bad output fails fast
// (exit 2) and leaves nothing behind.
void prepare_output(const std::string& out) {
  std::error_code ec;
  const bool existed = fs::exists(out, ec);
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    throw Error(out, "--out", "cannot create the output folder" + (ec ? ": " + ec.message() : ""));
  }
  const fs::path probe = fs::path(out) / ".pbm-write-test";
  std::ofstream test(probe);
  const bool writable = static_cast<bool>(test);
  test.close();
  fs::remove(probe, ec);
  if (!writable) {
    if (!existed) fs::remove(out, ec);
    throw Error(out, "--out", "the output folder is not writable");
  }
}

bool have_program(const std::string& name) {
  return std::system(("command -v " + name + " > /dev/null 2>&1").c_str()) == 0;
}

std::string frame_name(long frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04ld.png", frame);
  return name;
}

}  // namespace

int run_render(const RenderCommandOptions& o) {
  std::unique_ptr<Simulation> sim;
  Plan plan;
  try {
    const Scene scene = load_scene(o.scene);
    sim = std::make_unique<Simulation>(scene);
    plan = plan_render(o, sim->model);
    if (!o.video.empty() && !have_program("ffmpeg")) {
      throw Error("", "--video",
                  "needs the ffmpeg program, which is not installed (apt-get install ffmpeg); "
                  "the PNG frames alone need nothing");
    }
    prepare_output(o.out);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  const std::unique_ptr<HeadlessRenderer> headless = open_headless_renderer();
  if (!headless) return 1;
  Renderer* renderer = &headless->renderer;

  const Model& model = sim->model;
  RenderOptions options;
  options.width = plan.width;
  options.height = plan.height;
  options.samples = o.samples;
  options.overlays = o.overlays;
  // The scene's camera moves only with its tracks (a function of time: the snapshot's camera);
  // without one the framing of frame 0 holds for the whole render. Either way frame k is the
  // same image whether rendered alone or in a sequence.
  const Camera framed =
      frame_focus(make_snapshot(*sim), static_cast<float>(plan.width) / plan.height);
  RgbImage image;
  image.width = plan.width;
  image.height = plan.height;
  ProgressBar bar("render", plan.last - plan.first + 1);
  const auto start = std::chrono::steady_clock::now();
  int code = 0;
  try {
    for (long frame = 0; frame <= plan.last; ++frame) {
      if (frame > 0) {
        const FrameResult r = advance_frame(*sim);
        if (!r.ok) {
          spdlog::error("{}: simulation failed at frame {}: {}", o.scene, frame, r.message);
          code = 1;
          break;
        }
      }
      if (frame < plan.first) continue;
      const draw::Snapshot snapshot = make_snapshot(*sim);
      renderer->render(snapshot, snapshot.camera ? camera_from_view(*snapshot.camera) : framed,
                       options);
      renderer->read_rgb(image.pixels);
      write_png((fs::path(o.out) / frame_name(frame)).string(), image);
      const long done = frame - plan.first + 1;
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      char detail[64];
      std::snprintf(detail, sizeof detail, "frame %ld, %.1f fps", frame, done / elapsed);
      bar.update(done, detail);
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    code = 1;
  }
  bar.finish();
  if (code != 0) return code;
  spdlog::info("{} frames in {} ({}x{}, {} samples)", plan.last - plan.first + 1, o.out, plan.width,
               plan.height, renderer->samples());
  if (!o.video.empty()) {
    const std::string command =
        "ffmpeg -y -loglevel error -framerate " + std::to_string(model.solver.fps) +
        " -start_number " + std::to_string(plan.first) + " -i '" +
        (fs::path(o.out) / "frame_%04d.png").string() +
        "' -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + o.video + "'";
    if (std::system(command.c_str()) != 0) {
      spdlog::error("ffmpeg could not encode {}", o.video);
      return 1;
    }
    spdlog::info("video: {}", o.video);
  }
  return 0;
}

}  // namespace pbm
