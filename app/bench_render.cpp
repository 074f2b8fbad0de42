#include "bench_render.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "camera.h"
#include "core/error.h"
#include "headless_renderer.h"
#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int run_bench_render(const std::string& scene_path, int frames) {
  Scene base;
  try {
    base = load_scene(scene_path);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  const std::unique_ptr<HeadlessRenderer> headless = open_headless_renderer();
  if (!headless) return 1;
  Renderer* renderer = &headless->renderer;
  RenderOptions options;  // 1280x720, 4 samples, shadows
  std::printf("bench render: '%s' at %dx%d, %d frames each, median ms per frame\n",
              base.name.c_str(), options.width, options.height, frames);
  std::printf("%8s %10s %10s %10s %10s %10s %10s\n", "nodes", "triangles", "simulate", "upload",
              "draw", "bare draw", "draw/bare");
  for (int resolution : {45, 128}) {  // about 2k and 16k nodes
    Scene scene = base;
    BodyDef& body = scene.bodies[0];
    body.tessellation.rings = resolution;
    body.tessellation.segments = resolution;
    // The same ball at both resolutions (see bench deform).
    if (body.material.nodal_mass > 0) {
      body.material.mass = body.material.nodal_mass * 258;
      body.material.nodal_mass = 0;
    }
    Simulation sim(scene);
    const Model& model = sim.model;
    const draw::Snapshot first = make_snapshot(sim);
    const Camera camera =
        first.camera ? camera_from_view(*first.camera) : frame_focus(first, 16.0f / 9.0f);
    std::vector<double> simulate, upload, draw, bare;
    std::size_t triangles = 0;
    for (int f = 0; f < frames + 3; ++f) {  // 3 warm-up frames: shader JIT, buffer sizes
      auto t0 = Clock::now();
      if (!advance_frame(sim).ok) break;
      const draw::Snapshot snapshot = make_snapshot(sim);
      const double sim_ms = ms_since(t0);
      triangles = snapshot.meshes[0].topology->triangles.size();  // body 0's
      renderer->render(snapshot, camera, options);
      const RenderTimes times = renderer->times();
      renderer->render_bare(snapshot, camera, options);
      if (f < 3) continue;
      simulate.push_back(sim_ms);
      upload.push_back(1e3 * times.upload);
      draw.push_back(1e3 * times.draw);
      bare.push_back(1e3 * renderer->times().draw);
    }
    std::printf("%8d %10zu %10.2f %10.2f %10.2f %10.2f %10.2f\n", model.bodies[0].n_nodes(),
                triangles, median(simulate), median(upload), median(draw), median(bare),
                median(draw) / median(bare));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace pbm
