// Liquids in the World (sim/stages_liquid.h): a liquid read from a scene file steps on its own CFL
// clock inside the frames, still water stays still, a dam break keeps its volume and every
// solve's divergence below epsilon, the run is deterministic and scrubs back exactly, a body
// beside a liquid moves bit for bit as it does alone, a NaN in the grid stops the run with the
// liquid's name, and the snapshot draws the markers.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "scene/scene_json.h"
#include "sim/simulation.h"
#include "sim/snapshot.h"

namespace pbm {
namespace {

// A 2D tank 1 m wide, 0.6 m tall, water 0.25 m deep; or a dam break with a column 0.3 m wide and
// 0.5 m tall at its left wall.
std::string tank_scene(bool dam_break, const std::string& extra = "") {
  const std::string fluid = dam_break ? R"({"box": {"min": [0, 0, 0], "max": [0.3, 0.1, 0.5]}})"
                                      : R"({"box": {"min": [0, 0, 0], "max": [1, 0.1, 0.25]}})";
  return R"({"name": "tank", "solver": {"fps": 30}, "liquids": [{"name": "water",
      "domain": {"min": [0, 0, 0], "max": [1, 0.1, 0.6]}, "resolution": [20, 1, 12],
      "fluid": [)" +
         fluid + "]" + extra + "}]}";
}

TEST(LiquidWorld, StillWaterStaysStillAndTheLiquidKeepsUpWithTheFrames) {
  Simulation sim(parse_scene(tank_scene(false), "tank.json"));
  ASSERT_TRUE(sim.world.has(SubsystemId::liquids));
  const Real volume0 = sim.stats.liquids.at(0).volume;
  EXPECT_NEAR(volume0, 1.0 * 0.1 * 0.25, 1e-12);
  for (int f = 0; f < 30; ++f) {
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    // At a frame's end the liquid has reached the frame's time exactly.
    EXPECT_EQ(sim.state.liquids[0].time, sim.state.time);
    const LiquidFrameStats& l = sim.stats.liquids[0];
    EXPECT_GT(l.step.substeps, 0);
    EXPECT_LT(l.max_speed, 1e-6);
    EXPECT_NEAR(l.volume, volume0, 1e-12);
  }
}

TEST(LiquidWorld, ADamBreakKeepsItsVolumeDivergenceAndCfl) {
  Simulation sim(parse_scene(tank_scene(true, R"(, "volume_correction": 0.2)"), "dam.json"));
  const Real volume0 = sim.stats.liquids.at(0).volume;
  const Real cfl = sim.model.liquids[0].def.cfl;
  const Real tolerance = sim.model.liquids[0].def.tolerance;
  int substeps = 0;
  Real fastest = 0;
  for (int f = 0; f < 45; ++f) {  // 1.5 s: the front reaches the far wall and climbs it
    const FrameResult r = advance_frame(sim);
    ASSERT_TRUE(r.ok) << r.message;
    const LiquidFrameStats& l = sim.stats.liquids[0];
    substeps += l.step.substeps;
    fastest = std::max(fastest, l.max_speed);
    EXPECT_LE(l.step.cfl, cfl * (1 + 1e-9)) << "frame " << f;
    EXPECT_LT(l.step.divergence, tolerance) << "frame " << f;
    EXPECT_EQ(l.step.unconverged, 0);
  }
  // The front moves at about sqrt(2 g H) = 3.1 m/s; CFL 0.5 over 5 cm cells: ~60 substeps a
  // second at the least.
  EXPECT_GT(fastest, 1.5);
  EXPECT_GT(substeps, 45);
  EXPECT_NEAR(sim.stats.liquids[0].volume / volume0, 1, 0.03);
}

TEST(LiquidWorld, DeterministicAndScrubsBackExactly) {
  const Scene scene = parse_scene(tank_scene(true), "dam.json");
  Simulation a(scene), b(scene);
  State saved;
  for (int f = 0; f < 20; ++f) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
    if (f == 9) saved = a.state;
  }
  EXPECT_EQ(hash_state(a.state), hash_state(b.state));
  const std::uint64_t at20 = hash_state(a.state);
  // Restored at frame 10 into a fresh workspace (the timeline's seek), stepped on.
  Simulation c(scene);
  c.state = saved;
  for (int f = 10; f < 20; ++f) ASSERT_TRUE(advance_frame(c).ok);
  EXPECT_EQ(hash_state(c.state), at20);
  // And the hash sees the liquid: frame 10's differs.
  EXPECT_NE(hash_state(saved), at20);
}

TEST(LiquidWorld, ABodyBesideALiquidMovesAsItDoesAlone) {
  const std::string body =
      R"("bodies": [{"name": "ball", "position": [3, 0, 2], "level": "rigid",
                     "material": {"mass": 1}}])";
  const Scene alone = parse_scene("{" + body + "}", "ball.json");
  Scene with = parse_scene(tank_scene(true), "dam.json");
  with.bodies = alone.bodies;
  Simulation a(alone), b(with);
  EXPECT_FALSE(a.world.has(SubsystemId::liquids));
  EXPECT_TRUE(a.state.liquids.empty());
  for (int f = 0; f < 10; ++f) {
    ASSERT_TRUE(advance_frame(a).ok);
    ASSERT_TRUE(advance_frame(b).ok);
  }
  EXPECT_EQ(a.state.q, b.state.q);
  EXPECT_EQ(a.state.v, b.state.v);
}

TEST(LiquidWorld, ANanInTheGridStopsTheRunNamingTheLiquid) {
  Simulation sim(parse_scene(tank_scene(false), "tank.json"));
  ASSERT_TRUE(advance_frame(sim).ok);
  const MacGrid& g = sim.model.liquids[0].grid;
  sim.state.liquids[0].velocity.u[2][static_cast<std::size_t>(g.index(5, 1, 2))] =
      std::numeric_limits<Real>::quiet_NaN();
  const FrameResult r = advance_frame(sim);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("liquid 'water'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("NaN"), std::string::npos) << r.message;
}

TEST(LiquidWorld, TheSnapshotDrawsTheSurfaceOrTheMarkersAndFramesTheDomain) {
  // By default a marker liquid draws its surface: one translucent mesh named after it, closed
  // around its markers.
  Simulation surface(parse_scene(tank_scene(true), "dam.json"));
  ASSERT_TRUE(advance_frame(surface).ok);
  const draw::Snapshot drawn = make_snapshot(surface);
  EXPECT_TRUE(drawn.points.empty());
  ASSERT_EQ(drawn.meshes.size(), 1u);
  EXPECT_EQ(drawn.meshes[0].name, surface.model.liquids[0].def.name);
  EXPECT_LT(drawn.meshes[0].material.opacity, 1.0f);
  EXPECT_GT(drawn.meshes[0].topology->triangles.size(), 100u);
  // display "markers": the markers as points.
  Scene scene = parse_scene(tank_scene(true), "dam.json");
  scene.liquids[0].display = LiquidDisplay::markers;
  Simulation sim(scene);
  ASSERT_TRUE(advance_frame(sim).ok);
  const draw::Snapshot snap = make_snapshot(sim);
  EXPECT_TRUE(snap.meshes.empty());
  ASSERT_EQ(snap.points.size(), 1u);
  EXPECT_EQ(snap.points[0].positions.size(), sim.state.liquids[0].markers.size());
  EXPECT_EQ(snap.points[0].layer, draw::Layer::scene);
  // 2 x 2 markers in each of the 6 x 10 cells of the column.
  EXPECT_EQ(sim.state.liquids[0].markers.size(), 240u);
  EXPECT_FLOAT_EQ(snap.focus.max.x(), 1.0f);
  EXPECT_FLOAT_EQ(snap.focus.max.z(), 0.6f);
  EXPECT_TRUE(snap.sections.empty());  // section "none", the default
}

TEST(LiquidWorld, ThePressureSectionIsHydrostaticAndTheSpeedSectionStill) {
  // Still water 0.25 m deep in cells 0.05 m tall: p = rho g (0.25 - z) at the Full cells'
  // centres, no value above the surface.
  for (const char* quantity : {"pressure", "speed"}) {
    Simulation sim(parse_scene(tank_scene(false, std::string(R"(, "section": ")") + quantity +
                                                     R"(", "section_axis": "y")"),
                               "tank.json"));
    for (int f = 0; f < 10; ++f) ASSERT_TRUE(advance_frame(sim).ok);
    const draw::Snapshot snap = make_snapshot(sim);
    ASSERT_EQ(snap.sections.size(), 1u);
    const draw::FieldSection& s = snap.sections[0];
    ASSERT_EQ(s.nu, 20);
    ASSERT_EQ(s.nv, 12);
    EXPECT_FLOAT_EQ(s.u.x(), 1.0f);
    EXPECT_FLOAT_EQ(s.v.z(), 0.6f);
    EXPECT_FLOAT_EQ(s.corner.y(), 0.05f);  // the one layer's middle
    EXPECT_EQ(s.label, std::string("water ") + quantity +
                           (quantity == std::string("pressure") ? " [Pa]" : " [m/s]"));
    for (int j = 0; j < s.nv; ++j) {
      for (int i = 0; i < s.nu; ++i) {
        const float value = s.values[static_cast<std::size_t>(i + s.nu * j)];
        const Real z = 0.05 * (j + 0.5);
        if (z > 0.25) {
          EXPECT_TRUE(std::isnan(value)) << i << " " << j;
        } else if (quantity == std::string("speed")) {
          EXPECT_LT(value, 1e-6);
        } else if (z < 0.2) {  // Full cells
          EXPECT_NEAR(value, 1000 * 9.81 * (0.25 - z), 0.01 * 1000 * 9.81 * 0.25) << i << " " << j;
        }
      }
    }
    if (quantity == std::string("pressure")) {
      EXPECT_NEAR(s.high, 1000 * 9.81 * (0.25 - 0.025), 0.01 * 1000 * 9.81 * 0.25);
    }
  }
}

}  // namespace
}  // namespace pbm

namespace pbm {
namespace {

// 16.6.1 by a track: an inflow in the left wall of a closed 2D tank whose velocity ramps from 0
// to 0.2 m/s over 1 s and holds adds A * integral v dt = A * (0.1 + 0.2 * 0.5) of liquid.
TEST(LiquidWorld, AnInflowTrackAddsTheVolumeItsVelocityCarries) {
  const std::string scene = R"({"name": "fill", "solver": {"fps": 30}, "liquids": [{
      "name": "water", "domain": {"min": [0, 0, 0], "max": [1, 0.1, 0.6]},
      "resolution": [20, 1, 12], "markers_per_axis": 3,
      "fluid": [{"box": {"min": [0, 0, 0], "max": [1, 0.1, 0.25]}}],
      "inflows": [{"box": {"min": [0, 0, 0.05], "max": [0.05, 0.1, 0.2]},
                   "velocity": [0.2, 0, 0]}]}],
      "tracks": [{"target": "liquids[0].inflow_velocity[0]",
                  "keys": [[0, 0], [1, 0.2]]}]})";
  Simulation sim(parse_scene(scene, "fill.json"));
  const Real v0 = sim.stats.liquids.at(0).volume;
  for (int f = 0; f < 45; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  // Inflow cross-section: 0.15 m tall (its 3 cells) x 0.1 m thick.
  const Real expected = 0.15 * 0.1 * (0.2 * 0.5 + 0.2 * 0.5);
  const Real added = sim.stats.liquids[0].volume - v0;
  std::printf("inflow track: expected %.5f m^3, added %.5f m^3\n", expected, added);
  EXPECT_NEAR(added / expected, 1, 0.05);
}

// 16.6.2 by a track: a uniform pressure on the surface of a closed tank moves no liquid and
// raises the pressure everywhere in it by itself (kinematic: p / rho). Markers: under a height
// field an applied pressure is not yet still (a flow of 0.15 m/s grows from rounding after 1 s;
// the issue's note).
TEST(LiquidWorld, ASurfacePressureTrackRaisesThePressureEverywhere) {
  const std::string base = R"({"name": "press", "solver": {"fps": 30}, "liquids": [{
      "name": "water", "domain": {"min": [0, 0, 0], "max": [1, 0.1, 0.6]},
      "resolution": [20, 1, 12],
      "fluid": [{"box": {"min": [0, 0, 0], "max": [1, 0.1, 0.25]}}]}])";
  Simulation plain(parse_scene(base + "}", "a.json"));
  Simulation pressed(parse_scene(
      base +
          R"(, "tracks": [{"target": "liquids[0].surface_pressure", "keys": [[0, 0], [0.5, 500]]}]})",
      "b.json"));
  for (int f = 0; f < 30; ++f) {
    ASSERT_TRUE(advance_frame(plain).ok);
    ASSERT_TRUE(advance_frame(pressed).ok);
  }
  const MacGrid& g = plain.model.liquids[0].grid;
  int checked = 0;
  for (int i = 1; i <= g.n.x(); ++i) {
    for (int k = 1; k <= 4; ++k) {  // Full cells, below the surface's cell
      const auto c = static_cast<std::size_t>(g.index(i, 1, k));
      EXPECT_NEAR(pressed.state.liquids[0].pressure[c] - plain.state.liquids[0].pressure[c], 0.5,
                  0.005);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 80);
  // Still to the solve's tolerance: |div u| < 1e-4 1/s over 5 cm cells leaves 5e-6 m/s.
  EXPECT_LT(pressed.stats.liquids[0].max_speed, 1e-5);
}

}  // namespace
}  // namespace pbm

namespace pbm {
namespace {

// Convergence under refinement: a 2D dam break's front (the rightmost marker) at 0.2 s with 16,
// 32 and 64 cells across a 1 m tank changes less at each refinement (0.028 m, then 0.019 m), and
// is near Martin and Moyce's measured front (Z = x / a ~ 1.9 at T = t sqrt(2 g / a) ~ 1.8 for a
// column a = 0.25 m wide: x ~ 0.475 m from the wall). Ours runs about 20% ahead (0.57 m at 64
// cells): an inviscid grid with free-slip walls, against an experiment whose gate took time to
// lift.
TEST(LiquidWorld, ADamBreaksFrontConvergesUnderRefinement) {
  Real front[3];
  const int across[3] = {16, 32, 64};
  for (int r = 0; r < 3; ++r) {
    const int n = across[r];
    const std::string scene =
        R"({"name": "dam", "solver": {"fps": 30}, "liquids": [{
        "name": "water", "domain": {"min": [0, 0, 0], "max": [1, 0.05, 0.5]},
        "resolution": [)" +
        std::to_string(n) + ", 1, " + std::to_string(n / 2) +
        R"(], "fluid": [{"box": {"min": [0, 0, 0], "max": [0.25, 0.05, 0.375]}}]}]})";
    Simulation sim(parse_scene(scene, "dam.json"));
    for (int f = 0; f < 6; ++f) ASSERT_TRUE(advance_frame(sim).ok);
    Real x = 0;
    for (const Vec3& m : sim.state.liquids[0].markers) x = std::max(x, m.x());
    front[r] = x;
  }
  std::printf("dam-break front at 0.2 s: %.4f, %.4f, %.4f m (16, 32, 64 cells)\n", front[0],
              front[1], front[2]);
  EXPECT_LT(std::abs(front[2] - front[1]), std::abs(front[1] - front[0]));
  EXPECT_NEAR(front[2], 0.475, 0.12);
}

}  // namespace
}  // namespace pbm
