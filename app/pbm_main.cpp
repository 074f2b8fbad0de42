// pbm: the command line (validate, simulate, render, bench). A thin main over engine/
// (docs/architecture.md, "Folders").
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "bench_command.h"
#include "bench_realtime.h"
#include "bench_tradeoff.h"
#include "render_command.h"
#include "simulate_command.h"

int main(int argc, char** argv) {
  CLI::App app{"pbm: physics-based deformable models from the command line"};
  app.require_subcommand(1);
  std::string validate_scene;
  auto* validate =
      app.add_subcommand("validate", "check a scene file (exit 2 with the field path)");
  validate->add_option("scene", validate_scene, "scene JSON file")->required();
  bool validate_materials = false;
  validate->add_flag("--materials", validate_materials,
                     "print each body's mass, area, contact stiffness per area and step limit");

  pbm::SimulateOptions sim;
  auto* simulate = app.add_subcommand("simulate", "simulate a scene and write states/stats/meshes");
  simulate->add_option("scene", sim.scene, "scene JSON file")->required();
  simulate->add_option("--seconds", sim.seconds, "simulated time (default: the scene's duration)");
  simulate->add_option("--frames", sim.frames, "number of frames after frame 0");
  simulate->add_option("--dt", sim.dt, "largest substep [s] (default: the scene's)");
  simulate->add_option("--integrator", sim.integrator, "euler | rk4 | rk45 | implicit");
  simulate->add_option("--tolerance", sim.tolerance, "rk45 local error tolerance");
  simulate->add_option("--out", sim.states_out, "states as JSON lines (one per frame)");
  simulate->add_option("--stats", sim.stats_out, "per-frame statistics JSON");
  simulate->add_option("--mesh-dir", sim.mesh_dir, "write each frame's surfaces here");
  simulate->add_option("--mesh-format", sim.mesh_format, "obj | gltf | ply");
  simulate->add_option("--vdb-dir", sim.vdb_dir,
                       "write each frame's liquid level sets (.vdb) here");
  simulate->add_option("--surface-voxel", sim.surface_voxel,
                       "liquid level set voxel, a fraction of a cell (default: half the markers' "
                       "spacing)");
  simulate->add_option("--surface-smoothing", sim.surface_smoothing,
                       "mean-curvature passes over the liquid's level set (default 2)");

  pbm::RenderCommandOptions render;
  auto* render_cmd = app.add_subcommand("render", "simulate a scene and write PNG frames");
  render_cmd->add_option("scene", render.scene, "scene JSON file")->required();
  render_cmd->add_option("--frames", render.frames, "A:B, inclusive (default: every frame)");
  render_cmd->add_option("--seconds", render.seconds, "render frames 0 .. T * fps");
  render_cmd->add_option("--size", render.size, "WxH in pixels (default 1280x720)");
  render_cmd->add_option("--out", render.out, "folder for frame_NNNN.png (default out)");
  render_cmd->add_option("--video", render.video, "also encode this video with ffmpeg");
  render_cmd->add_option("--samples", render.samples, "MSAA samples, 1-16 (default 4)");
  render_cmd->add_flag("--overlays", render.overlays,
                       "draw the editor overlays: springs, constraints, the finite-element mesh");

  pbm::BenchOptions bench;
  auto* bench_cmd = app.add_subcommand(
      "bench",
      "benchmarks: deform (ours vs Bullet btSoftBody), render (ours vs a bare draw), "
      "constraints (dense vs sparse constraint solve), drag (a mouse-drag move vs recompiling), "
      "figures (articulated-body dynamics vs Bullet btMultiBody), "
      "tradeoff <scene> (error against cost over a sweep of the knobs: CSV and PNG), realtime "
      "[folder] (the real-time factor of every scene in it, default scenes)");
  bench_cmd
      ->add_option("what", bench.what,
                   "deform | render | constraints | drag | figures | tradeoff | realtime")
      ->required();
  bench_cmd->add_option("--steps", bench.steps, "steps timed per size (drag: frames of moves)");
  bench_cmd->add_option("--scene", bench.scene,
                        "scene of deform, render and drag (default scenes/jello-ball.json)");
  bench_cmd->add_option("--max-nodes", bench.max_nodes, "largest node count to run");
  bench_cmd->add_option("--max-constraints", bench.max_constraints,
                        "constraints: largest number of constraints to run");

  pbm::TradeoffCommandOptions tradeoff;
  bench_cmd->add_option("target", tradeoff.scene,
                        "tradeoff: the scene JSON file; realtime: the folder of scenes");
  bench_cmd->add_option("--knobs", tradeoff.knobs,
                        "tradeoff: knobs to sweep, of dt,integrator,tolerance,resolution,contact "
                        ", the figures' stiffness,restitution,gains,settling and the liquids' "
                        "liquid_resolution,cfl,advection,pressure_solver,relaxation,epsilon,"
                        "markers (default dt,integrator,resolution)");
  bench_cmd->add_option("--seconds", tradeoff.seconds,
                        "tradeoff, realtime: simulated time per run (2; realtime 10, at most the "
                        "scene's duration)");
  bench_cmd->add_option("--reference-tolerance", tradeoff.reference_tolerance,
                        "tradeoff: rk45 tolerance of the reference run (1e-7)");
  bench_cmd->add_option("--out", tradeoff.out, "tradeoff: folder of the CSV and PNG (out)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  spdlog::set_pattern("%^%l%$: %v");
  if (*validate) return pbm::run_validate(validate_scene, validate_materials);
  if (*simulate) return pbm::run_simulate(sim);
  if (*render_cmd) return pbm::run_render(render);
  if (*bench_cmd && bench.what == "tradeoff") {
    if (tradeoff.scene.empty()) tradeoff.scene = bench.scene;
    return pbm::run_bench_tradeoff(tradeoff);
  }
  if (*bench_cmd && bench.what == "realtime") {
    const bool seconds_given = bench_cmd->count("--seconds") > 0;
    return pbm::run_bench_realtime(tradeoff.scene.empty() ? "scenes" : tradeoff.scene,
                                   seconds_given ? tradeoff.seconds : 10.0);
  }
  if (*bench_cmd) return pbm::run_bench(bench);
  return 2;
}
