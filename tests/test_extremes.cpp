// Stability at the extremes (issue 12): a matrix of scenes at the ends of every knob, each read
// through the scene format like a user's file and run for its frames. Each cell ends in one of
//   ran      every frame computed at the scene's settings;
//   refined  every frame computed, with the substep shortened to a body's stability limit or
//            frames retried by the guard;
//   refused  the file refused with the field named (exit 2), or the run stopped with the body and
//            the quantity named (exit 1);
// and never in a crash, a hang or a NaN frame. The outcome of every cell is committed in
// docs/extremes.md; `tools/extremes-table` regenerates that table from this test.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "constraint_scenes.h"
#include "core/error.h"
#include "scene/json_reader.h"
#include "scene/scene_json.h"
#include "scene_builders.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

using test::constraints::body_point;
using test::constraints::joint;
using test::constraints::part;
using test::constraints::world;

struct Cell {
  std::string name;
  std::function<Scene()> make;
  int frames = 30;
};

// A local ball (8 x 8, 10 kg, radius 1) dropped from 1 m onto the ground: the base of most cells.
Scene ball_on_ground() {
  BodyDef b = test::ball(DeformLevel::local, 8);
  b.position = Vec3(0, 0, 2);
  b.material.damping = 1;
  Scene s;
  s.name = "extreme";
  s.solver.dt = 1e-3;
  s.bodies = {b};
  ObstacleDef ground;
  ground.name = "ground";
  s.obstacles = {ground};
  return s;
}

Scene with(std::function<void(Scene&)> change) {
  Scene s = ball_on_ground();
  change(s);
  return s;
}

// n capsules of `mass` kg, 5 / n m long, hanging by revolute joints about y from 6 m, released
// horizontal (a figure, ch. 15); the last one `last_mass` kg when given.
Scene figure_chain(int n, IntegratorKind integrator, Real mass, Real damping = 0,
                   Real last_mass = 0) {
  Scene s;
  s.name = "extreme";
  s.solver.dt = 1e-3;
  s.solver.integrator = integrator;
  FigureDef chain;
  chain.name = "chain";
  const Real link = 5.0 / n;
  for (int i = 0; i < n; ++i) {
    SegmentDef seg;
    seg.name = "link" + std::to_string(i);
    if (i > 0) seg.parent = "link" + std::to_string(i - 1);
    seg.joint.axis = Vec3::UnitY();
    seg.joint.position = i ? Vec3(0, 0, -link) : Vec3(0, 0, 6);
    seg.joint.damping = damping;
    if (i == 0) seg.joint.q0 = {1.5707963267948966};
    seg.shape.kind = SegmentShapeKind::capsule;
    seg.shape.size = Vec3(0.2 * link, 0.2 * link, 0.3 * link);
    seg.shape.center = Vec3(0, 0, -0.5 * link);
    seg.mass = i + 1 == n && last_mass > 0 ? last_mass : mass;
    chain.segments.push_back(seg);
  }
  s.figures = {chain};
  return s;
}

// A free `shape` of `mass` kg whose centre starts at `at` moving at `velocity` (a figure of one
// segment on a free joint, ch. 15).
FigureDef free_segment(const std::string& name, SegmentShapeKind shape, const Vec3& size, Real mass,
                       const Vec3& at, const Vec3& velocity) {
  FigureDef f;
  f.name = name;
  SegmentDef seg;
  seg.name = name;
  seg.joint.kind = JointKind::free;
  seg.joint.q0 = {at.x(), at.y(), at.z(), 1, 0, 0, 0};
  seg.joint.v0 = {0, 0, 0, velocity.x(), velocity.y(), velocity.z()};
  seg.shape.kind = shape;
  seg.shape.size = size;
  seg.mass = mass;
  f.segments = {seg};
  return f;
}

// A 5-link chain of 1 kg links with a controller on every joint holding 0.5 rad, the
// controller's settings changed by `change`.
template <typename Change>
Scene controlled_chain(IntegratorKind integrator, Change&& change) {
  Scene s = figure_chain(5, integrator, 1);
  for (const SegmentDef& seg : s.figures[0].segments) {
    ControllerDef d;
    d.joint = seg.name;
    d.keys = {{0, 0.5}};
    change(d);
    s.figures[0].controllers.push_back(d);
  }
  return s;
}

std::vector<Cell> cells() {
  std::vector<Cell> c;
  for (Real w : {1e-6, 1e6}) {
    c.push_back({"membrane w0 = w1 = " + format_real(w), [w] {
                   return with(
                       [w](Scene& s) { s.bodies[0].material.w0 = s.bodies[0].material.w1 = w; });
                 }});
  }
  for (Real k : {1e-6, 1e6}) {
    c.push_back({"global stiffness k_s = " + format_real(k),
                 [k] { return with([k](Scene& s) { s.bodies[0].k_s.setConstant(k); }); }});
  }
  // solver.dt as a multiple of the ball's Euler limit (max_retries < 0: the default), in frames
  // of 0.5 s so that the substep is solver.dt's own and not the frame's.
  for (const auto& [name, factor, max_retries] :
       {std::tuple{"dt at the Euler limit", 1.0, -1},
        {"dt 0.8 of the Euler limit", 0.8, -1},
        {"dt 10x past the Euler limit, max_retries 0", 10.0, 0}}) {
    c.push_back({name,
                 [factor, max_retries] {
                   Scene s = ball_on_ground();
                   s.solver.fps = 2;
                   // The membrane's limit (the shape parameters' is 2 solver.dt, never reached).
                   const BodyModel body = Simulation(s).model.bodies[0];
                   const Real w = body.stability.omega, nu = body.damping;
                   s.solver.dt = factor * 2 / (nu / 2 + std::sqrt(nu * nu / 4 + w * w));
                   if (max_retries >= 0) s.solver.max_retries = max_retries;
                   return s;
                 },
                 4});
  }
  for (Real mass : {1e-6, 1e6}) {
    c.push_back({"body mass " + format_real(mass) + " kg", [mass] {
                   return with([mass](Scene& s) { test::set_uniform_mass(s.bodies[0], mass); });
                 }});
  }
  for (Real eps : {0.1, 4.0}) {
    c.push_back({"squareness eps1 = eps2 = " + format_real(eps), [eps] {
                   return with([eps](Scene& s) {
                     s.bodies[0].q_s[4] = s.bodies[0].q_s[5] = eps;
                     s.bodies[0].q_s0 = s.bodies[0].q_s;
                   });
                 }});
  }
  for (Real taper : {-1.0, 1.0}) {
    c.push_back({"taper t1 = t2 = " + format_real(taper), [taper] {
                   return with([taper](Scene& s) {
                     BodyDef& b = s.bodies[0];
                     b.shape = ShapeKind::taper_bend;
                     b.q_s = default_shape_parameters(b.shape);
                     b.q_s[6] = b.q_s[7] = taper;
                     b.q_s0 = b.q_s;
                     b.k_s = VecX::Constant(b.q_s.size(), 2000.0);
                   });
                 }});
  }
  for (DeformLevel level : {DeformLevel::rigid, DeformLevel::global, DeformLevel::local}) {
    const char* names[] = {"rigid", "global", "local"};
    c.push_back(
        {std::string("10 m/s impact, ") + names[static_cast<int>(level)] + " ball", [level] {
           return with([level](Scene& s) {
             s.bodies[0].level = level;
             s.bodies[0].velocity = Vec3(0, 0, -10);
           });
         }});
  }
  // The implicit integrator (deform/implicit_membrane.h) at the same ends: the membrane it takes
  // at the step's end, a step far past Euler's limit with no retry allowed, the hardest impact.
  c.push_back({"membrane w0 = w1 = 1e+06, implicit", [] {
                 return with([](Scene& s) {
                   s.bodies[0].material.w0 = s.bodies[0].material.w1 = 1e6;
                   s.solver.integrator = IntegratorKind::implicit;
                 });
               }});
  c.push_back({"dt 10x past the Euler limit, implicit, max_retries 0",
               [] {
                 Scene s = ball_on_ground();
                 s.solver.fps = 2;
                 const BodyModel body = Simulation(s).model.bodies[0];
                 const Real w = body.stability.omega, nu = body.damping;
                 s.solver.dt = 10 * 2 / (nu / 2 + std::sqrt(nu * nu / 4 + w * w));
                 s.solver.integrator = IntegratorKind::implicit;
                 s.solver.max_retries = 0;
                 return s;
               },
               4});
  c.push_back({"10 m/s impact, local ball, implicit", [] {
                 return with([](Scene& s) {
                   s.bodies[0].velocity = Vec3(0, 0, -10);
                   s.solver.integrator = IntegratorKind::implicit;
                 });
               }});
  c.push_back({"mass ratio 1:1e4, 1e4 kg ball dropped on a 1 kg ball", [] {
                 return with([](Scene& s) {
                   BodyDef heavy = s.bodies[0];
                   heavy.name = "heavy";
                   heavy.position = Vec3(0, 0, 4.2);
                   test::set_uniform_mass(heavy, 1e4);
                   test::set_uniform_mass(s.bodies[0], 1);
                   s.bodies[0].position = Vec3(0, 0, 1.05);
                   s.bodies.push_back(heavy);
                 });
               }});
  // The constraint solver at its size limit; the links' collisions with their neighbours'
  // neighbours are left out (they would time the body-collision stage instead).
  c.push_back({"1000 constraints, a chain of rigid links",
               [] {
                 Scene s;
                 s.solver.body_collisions = false;
                 s.solver.dt = 1e-3;
                 s.solver.fps = 50;
                 s.solver.constraint_solver = ConstraintSolverKind::sparse;
                 const Real link = 0.01;
                 for (int i = 0; i < 1000; ++i) {
                   BodyDef b = part("link" + std::to_string(i), DeformLevel::rigid,
                                    Vec3((i + 0.5) * link, 0, 0), 0.004);
                   b.tessellation.rings = 2;
                   b.tessellation.segments = 3;
                   test::set_uniform_mass(b, 0.01);
                   s.bodies.push_back(b);
                 }
                 s.constraints.push_back(
                     joint(body_point(0, Vec3(-0.5 * link, 0, 0)), world(Vec3::Zero())));
                 for (int i = 0; i + 1 < 1000; ++i) {
                   s.constraints.push_back(joint(body_point(i, Vec3(0.5 * link, 0, 0)),
                                                 body_point(i + 1, Vec3(-0.5 * link, 0, 0))));
                 }
                 return s;
               },
               10});
  // Articulated figures (ch. 15): long chains, a mass ratio across a joint, stiff joint damping.
  c.push_back({"figure: 100-segment chain, rk4",
               [] { return figure_chain(100, IntegratorKind::rk4, 0.1); }});
  c.push_back({"figure: 100-segment chain, euler",
               [] { return figure_chain(100, IntegratorKind::euler, 0.1); }});
  c.push_back({"figure: mass ratio 1:1e4, a 1e4 kg segment hung from 1 kg ones",
               [] { return figure_chain(5, IntegratorKind::rk4, 1, 0, 1e4); }});
  c.push_back({"figure: joint damping 1e6 N m s/rad, euler",
               [] { return figure_chain(5, IntegratorKind::euler, 1, 1e6); }});
  c.push_back(
      {"figure: segment mass 1e-6 kg", [] { return figure_chain(5, IntegratorKind::rk4, 1e-6); }});
  // Impacts at 10 m/s (sec. 15.3): a segment on the ground, two figures head on, a segment into
  // the deformable ball (5.2.2 with the segment as one body).
  c.push_back({"figure: a 2 kg box striking the ground at 10 m/s", [] {
                 Scene s = ball_on_ground();
                 s.bodies.clear();
                 s.figures = {free_segment("box", SegmentShapeKind::box, Vec3(0.2, 0.2, 0.2), 2,
                                           Vec3(0, 0, 0.5), Vec3(0, 0, -10))};
                 return s;
               }});
  c.push_back({"figure: two 1 kg spheres meeting head on at 10 m/s each", [] {
                 Scene s = ball_on_ground();
                 s.bodies.clear();
                 s.gravity = Vec3::Zero();
                 s.figures = {free_segment("left", SegmentShapeKind::sphere, Vec3::Constant(0.2), 1,
                                           Vec3(-0.5, 0, 1), Vec3(10, 0, 0)),
                              free_segment("right", SegmentShapeKind::sphere, Vec3::Constant(0.2),
                                           1, Vec3(0.5, 0, 1), Vec3(-10, 0, 0))};
                 return s;
               }});
  c.push_back({"figure: a 5 kg capsule striking the local ball at 10 m/s", [] {
                 Scene s = ball_on_ground();
                 s.bodies[0].position = Vec3(0, 0, 1);
                 s.figures = {free_segment("bat", SegmentShapeKind::capsule, Vec3(0.1, 0.1, 0.3), 5,
                                           Vec3(0, 0, 2.8), Vec3(0, 0, -10))};
                 return s;
               }});
  // Joint controllers (sec. 15.4) on every joint of the chain, driving it to hang at 0.5 rad.
  c.push_back({"figure: MRAC t_s 0.01 s on every joint, rk4", [] {
                 return controlled_chain(IntegratorKind::rk4,
                                         [](ControllerDef& d) { d.settling_time = 0.01; });
               }});
  c.push_back({"figure: MRAC limited to 1e-3 N m, rk4", [] {
                 return controlled_chain(IntegratorKind::rk4,
                                         [](ControllerDef& d) { d.max_output = 1e-3; });
               }});
  // The explicit servo at gains 1000 times lower already needs the substep shortened; at the
  // stable servo's gains it would need 1e-7 s.
  c.push_back({"figure: explicit PD kp 1e6, kd 1e3, euler", [] {
                 return controlled_chain(IntegratorKind::euler, [](ControllerDef& d) {
                   d.kind = ControllerKind::pd;
                   d.kp = 1e6;
                   d.kd = 1e3;
                 });
               }});
  c.push_back({"figure: stable PD kp 1e9, kd 1e6, euler", [] {
                 return controlled_chain(IntegratorKind::euler, [](ControllerDef& d) {
                   d.kind = ControllerKind::stable_pd;
                   d.kp = 1e9;
                   d.kd = 1e6;
                 });
               }});
  // Stable PD servos at the same gains on ball joints: each spherical joint's three components of
  // its rotation vector (control/ball_coordinates.h), targets 0.5 rad about y.
  c.push_back({"figure: stable PD kp 1e9, kd 1e6 on ball joints, euler", [] {
                 Scene s = figure_chain(5, IntegratorKind::euler, 1);
                 FigureDef& chain = s.figures[0];
                 chain.segments[0].joint.q0 = {0.7071067811865476, 0, 0.7071067811865476, 0};
                 for (SegmentDef& seg : chain.segments) {
                   seg.joint.kind = JointKind::spherical;
                   for (int k = 0; k < 3; ++k) {
                     ControllerDef d;
                     d.kind = ControllerKind::stable_pd;
                     d.joint = seg.name;
                     d.dof = k;
                     d.keys = {{0, k == 1 ? 0.5 : 0.0}};
                     d.kp = 1e9;
                     d.kd = 1e6;
                     chain.controllers.push_back(d);
                   }
                 }
                 return s;
               }});
  // Liquids (ch. 16): a 2D dam break (20 x 1 x 12 cells of 5 cm) at the ends of its knobs.
  auto liquid = [](const std::string& knobs, const std::string& inflow = "",
                   const std::string& resolution = "[20, 1, 12]") {
    return [knobs, inflow, resolution] {
      return parse_scene(R"({"name": "extreme", "solver": {"fps": 30}, "liquids": [{
          "name": "water", "domain": {"min": [0, 0, 0], "max": [1, 0.1, 0.6]},
          "resolution": )" + resolution +
                             R"(,
          "fluid": [{"box": {"min": [0, 0, 0], "max": [0.3, 0.1, 0.5]}}])" +
                             inflow + knobs + "}]}",
                         "extreme.json");
    };
  };
  c.push_back({"liquid: dam break at CFL 1", liquid(R"(, "cfl": 1)")});
  c.push_back({"liquid: inflow at 10 m/s",
               liquid("", R"(, "inflows": [{"box": {"min": [0, 0, 0.5], "max": [0.05, 0.1, 0.55]},
                           "velocity": [10, 0, 0]}])")});
  c.push_back({"liquid: viscosity 0", liquid(R"(, "viscosity": 0)")});
  c.push_back({"liquid: viscosity 1 m^2/s", liquid(R"(, "viscosity": 1)")});
  c.push_back({"liquid: 512^3 cells, over the grid budget", liquid("", "", "[512, 512, 512]")});
  return c;
}

struct Outcome {
  std::string kind;    // ran, refined, refused; anything else fails the test
  std::string detail;  // the message, or what the guard and the limit did
};

Outcome run(const Cell& cell) {
  std::unique_ptr<Simulation> sim;
  try {
    // Through the file format, as a user's scene comes in.
    const Scene scene = parse_scene(scene_to_json(cell.make()), cell.name + ".json");
    sim = std::make_unique<Simulation>(scene);
  } catch (const Error& e) {
    return {"refused", e.what()};
  }
  int retries = 0;
  for (int f = 0; f < cell.frames; ++f) {
    const FrameResult r = advance_frame(*sim);
    if (!sim->state.q.allFinite() || !sim->state.v.allFinite()) {
      return {"NaN", "frame " + std::to_string(f + 1)};
    }
    if (!r.ok) return {"refused", "frame " + std::to_string(f + 1) + ": " + r.message};
    retries += sim->stats.retries;
  }
  const bool shortened = sim->model.substep < sim->model.solver.dt;
  if (retries == 0 && !shortened) return {"ran", ""};
  std::ostringstream detail;
  if (shortened) {
    char text[64];
    std::snprintf(text, sizeof text, "substep %.3g s (solver.dt %.3g s); ", sim->model.substep,
                  sim->model.solver.dt);
    detail << text;
  }
  detail << retries << " retries";
  return {"refined", detail.str()};
}

// The committed outcomes: "| cell | outcome | detail |" rows of docs/extremes.md.
std::vector<std::pair<std::string, std::string>> committed_outcomes() {
  std::ifstream file(PBM_SOURCE_DIR "/docs/extremes.md");
  std::vector<std::pair<std::string, std::string>> rows;
  std::string line;
  while (std::getline(file, line)) {
    if (!line.starts_with("| ") || line.starts_with("| cell") || line.starts_with("|--")) continue;
    std::vector<std::string> cols;
    std::stringstream ss(line.substr(2));
    std::string col;
    while (std::getline(ss, col, '|')) {
      while (!col.empty() && col.back() == ' ') col.pop_back();
      while (!col.empty() && col.front() == ' ') col.erase(col.begin());
      cols.push_back(col);
    }
    if (cols.size() >= 2) rows.emplace_back(cols[0], cols[1]);
  }
  return rows;
}

TEST(Extremes, EveryCellRunsRefinesOrRefusesAsCommitted) {
  const std::vector<Cell> all = cells();
  const auto committed = committed_outcomes();
  std::ostringstream table;
  table << "| cell | outcome | detail |\n|---|---|---|\n";
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const Outcome o = run(all[i]);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::string detail = o.detail;
    for (char& ch : detail) {
      if (ch == '|' || ch == '\n') ch = ' ';
    }
    table << "| " << all[i].name << " | " << o.kind << " | " << detail << " |\n";
    std::printf("%-55s %-8s %5.2f s  %s\n", all[i].name.c_str(), o.kind.c_str(), seconds,
                detail.c_str());
    EXPECT_TRUE(o.kind == "ran" || o.kind == "refined" || o.kind == "refused")
        << all[i].name << ": " << o.kind << " " << o.detail;
    if (i < committed.size()) {
      EXPECT_EQ(committed[i].first, all[i].name) << "docs/extremes.md: regenerate it";
      EXPECT_EQ(committed[i].second, o.kind)
          << all[i].name << " (docs/extremes.md says " << committed[i].second << "; run "
          << "tools/extremes-table if the change is meant)";
    }
  }
  EXPECT_EQ(committed.size(), all.size()) << "docs/extremes.md: regenerate it";
  if (const char* out = std::getenv("PBM_EXTREMES_TABLE")) std::ofstream(out) << table.str();
}

}  // namespace
}  // namespace pbm
