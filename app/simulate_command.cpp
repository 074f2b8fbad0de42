#include "simulate_command.h"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/error.h"
#include "frame_output.h"
#include "liquid/liquid_surface_mesh.h"
#include "mesh_export.h"
#include "progress_bar.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_json.h"
#include "sim/adaptive_step.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

namespace fs = std::filesystem;

// Opens an output file up front, so a bad path fails before any simulation (exit 2).
std::ofstream open_output(const std::string& path, const std::string& option) {
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw Error(path, "", "cannot write " + option + " file");
  return out;
}

std::vector<MeshData> body_meshes(const Model& model, const Workspace& ws) {
  std::vector<MeshData> meshes;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    MeshData mesh;
    mesh.name = model.bodies[b].name;
    mesh.positions = ws.bodies[b].x;
    mesh.triangles = model.bodies[b].tessellation.triangles;
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

// Every body's surface, then every liquid's (named after it), meshed from its level set; with a
// vdb_dir each level set is also written there.
std::vector<MeshData> surface_meshes(const Model& model, const State& state, const Workspace& ws,
                                     const SimulateOptions& o, long frame, bool meshes_wanted) {
  std::vector<MeshData> meshes;
  if (meshes_wanted) meshes = body_meshes(model, ws);
  const LiquidSurfaceOptions options{.voxel = o.surface_voxel, .smoothing = o.surface_smoothing};
  for (std::size_t l = 0; l < model.liquids.size(); ++l) {
    const LiquidModel& liquid = model.liquids[l];
    std::string vdb;
    if (!o.vdb_dir.empty()) {
      char name[64];
      std::snprintf(name, sizeof name, "_%05ld.vdb", frame);
      vdb = (fs::path(o.vdb_dir) / ("liquid_" + liquid.def.name + name)).string();
    }
    if (!meshes_wanted && vdb.empty()) continue;
    LiquidSurfaceMesh surface = liquid_surface_mesh(liquid, state.liquids[l], options, vdb);
    if (!meshes_wanted || surface.triangles.empty()) continue;  // no liquid left
    MeshData mesh;
    mesh.name = liquid.def.name;
    mesh.positions = std::move(surface.positions);
    mesh.triangles = std::move(surface.triangles);
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

void apply_overrides(const SimulateOptions& o, Scene& scene) {
  if (o.dt) {
    if (!(*o.dt > 0) || !std::isfinite(*o.dt)) throw Error("", "--dt", "must be > 0");
    scene.solver.dt = *o.dt;
  }
  if (o.tolerance) {
    if (!(*o.tolerance > 0)) throw Error("", "--tolerance", "must be > 0");
    scene.solver.tolerance = *o.tolerance;
  }
  if (o.integrator) {
    // The scene format's own names (scene/scene_enum_names.h), so the flag and the file agree.
    const auto named =
        std::find_if(kIntegratorKindNames.begin(), kIntegratorKindNames.end(),
                     [&](const auto& entry) { return entry.first == *o.integrator; });
    if (named == kIntegratorKindNames.end())
      throw Error("", "--integrator", "must be euler, rk4, rk45 or implicit");
    scene.solver.integrator = named->second;
  }
}

}  // namespace

int run_validate(const std::string& scene_path, bool materials) {
  try {
    const Scene scene = load_scene(scene_path);
    const Model model = build_model(scene);
    int nodes = 0;
    for (const BodyModel& b : model.bodies) nodes += b.n_nodes();
    int segments = 0;
    for (const CompiledFigure& figure : model.figures) segments += figure.model.size();
    spdlog::info(
        "{}: valid ({} bodies, {} nodes, {} figures, {} segments, {} obstacles, {} tracks)",
        scene_path, model.bodies.size(), nodes, model.figures.size(), segments,
        model.obstacles.size(), model.tracks.size());
    if (materials) {
      std::printf("%-16s %7s %12s %10s %12s %18s %18s %12s\n", "body", "nodes", "mass_kg",
                  "area_m2", "kg_per_m2", "contact_N_per_m3", "book_N_per_m3", "dt_euler_s");
      for (const BodyModel& b : model.bodies) {
        const Real in_use = b.contact_samples.empty() ? 0.0
                            : b.contact_from_material
                                ? scene.bodies[&b - model.bodies.data()].material.contact_stiffness
                                : b.book_contact_stiffness;
        std::printf("%-16s %7d %12.6g %10.6g %12.6g %18.6g %18.6g %12.4g\n", b.name.c_str(),
                    b.n_nodes(), b.mass, b.surface_area, b.mass / b.surface_area, in_use,
                    b.book_contact_stiffness, b.stability.dt_euler);
      }
    }
    return 0;
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
}

int run_simulate(const SimulateOptions& o) {
  std::unique_ptr<Simulation> sim;
  long n_frames = 0;
  std::ofstream states, stats;
  std::optional<MeshFormat> mesh_format;
  try {
    Scene scene = load_scene(o.scene);
    apply_overrides(o, scene);
    sim = std::make_unique<Simulation>(scene);
    const Model& model = sim->model;
    if (o.frames && o.seconds) throw Error("", "--frames", "give --frames or --seconds, not both");
    if (o.frames) {
      if (*o.frames < 0 || *o.frames > 10'000'000)
        throw Error("", "--frames", "must be in [0, 1e7]");
      n_frames = *o.frames;
    } else {
      const double seconds = o.seconds ? *o.seconds : model.solver.duration;
      if (!(seconds >= 0) || seconds > 1e6) throw Error("", "--seconds", "must be in [0, 1e6]");
      n_frames = std::lround(seconds * model.solver.fps);
    }
    if (!o.states_out.empty()) states = open_output(o.states_out, "--out");
    if (!o.stats_out.empty()) stats = open_output(o.stats_out, "--stats");
    if (!o.mesh_dir.empty()) {
      mesh_format = parse_mesh_format(o.mesh_format);
      if (!mesh_format) throw Error("", "--mesh-format", "must be obj, gltf or ply");
      std::error_code ec;
      fs::create_directories(o.mesh_dir, ec);
      if (ec || !fs::is_directory(o.mesh_dir)) {
        throw Error(o.mesh_dir, "", "cannot create --mesh-dir: " + ec.message());
      }
    }
    if (!o.vdb_dir.empty()) {
      if (model.liquids.empty())
        throw Error(o.scene, "liquids", "--vdb-dir: the scene has no liquid");
      std::error_code ec;
      fs::create_directories(o.vdb_dir, ec);
      if (ec || !fs::is_directory(o.vdb_dir)) {
        throw Error(o.vdb_dir, "", "cannot create --vdb-dir: " + ec.message());
      }
    }
    if (!(o.surface_voxel >= 0 && o.surface_voxel <= 4)) {
      throw Error("", "--surface-voxel", "must be in [0, 4] (a fraction of a cell; 0: default)");
    }
    if (o.surface_smoothing < 0 || o.surface_smoothing > 100) {
      throw Error("", "--surface-smoothing", "must be in [0, 100]");
    }
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  const Model& model = sim->model;
  if (!model.notes.empty()) spdlog::warn("{}: {}", o.scene, model.notes);
  const State& state = sim->state;
  bool first_stats = true;
  auto emit = [&](long frame, const FrameStats& fs_) {
    if (states) states << state_json_line(model, state, frame);
    if (stats) {
      stats << (first_stats ? "{\"scene\":" : ",\n");
      if (first_stats) stats << nlohmann::json(model.scene.name).dump() << ",\"frames\":[\n";
      stats << frame_stats_json(sim->world, fs_, frame);
      first_stats = false;
    }
    if (mesh_format || !o.vdb_dir.empty()) {
      const std::vector<MeshData> meshes =
          surface_meshes(model, state, sim->ws, o, frame, mesh_format.has_value());
      if (mesh_format && !meshes.empty()) {
        char name[64];
        std::snprintf(name, sizeof name, "frame_%05ld%s", frame,
                      mesh_format_extension(*mesh_format));
        write_mesh((fs::path(o.mesh_dir) / name).string(), *mesh_format, meshes);
      }
    }
  };
  int code = 0;
  // What the "auto" bodies saved (sim/level_of_detail.h), said at the end.
  long dormant_body_frames = 0, body_frames = 0, level_switches = 0, substeps = 0, rejected = 0;
  Real level_energy_jump = 0, level_position_jump = 0;
  ProgressBar bar("simulate", n_frames);
  try {
    emit(0, sim->stats);
    for (long f = 1; f <= n_frames; ++f) {
      const FrameResult r = advance_frame(*sim);
      if (!r.ok) {
        spdlog::error("{}: simulation failed at frame {}: {}", o.scene, f, r.message);
        code = 1;
        break;
      }
      emit(f, sim->stats);
      const LevelStats& levels = sim->stats.levels;
      dormant_body_frames += levels.dormant_bodies;
      level_switches += levels.switches;
      level_energy_jump = std::max(level_energy_jump, levels.energy_jump);
      level_position_jump = std::max(level_position_jump, levels.position_jump);
      substeps += sim->stats.substeps;
      rejected += sim->stats.rejected;
      for (const BodyModel& body : model.bodies) body_frames += body.auto_level ? 1 : 0;
      bar.update(f, "t=" + std::to_string(state.time).substr(0, 6) + "s");
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    code = 2;
  }
  bar.finish();
  if (body_frames > 0) {
    spdlog::info(
        "{}: auto levels: {} of {} body-frames without displacements, {} switches (largest "
        "switch off {:.3g} m, {:.3g} J), {} substeps",
        o.scene, dormant_body_frames, body_frames, level_switches, level_position_jump,
        level_energy_jump, substeps);
  }
  if (adaptive_steps(model)) {
    // What the adaptive step did (sim/adaptive_step.h): its accepted and rejected substeps.
    spdlog::info("{}: adaptive implicit step: {} substeps, {} rejected (adaptive_tolerance {:g} m)",
                 o.scene, substeps, rejected, model.solver.adaptive_tolerance);
  }
  if (stats) stats << (first_stats ? "{\"frames\":[" : "") << "\n]}\n";
  return code;
}

}  // namespace pbm
