#include "sim/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "liquid/cell_labels.h"
#include "liquid/surface_chains.h"
#include "scene/scene_enum_names.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

// What a run leaves to compare, frame by frame.
struct Trajectory {
  std::vector<std::vector<Vec3>> centres;  // [frame][body]
  std::vector<std::vector<VecX>> shapes;   // [frame][body]
  std::vector<VecX> nodes;                 // [frame]: every body's node positions, in order
  std::vector<std::vector<Mat3>> joints;   // [frame][segment]: parent -> segment rotations
  std::vector<Real> total_energy;          // [frame]
  Real largest_energy = 0;                 // kinetic + elastic over frames
  Real violation = 0;
  Real depth = 0;  // the deepest contact over the frames [m]
  // [frame][liquid]: volume [m^3], centre of mass, front and highest point [m].
  struct LiquidSample {
    Real volume = 0;
    Vec3 centre = Vec3::Zero();
    Real front = 0, top = 0;
  };
  std::vector<std::vector<LiquidSample>> liquids;
  double wall_seconds = 0;
  long substeps = 0, evaluations = 0, retries = 0;
  bool ok = true;
  std::string message;
};

// A liquid's centre of mass, its reach along the grid's first horizontal axis and its highest
// point: from its markers, its chains' loops (their centroid), or its height field's columns.
Trajectory::LiquidSample sample_liquid(const LiquidModel& m, const LiquidState& s, Real volume) {
  Trajectory::LiquidSample out;
  out.volume = volume;
  const MacGrid& g = m.grid;
  const ColumnAxes axes = column_axes(m);
  out.front = -1e300;
  out.top = -1e300;
  if (m.def.surface == SurfaceMethod::markers) {
    for (const Vec3& x : s.markers) {
      out.centre += x;
      out.front = std::max(out.front, x[axes.h0]);
      out.top = std::max(out.top, x[axes.v]);
    }
    if (!s.markers.empty()) out.centre /= static_cast<Real>(s.markers.size());
    return out;
  }
  if (m.def.surface == SurfaceMethod::chains) {
    (void)chains_area(m, s.chain, s.chain_next, &out.centre);
    for (const Vec3& x : s.chain) {
      out.front = std::max(out.front, x[axes.h0]);
      out.top = std::max(out.top, x[axes.v]);
    }
    return out;
  }
  const Real bottom = g.origin[axes.v];
  Real weight = 0;
  const int n0 = g.n[axes.h0];
  for (std::size_t c = 0; c < s.height.size(); ++c) {
    const Real depth = s.height[c] - bottom;
    Vec3 x = g.centre(1, 1, 1);
    x[axes.h0] = g.origin[axes.h0] + (static_cast<int>(c) % n0 + 0.5) * g.h[axes.h0];
    x[axes.h1] = g.origin[axes.h1] + (static_cast<int>(c) / n0 + 0.5) * g.h[axes.h1];
    x[axes.v] = bottom + 0.5 * depth;
    out.centre += depth * x;
    weight += depth;
    // A column holding liquid (deeper than a hundredth of a cell) reaches its far edge.
    if (depth > 0.01 * g.h[axes.v])
      out.front = std::max(out.front, x[axes.h0] + 0.5 * g.h[axes.h0]);
    out.top = std::max(out.top, s.height[c]);
  }
  if (weight > 0) out.centre /= weight;
  return out;
}

Trajectory record(const Scene& scene, Real seconds, const std::atomic<bool>* cancel) {
  Trajectory t;
  try {
    Simulation sim(scene);
    const int frames = std::max(1, static_cast<int>(std::lround(seconds * sim.model.solver.fps)));
    for (int f = 0; f < frames; ++f) {
      const FrameResult r = advance_frame(sim);
      if (!r.ok) {
        t.ok = false;
        t.message = "frame " + std::to_string(f + 1) + ": " + r.message;
        return t;
      }
      const FrameStats& s = sim.stats;
      t.wall_seconds += s.wall_seconds;
      t.substeps += s.substeps;
      t.evaluations += s.evaluations;
      t.retries += s.retries;
      t.violation = std::max(t.violation, s.constraint_violation);
      if (s.min_distance < 1e299) t.depth = std::max(t.depth, -s.min_distance);
      for (const FigureFrameStats& figure : s.figures) t.depth = std::max(t.depth, figure.depth);
      t.total_energy.push_back(s.kinetic + s.elastic + s.potential);
      t.largest_energy = std::max(t.largest_energy, s.kinetic + s.elastic);
      std::vector<Vec3> centres;
      std::vector<VecX> shapes;
      std::size_t count = 0;
      for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        centres.push_back(s.bodies[b].position);
        shapes.push_back(s.bodies[b].q_s);
        count += sim.ws.bodies[b].x.size();
      }
      // Every figure's segment origins join the centres (measure_state leaves each figure's
      // kinematics of the frame's end in the workspace): a joint angle's error shows there as
      // the distance it moves its segments.
      std::vector<Mat3> joints;
      for (std::size_t k = 0; k < sim.model.figures.size(); ++k) {
        std::vector<SpatialTransform> world;
        segment_world_transforms(sim.model.figures[k].model, sim.ws.figures->each[k], world);
        for (const SpatialTransform& X : world) centres.push_back(X.r);
        for (const SpatialTransform& X : sim.ws.figures->each[k].X_up) joints.push_back(X.E);
      }
      t.joints.push_back(std::move(joints));
      // measure_state leaves the bodies' kinematics of the frame's end in the workspace.
      VecX nodes(3 * static_cast<Eigen::Index>(count));
      Eigen::Index at = 0;
      for (const BodyWorkspace& bw : sim.ws.bodies) {
        for (const Vec3& x : bw.x) {
          nodes.segment<3>(at) = x;
          at += 3;
        }
      }
      std::vector<Trajectory::LiquidSample> liquids;
      for (std::size_t l = 0; l < sim.model.liquids.size(); ++l) {
        liquids.push_back(
            sample_liquid(sim.model.liquids[l], sim.state.liquids[l], s.liquids[l].volume));
      }
      t.liquids.push_back(std::move(liquids));
      t.centres.push_back(std::move(centres));
      t.shapes.push_back(std::move(shapes));
      t.nodes.push_back(std::move(nodes));
      if (cancel && cancel->load()) {
        t.ok = false;
        t.message = "cancelled";
        return t;
      }
    }
  } catch (const Error& e) {
    t.ok = false;
    t.message = e.what();
  }
  return t;
}

void compare(const Trajectory& run, const Trajectory& ref, TradeoffPoint& point) {
  const std::size_t frames = std::min(run.centres.size(), ref.centres.size());
  Real node_sum = 0;
  std::size_t node_count = 0;
  bool nodes_match = true;
  const Real scale = std::max(ref.largest_energy, 1e-12);
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t b = 0; b < run.centres[f].size() && b < ref.centres[f].size(); ++b) {
      point.centre_error =
          std::max(point.centre_error, (run.centres[f][b] - ref.centres[f][b]).norm());
      // Bodies' centres come first; the figures' segments after them have no shape.
      if (b >= run.shapes[f].size() || b >= ref.shapes[f].size()) continue;
      if (run.shapes[f][b].size() == ref.shapes[f][b].size() && run.shapes[f][b].size() > 0) {
        point.shape_error = std::max(point.shape_error,
                                     (run.shapes[f][b] - ref.shapes[f][b]).cwiseAbs().maxCoeff());
      }
    }
    // Joint angles: the rotation between the run's and the reference's parent -> segment
    // rotations, whatever the joint's coordinates (angles, a quaternion).
    for (std::size_t j = 0; j < run.joints[f].size() && j < ref.joints[f].size(); ++j) {
      // The angle as atan2(sin, cos): sin from the skew part, |vee(R - R^T)| / 2, keeps its
      // precision at small angles, where acos of the trace cannot resolve below ~1e-8 rad.
      const Mat3 relative = run.joints[f][j] * ref.joints[f][j].transpose();
      const Vec3 axis(relative(2, 1) - relative(1, 2), relative(0, 2) - relative(2, 0),
                      relative(1, 0) - relative(0, 1));
      const Real angle = std::atan2(axis.norm() / 2, (relative.trace() - 1) / 2);
      point.joint_error = std::max(point.joint_error, angle);
    }
    if (run.nodes[f].size() == ref.nodes[f].size()) {
      node_sum += (run.nodes[f] - ref.nodes[f]).squaredNorm();
      node_count += static_cast<std::size_t>(run.nodes[f].size() / 3);
    } else {
      nodes_match = false;
    }
    point.energy_error =
        std::max(point.energy_error, std::abs(run.total_energy[f] - ref.total_energy[f]) / scale);
    for (std::size_t l = 0; l < run.liquids[f].size() && l < ref.liquids[f].size(); ++l) {
      const Trajectory::LiquidSample& a = run.liquids[f][l];
      const Trajectory::LiquidSample& b = ref.liquids[f][l];
      if (b.volume > 0) {
        point.liquid_volume =
            std::max(point.liquid_volume, std::abs(a.volume - b.volume) / b.volume);
      }
      point.liquid_centre = std::max(point.liquid_centre, (a.centre - b.centre).norm());
      point.liquid_front = std::max(point.liquid_front, std::abs(a.front - b.front));
      point.liquid_height = std::max(point.liquid_height, std::abs(a.top - b.top));
    }
  }
  point.node_rms = nodes_match && node_count > 0 ? std::sqrt(node_sum / node_count) : -1;
}

}  // namespace

std::string TradeoffSetting::label() const {
  char text[160];
  if (integrator == IntegratorKind::rk45) {
    std::snprintf(text, sizeof text, "rk45 tol %g dt %g res %gx", tolerance, dt, resolution);
  } else {
    std::snprintf(text, sizeof text, "%s dt %g res %gx", name_of(kIntegratorKindNames, integrator),
                  dt, resolution);
  }
  std::string label = text;
  if (contact) label += std::string(" ") + name_of(kContactQuadratureNames, *contact);
  if (stiffness != 1) {
    std::snprintf(text, sizeof text, " k %gx", stiffness);
    label += text;
  }
  if (restitution) {
    std::snprintf(text, sizeof text, " e %g", *restitution);
    label += text;
  }
  if (gains != 1) {
    std::snprintf(text, sizeof text, " gains %gx", gains);
    label += text;
  }
  if (settling != 1) {
    std::snprintf(text, sizeof text, " t_s %gx", settling);
    label += text;
  }
  if (liquid_resolution != 1) {
    std::snprintf(text, sizeof text, " cells %gx", liquid_resolution);
    label += text;
  }
  if (cfl > 0) {
    std::snprintf(text, sizeof text, " cfl %g", cfl);
    label += text;
  }
  if (advection) label += std::string(" ") + name_of(kLiquidAdvectionNames, *advection);
  if (pressure_solver) label += std::string(" ") + name_of(kPressureSolverNames, *pressure_solver);
  if (relaxation > 0) {
    std::snprintf(text, sizeof text, " beta0 %g", relaxation);
    label += text;
  }
  if (epsilon > 0) {
    std::snprintf(text, sizeof text, " eps %g", epsilon);
    label += text;
  }
  if (markers_per_axis > 0) {
    std::snprintf(text, sizeof text, " markers %d", markers_per_axis);
    label += text;
  }
  return label;
}

bool TradeoffSetting::same_physics(const TradeoffSetting& other) const {
  return stiffness == other.stiffness && restitution == other.restitution && gains == other.gains &&
         settling == other.settling;
}

bool TradeoffSetting::scenes_physics() const {
  return same_physics(TradeoffSetting{});
}

TradeoffKnobs default_knobs(const Scene& scene, const std::vector<std::string>& names,
                            std::vector<std::string>& notes) {
  TradeoffKnobs knobs;
  const Real frame = 1.0 / scene.solver.fps;
  const Real dt0 = std::min(scene.solver.dt, frame);
  knobs.dt = {dt0};
  knobs.integrators = {scene.solver.integrator};
  knobs.tolerances = {scene.solver.tolerance};
  knobs.resolutions = {1.0};
  for (const std::string& name : names) {
    if (name == "dt") {
      knobs.dt.clear();
      for (Real factor : {2.0, 1.0, 0.5, 0.25}) {
        const Real dt = std::min(factor * dt0, frame);
        if (std::find(knobs.dt.begin(), knobs.dt.end(), dt) == knobs.dt.end())
          knobs.dt.push_back(dt);
      }
    } else if (name == "integrator") {
      knobs.integrators = {IntegratorKind::euler, IntegratorKind::rk4, IntegratorKind::implicit};
      if (scene.solver.integrator == IntegratorKind::rk45)
        knobs.integrators.push_back(IntegratorKind::rk45);
    } else if (name == "tolerance") {
      knobs.tolerances = {1e-3, 1e-4, 1e-5};
      if (std::find(knobs.integrators.begin(), knobs.integrators.end(), IntegratorKind::rk45) ==
          knobs.integrators.end())
        knobs.integrators.push_back(IntegratorKind::rk45);
    } else if (name == "resolution") {
      bool per_node = false;
      for (const BodyDef& body : scene.bodies) per_node |= body.material.nodal_mass > 0;
      if (per_node) {
        notes.push_back(
            "resolution left out: a body's mass is given per node (nodal_mass), so refining its "
            "mesh adds mass (scenes/README.md, \"Materials that converge\")");
      } else {
        knobs.resolutions = {0.5, 1.0, 2.0};
      }
    } else if (name == "contact") {
      bool local = false;
      for (const BodyDef& body : scene.bodies)
        local |= body.level != DeformLevel::rigid && body.level != DeformLevel::global;
      if (local) {
        knobs.contacts = {ContactQuadrature::three_point, ContactQuadrature::centroid};
      } else {
        notes.push_back("contact left out: no body is local, so none has contact points");
      }
    } else if (name == "stiffness") {
      if (scene.figures.empty()) {
        notes.push_back("stiffness left out: no figure (it sets the figures' contact springs)");
      } else {
        knobs.stiffness = {0.25, 1.0, 4.0};
      }
    } else if (name == "restitution") {
      if (scene.figures.empty()) {
        notes.push_back("restitution left out: no figure (it sets the figures' impacts' e)");
      } else {
        // The scene's own, then the usual three that differ from it.
        knobs.restitution = {std::nullopt};
        for (Real e : {0.0, 0.5, 1.0}) {
          bool scenes = true;
          for (const FigureDef& figure : scene.figures) scenes &= figure.restitution == e;
          if (!scenes) knobs.restitution.push_back(e);
        }
      }
    } else if (name == "gains") {
      bool servos = false;
      for (const FigureDef& figure : scene.figures)
        servos |= !figure.controllers.empty() || (figure.mocap && !figure.mocap->joints.empty());
      if (servos) {
        knobs.gains = {0.5, 1.0, 2.0};
      } else {
        notes.push_back("gains left out: no figure has a joint controller");
      }
    } else if (name == "settling") {
      bool mrac = false;
      for (const FigureDef& figure : scene.figures) {
        for (const ControllerDef& c : figure.controllers) mrac |= c.kind == ControllerKind::mrac;
        mrac |= figure.mocap && !figure.mocap->joints.empty() &&
                figure.mocap->controller == ControllerKind::mrac;
      }
      if (mrac) {
        knobs.settling = {0.5, 1.0, 2.0};
      } else {
        notes.push_back("settling left out: no figure has an MRAC controller (t_s is MRAC's)");
      }
    } else if (name == "liquid_resolution" || name == "cfl" || name == "advection" ||
               name == "pressure_solver" || name == "relaxation" || name == "epsilon" ||
               name == "markers") {
      if (scene.liquids.empty()) {
        notes.push_back(name + " left out: the scene has no liquid");
        continue;
      }
      bool markers = false, spaced = false;  // markers carry flip; chains have a spacing too
      for (const LiquidDef& liquid : scene.liquids) {
        markers |= liquid.surface == SurfaceMethod::markers;
        spaced |= liquid.surface != SurfaceMethod::height_field;
      }
      if (name == "liquid_resolution") {
        knobs.liquid_resolution = {0.5, 1.0, 2.0};
      } else if (name == "cfl") {
        knobs.cfl = {1.0, 0.5, 0.25};
      } else if (name == "advection") {
        knobs.advection = {LiquidAdvection::book, LiquidAdvection::semi_lagrangian};
        if (markers) {
          knobs.advection.push_back(LiquidAdvection::flip);
        } else {
          notes.push_back("advection flip left out: no liquid has markers to carry it");
        }
      } else if (name == "pressure_solver") {
        knobs.pressure_solver = {PressureSolver::relaxation, PressureSolver::mic_pcg,
                                 PressureSolver::mgpcg};
      } else if (name == "relaxation") {
        bool relaxed = false;
        for (const LiquidDef& liquid : scene.liquids) {
          relaxed |= liquid.solver == PressureSolver::relaxation;
        }
        if (relaxed) {
          knobs.relaxation = {1.2, 1.5, 1.9};
        } else {
          notes.push_back(
              "relaxation left out: beta_0 is the relaxation solver's, which no "
              "liquid uses (sweep pressure_solver)");
        }
      } else if (name == "epsilon") {
        knobs.epsilon = {1e-3, 1e-4, 1e-5};
      } else if (spaced) {
        knobs.markers_per_axis = {1, 2, 3};
      } else {
        notes.push_back("markers left out: no liquid has markers or chains");
      }
    } else {
      throw Error("", "--knobs",
                  "unknown knob '" + name +
                      "' (dt, integrator, tolerance, resolution, contact, stiffness, "
                      "restitution, gains, settling, liquid_resolution, cfl, advection, "
                      "pressure_solver, relaxation, epsilon, markers)");
    }
  }
  return knobs;
}

Scene apply_setting(const Scene& scene, const TradeoffSetting& setting) {
  Scene s = scene;
  // The model stays the scene's: the shape parameters' inertia floor keeps its time scale while
  // dt moves (deform/body_model.h), so the sweep measures the step, not another model.
  s.solver.shape_inertia_time = scene.solver.shape_inertia_time.value_or(scene.solver.dt);
  s.solver.dt = setting.dt;
  s.solver.integrator = setting.integrator;
  s.solver.tolerance = setting.tolerance;
  for (BodyDef& body : s.bodies) {
    TessellationDef& t = body.tessellation;
    t.rings = std::max(2, static_cast<int>(std::lround(t.rings * setting.resolution)));
    t.segments = std::max(3, static_cast<int>(std::lround(t.segments * setting.resolution)));
    if (setting.contact) t.contact = *setting.contact;
  }
  // The figures' physics. Damping goes with the square root of a stiffness or gain so that a
  // contact's or servo's damping ratio, c / (2 sqrt(k m)), stays the scene's.
  const Real root_stiffness = std::sqrt(setting.stiffness), root_gains = std::sqrt(setting.gains);
  for (FigureDef& figure : s.figures) {
    figure.contact_stiffness *= setting.stiffness;
    figure.contact_damping *= root_stiffness;
    if (setting.restitution) figure.restitution = *setting.restitution;
    for (ControllerDef& c : figure.controllers) {
      c.kp *= setting.gains;
      c.kd *= root_gains;
      c.alpha *= setting.gains;
      c.beta *= setting.gains;
      c.settling_time *= setting.settling;
    }
    if (figure.mocap) {
      MocapDef& m = *figure.mocap;
      m.kp *= setting.gains;
      m.kd *= root_gains;
      m.alpha *= setting.gains;
      m.beta *= setting.gains;
      m.settling_time *= setting.settling;
    }
  }
  for (LiquidDef& liquid : s.liquids) {
    if (setting.liquid_resolution != 1) {
      // The cells per axis, and with them the domain's grid; a 2D liquid stays one cell thick.
      for (int a = 0; a < 3; ++a) {
        if (liquid.resolution[a] == 1) continue;
        liquid.resolution[a] = std::max(
            2, static_cast<int>(std::lround(liquid.resolution[a] * setting.liquid_resolution)));
      }
    }
    if (setting.cfl > 0) liquid.cfl = setting.cfl;
    // flip needs markers: a height field keeps its own advection.
    if (setting.advection &&
        (*setting.advection != LiquidAdvection::flip || liquid.surface == SurfaceMethod::markers)) {
      liquid.advection = *setting.advection;
    }
    if (setting.pressure_solver) liquid.solver = *setting.pressure_solver;
    if (setting.relaxation > 0) liquid.relaxation = setting.relaxation;
    if (setting.epsilon > 0) liquid.tolerance = setting.epsilon;
    if (setting.markers_per_axis > 0) liquid.markers_per_axis = setting.markers_per_axis;
  }
  return s;
}

TradeoffReport run_tradeoff(const Scene& scene, const TradeoffOptions& options,
                            TradeoffProgress progress, const std::atomic<bool>* cancel) {
  TradeoffReport report;
  const TradeoffKnobs& k = options.knobs;
  std::vector<TradeoffSetting> settings;
  // A contact rule is the scene's own where every body already has it.
  const auto scenes_own = [&](const std::optional<ContactQuadrature>& rule) {
    if (!rule) return true;
    for (const BodyDef& body : scene.bodies) {
      if (body.tessellation.contact != *rule) return false;
    }
    return true;
  };
  const auto or_scenes = []<typename T>(const std::vector<T>& values, T scenes) {
    return values.empty() ? std::vector<T>{scenes} : values;
  };
  const std::vector<std::optional<ContactQuadrature>> contacts =
      or_scenes(k.contacts, std::optional<ContactQuadrature>{});
  // The physics settings, the scene's own first: every other is compared with it.
  std::vector<TradeoffSetting> physics{TradeoffSetting{}};
  for (Real stiffness : or_scenes(k.stiffness, 1.0))
    for (const std::optional<Real>& restitution : or_scenes(k.restitution, std::optional<Real>{}))
      for (Real gains : or_scenes(k.gains, 1.0))
        for (Real settling : or_scenes(k.settling, 1.0)) {
          TradeoffSetting p;
          p.stiffness = stiffness;
          p.restitution = restitution;
          p.gains = gains;
          p.settling = settling;
          if (!p.scenes_physics()) physics.push_back(p);
        }
  for (const TradeoffSetting& p : physics)
    for (const std::optional<ContactQuadrature>& contact : contacts)
      for (Real resolution : k.resolutions)
        for (IntegratorKind integrator : k.integrators) {
          const bool adaptive = integrator == IntegratorKind::rk45;
          for (Real tolerance : adaptive ? k.tolerances : std::vector<Real>{scene.solver.tolerance})
            for (Real dt : k.dt) {
              TradeoffSetting s = p;
              s.dt = dt;
              s.integrator = integrator;
              s.tolerance = tolerance;
              s.resolution = resolution;
              s.contact = contact;
              s.current = resolution == 1.0 && integrator == scene.solver.integrator &&
                          dt == std::min(scene.solver.dt, 1.0 / scene.solver.fps) &&
                          (!adaptive || tolerance == scene.solver.tolerance) &&
                          scenes_own(contact) && p.scenes_physics();
              settings.push_back(s);
            }
        }
  // The liquids' knobs, one at a time around the scene's own setting (the factorial's current
  // point, or its first).
  TradeoffSetting centre = settings.front();
  for (const TradeoffSetting& s : settings) {
    if (s.current) centre = s;
  }
  // A value every liquid already has is the centre itself, run once.
  auto one_liquid_knob = [&](bool already, auto apply) {
    if (already) return;
    TradeoffSetting s = centre;
    apply(s);
    s.current = false;
    settings.push_back(s);
  };
  auto every_liquid = [&](auto has) {
    return std::all_of(scene.liquids.begin(), scene.liquids.end(), has);
  };
  for (Real r : k.liquid_resolution)
    one_liquid_knob(r == 1, [&](TradeoffSetting& s) { s.liquid_resolution = r; });
  for (Real c : k.cfl)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.cfl == c; }),
                    [&](TradeoffSetting& s) { s.cfl = c; });
  for (LiquidAdvection a : k.advection)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.advection == a; }),
                    [&](TradeoffSetting& s) { s.advection = a; });
  for (PressureSolver p : k.pressure_solver)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.solver == p; }),
                    [&](TradeoffSetting& s) { s.pressure_solver = p; });
  for (Real b : k.relaxation)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.relaxation == b; }),
                    [&](TradeoffSetting& s) { s.relaxation = b; });
  for (Real e : k.epsilon)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.tolerance == e; }),
                    [&](TradeoffSetting& s) { s.epsilon = e; });
  for (int m : k.markers_per_axis)
    one_liquid_knob(every_liquid([&](const LiquidDef& l) { return l.markers_per_axis == m; }),
                    [&](TradeoffSetting& s) { s.markers_per_axis = m; });
  report.reference.dt = *std::min_element(k.dt.begin(), k.dt.end());
  report.reference.integrator = IntegratorKind::rk45;
  report.reference.tolerance = options.reference_tolerance;
  report.reference.resolution = *std::max_element(k.resolutions.begin(), k.resolutions.end());
  // The three-point rule, the more accurate, when the sweep compares the rules.
  for (const std::optional<ContactQuadrature>& rule : k.contacts) {
    if (rule) report.reference.contact = ContactQuadrature::three_point;
  }
  // The liquids' converged end of each knob swept: the finest grid, the smallest CFL and epsilon,
  // the most markers (advection and solver stay the scene's).
  if (!k.liquid_resolution.empty()) {
    report.reference.liquid_resolution =
        *std::max_element(k.liquid_resolution.begin(), k.liquid_resolution.end());
  }
  if (!k.cfl.empty()) report.reference.cfl = *std::min_element(k.cfl.begin(), k.cfl.end());
  if (!k.epsilon.empty()) {
    report.reference.epsilon = *std::min_element(k.epsilon.begin(), k.epsilon.end());
  }
  if (!k.markers_per_axis.empty()) {
    report.reference.markers_per_axis =
        *std::max_element(k.markers_per_axis.begin(), k.markers_per_axis.end());
  }
  report.references = static_cast<int>(physics.size());
  const int total = static_cast<int>(settings.size()) + report.references;
  int done = 0;
  // Each physics setting's reference; a failed one fails its points, the scene's the sweep.
  std::vector<Trajectory> refs;
  std::vector<TradeoffPoint> physics_change(physics.size());
  for (std::size_t r = 0; r < physics.size(); ++r) {
    TradeoffSetting reference = report.reference;
    reference.stiffness = physics[r].stiffness;
    reference.restitution = physics[r].restitution;
    reference.gains = physics[r].gains;
    reference.settling = physics[r].settling;
    progress(done++, total, "reference: " + reference.label());
    refs.push_back(record(apply_setting(scene, reference), options.seconds, cancel));
    report.reference_wall_seconds += refs.back().wall_seconds;
    if (cancel && cancel->load()) {
      report.cancelled = true;
      return report;
    }
    if (!refs.back().ok) {
      if (r == 0) {
        throw Error(scene.file, "solver",
                    "the reference run (" + reference.label() + ") failed: " + refs[0].message);
      }
      refs.back().message =
          "its reference (" + reference.label() + ") failed: " + refs.back().message;
      continue;
    }
    if (r > 0) compare(refs[r], refs[0], physics_change[r]);
  }
  for (std::size_t i = 0; i < settings.size(); ++i) {
    if (cancel && cancel->load()) {
      report.cancelled = true;
      break;
    }
    std::size_t r = 0;
    while (!settings[i].same_physics(physics[r])) ++r;
    progress(done++, total, settings[i].label());
    TradeoffPoint point;
    point.setting = settings[i];
    if (!refs[r].ok) {
      point.message = refs[r].message;
      report.points.push_back(point);
      continue;
    }
    const Trajectory run = record(apply_setting(scene, settings[i]), options.seconds, cancel);
    point.ok = run.ok;
    point.message = run.message;
    point.wall_seconds = run.wall_seconds;
    point.substeps = run.substeps;
    point.evaluations = run.evaluations;
    point.retries = run.retries;
    point.constraint_violation = run.violation;
    point.depth = run.depth;
    point.physics_centre = physics_change[r].centre_error;
    point.physics_joint = physics_change[r].joint_error;
    if (run.ok) compare(run, refs[r], point);
    report.points.push_back(point);
  }
  mark_pareto_front(report.points);
  return report;
}

void mark_pareto_front(std::vector<TradeoffPoint>& points) {
  for (TradeoffPoint& p : points) {
    p.pareto = p.ok;
    if (!p.ok) continue;
    for (const TradeoffPoint& q : points) {
      if (&q == &p || !q.ok) continue;
      const bool no_worse =
          q.wall_seconds <= p.wall_seconds && q.accuracy_error() <= p.accuracy_error();
      const bool better =
          q.wall_seconds < p.wall_seconds || q.accuracy_error() < p.accuracy_error();
      if (no_worse && better) {
        p.pareto = false;
        break;
      }
    }
  }
}

}  // namespace pbm
