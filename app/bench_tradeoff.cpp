#include "bench_tradeoff.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "plot_png.h"
#include "progress_bar.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_json.h"
#include "sim/tradeoff.h"

namespace pbm {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

void write_csv(const std::string& path, const TradeoffReport& report) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << "integrator,dt_s,tolerance,resolution,contact,stiffness,restitution,gains,settling,"
         "current,ok,wall_s,substeps,evaluations,retries,"
         "centre_error_m,joint_error_rad,shape_error,node_rms_m,constraint_violation_m,"
         "energy_error,depth_m,physics_centre_m,physics_joint_rad,pareto,"
         "liquid_resolution,cfl,advection,pressure_solver,relaxation,epsilon,markers_per_axis,"
         "liquid_volume,liquid_centre_m,liquid_front_m,liquid_height_m,"
         "message\n";
  char line[960];
  for (const TradeoffPoint& p : report.points) {
    const TradeoffSetting& s = p.setting;
    const std::string restitution = s.restitution ? std::to_string(*s.restitution) : "scene";
    std::snprintf(line, sizeof line,
                  "%s,%.9g,%.3g,%g,%s,%g,%s,%g,%g,%d,%d,%.6g,%ld,%ld,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,"
                  "%.6g,%.6g,%.6g,%.6g,%d,",
                  name_of(kIntegratorKindNames, s.integrator), s.dt, s.tolerance, s.resolution,
                  s.contact ? name_of(kContactQuadratureNames, *s.contact) : "scene", s.stiffness,
                  restitution.c_str(), s.gains, s.settling, s.current ? 1 : 0, p.ok ? 1 : 0,
                  p.wall_seconds, p.substeps, p.evaluations, p.retries, p.centre_error,
                  p.joint_error, p.shape_error, p.node_rms, p.constraint_violation, p.energy_error,
                  p.depth, p.physics_centre, p.physics_joint, p.pareto ? 1 : 0);
    out << line;
    std::string message = p.message;
    for (char& c : message) {
      if (c == ',' || c == '\n' || c == '"') c = ' ';
    }
    std::snprintf(line, sizeof line, "%g,%g,%s,%s,%g,%g,%d,%.6g,%.6g,%.6g,%.6g,",
                  s.liquid_resolution, s.cfl,
                  s.advection ? name_of(kLiquidAdvectionNames, *s.advection) : "scene",
                  s.pressure_solver ? name_of(kPressureSolverNames, *s.pressure_solver) : "scene",
                  s.relaxation, s.epsilon, s.markers_per_axis, p.liquid_volume, p.liquid_centre,
                  p.liquid_front, p.liquid_height);
    out << line << message << "\n";
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

LogLogPlot make_plot(const Scene& scene, const TradeoffReport& report, double seconds) {
  LogLogPlot plot;
  char title[256];
  std::snprintf(title, sizeof title,
                "%s: error against wall time, %zu runs of %g s; reference %s (%.2f s)",
                scene.name.c_str(), report.points.size(), seconds, report.reference.label().c_str(),
                report.reference_wall_seconds);
  plot.title = title;
  plot.x_label = "wall time of the run [s]";
  plot.y_label = "largest centre error against the reference [m] (bodies' or liquids')";
  const std::map<IntegratorKind, std::array<unsigned char, 3>> colors{
      {IntegratorKind::euler, {40, 100, 200}},
      {IntegratorKind::rk4, {40, 160, 70}},
      {IntegratorKind::rk45, {140, 60, 170}},
      {IntegratorKind::implicit, {230, 140, 20}}};
  std::map<IntegratorKind, PlotSeries> by_kind;
  std::vector<std::array<double, 2>> front;
  for (const TradeoffPoint& p : report.points) {
    if (!p.ok) continue;
    // A run that matches the reference to the last bit still needs a place on a log axis.
    const std::array<double, 2> xy{std::max(p.wall_seconds, 1e-6),
                                   std::max(p.accuracy_error(), 1e-12)};
    PlotSeries& s = by_kind[p.setting.integrator];
    s.name = name_of(kIntegratorKindNames, p.setting.integrator);
    s.color = colors.at(p.setting.integrator);
    s.points.push_back(xy);
    s.radii.push_back(3.0 + 2.0 * std::sqrt(p.setting.resolution));
    if (p.pareto) front.push_back(xy);
    if (p.setting.current) plot.highlight.push_back(xy);
  }
  for (auto& [kind, series] : by_kind) plot.series.push_back(series);
  std::sort(front.begin(), front.end());
  plot.line = front;
  plot.line_name = "Pareto front";
  plot.highlight_name = "scene's setting";
  plot.size_note = "marker size: resolution";
  return plot;
}

}  // namespace

int run_bench_tradeoff(const TradeoffCommandOptions& o) {
  Scene scene;
  TradeoffOptions options;
  TradeoffReport report;
  try {
    scene = load_scene(o.scene);
    // A scene without a name is named for its file (the title, the CSV's and PNG's names).
    if (scene.name.empty()) scene.name = std::filesystem::path(o.scene).stem().string();
    if (!(o.seconds > 0)) throw Error("", "--seconds", "must be > 0");
    if (!(o.reference_tolerance > 0)) throw Error("", "--reference-tolerance", "must be > 0");
    options.seconds = o.seconds;
    options.reference_tolerance = o.reference_tolerance;
    std::vector<std::string> notes;
    options.knobs = default_knobs(scene, split(o.knobs), notes);
    for (const std::string& note : notes) spdlog::warn("{}", note);
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  try {
    ProgressBar bar("tradeoff", 1);
    int total_runs = 1;
    auto progress = [&](int done, int total, const std::string& label) {
      total_runs = total;
      bar = ProgressBar("tradeoff", total);
      bar.update(done, label);
    };
    report = run_tradeoff(scene, options, progress);
    bar.finish();
    (void)total_runs;
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  std::printf("bench tradeoff: '%s', %g s per run; reference %s: %.3f s of wall time%s\n",
              scene.name.c_str(), o.seconds, report.reference.label().c_str(),
              report.reference_wall_seconds,
              report.references > 1 ? " (all references: one per physics setting)" : "");
  // The physics columns only where a physics knob is swept: most sweeps have none.
  const bool physics = report.references > 1;
  std::printf("%-44s %9s %9s %10s %10s %11s %10s %11s %10s %10s", "setting", "wall s", "substeps",
              "centre m", "joint rad", "q_s", "nodes rms", "violation m", "energy", "depth m");
  if (physics) std::printf(" %10s %10s", "physics m", "phys rad");
  const bool liquids = !scene.liquids.empty();
  if (liquids)
    std::printf(" %10s %10s %10s %10s", "volume", "liq. cen m", "l. front m", "l. top m");
  std::printf(" %7s\n", "pareto");
  for (const TradeoffPoint& p : report.points) {
    const std::string label = p.setting.label() + (p.setting.current ? " *" : "");
    if (!p.ok) {
      std::printf("%-44s failed: %s\n", label.c_str(), p.message.c_str());
      continue;
    }
    std::printf("%-44s %9.4f %9ld %10.3e %10.3e %11.3e %10.3e %11.3e %10.3e %10.3e", label.c_str(),
                p.wall_seconds, p.substeps, p.centre_error, p.joint_error, p.shape_error,
                p.node_rms, p.constraint_violation, p.energy_error, p.depth);
    if (physics) std::printf(" %10.3e %10.3e", p.physics_centre, p.physics_joint);
    if (liquids) {
      std::printf(" %10.3e %10.3e %10.3e %10.3e", p.liquid_volume, p.liquid_centre, p.liquid_front,
                  p.liquid_height);
    }
    std::printf(" %7s\n", p.pareto ? "yes" : "");
  }
  std::printf("* the scene's own setting; nodes rms -1: another node count than the reference\n");
  if (physics) {
    std::printf(
        "errors against the reference of the point's own physics; physics m, phys rad: how far "
        "that reference lies from the scene's own (what the knob changes)\n");
  }
  const std::filesystem::path folder(o.out);
  const std::string stem = (folder / (scene.name + "-tradeoff")).string();
  try {
    std::filesystem::create_directories(folder);
    write_csv(stem + ".csv", report);
    write_png(stem + ".png", render_plot(make_plot(scene, report, o.seconds)));
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  std::printf("wrote %s.csv and %s.png\n", stem.c_str(), stem.c_str());
  return 0;
}

}  // namespace pbm
