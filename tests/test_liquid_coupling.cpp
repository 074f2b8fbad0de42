// Bodies in a liquid (sim/liquid_body_loads.h, 16.4), in a height-field tank (coupled one way:
// the liquid does not see the bodies, the book's assumption; tests/test_liquid_two_way.cpp has
// the bodies that displace it): the pressure integrated over a body's surface is Archimedes'
// rho g V_submerged at every depth and converges to the sphere's under refinement of its mesh; a
// box of half the liquid's density floats with half its height submerged, a denser one sinks to
// the floor; a sinking ball reaches the terminal velocity of its quadratic drag; a light ball
// released under water rises, bobs and floats at the draft its density gives, without the
// stability guard refusing the buoyancy's work; bit-identical runs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "scene/scene_json.h"
#include "sim/simulation.h"

namespace pbm {
namespace {

constexpr Real kG = 9.81, kRho = 1000;

struct Tank {
  Vec3 min, max;
  int nx, ny, nz;
  Real depth;
  std::string surface = "height_field";
  std::string coupling = "two_way";
};

std::string vec(const Vec3& v) {
  return "[" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " + std::to_string(v.z()) +
         "]";
}

// A rigid superquadric of scale a0 and aspects (a1, a2, a3), squareness eps, at `position`.
std::string body_json(Real a0, const Vec3& aspect, Real eps, Real mass, const Vec3& position,
                      int rings) {
  return R"({"name": "b", "level": "rigid", "shape": {"kind": "superquadric", "q_s": {"a0": )" +
         std::to_string(a0) + R"(, "a1": )" + std::to_string(aspect.x()) + R"(, "a2": )" +
         std::to_string(aspect.y()) + R"(, "a3": )" + std::to_string(aspect.z()) + R"(, "eps1": )" +
         std::to_string(eps) + R"(, "eps2": )" + std::to_string(eps) + R"(}}, "position": )" +
         vec(position) + R"(, "tessellation": {"kind": "triangles", "rings": )" +
         std::to_string(rings) + R"(, "segments": )" + std::to_string(rings) +
         R"(}, "material": {"mass": )" + std::to_string(mass) + R"(, "damping": 0}})";
}

std::string scene_json(const Tank& t, const std::string& body, Real drag, Real dt = 0.005) {
  Vec3 top = t.max;
  top.z() = t.min.z() + t.depth;
  return R"({"name": "tank", "solver": {"fps": 30, "dt": )" + std::to_string(dt) +
         R"(, "integrator": "rk4"}, "bodies": [)" + body + R"(],
      "obstacles": [{"name": "floor", "kind": "plane", "point": )" +
         vec(t.min) +
         R"(, "normal": [0, 0, 1], "size": [4, 4], "elasticity": 20000, "friction": 0.3}],
      "liquids": [{"name": "water", "domain": {"min": )" +
         vec(t.min) + R"(, "max": )" + vec(t.max) + R"(}, "resolution": [)" + std::to_string(t.nx) +
         ", " + std::to_string(t.ny) + ", " + std::to_string(t.nz) + R"(], "surface": ")" +
         t.surface + R"(", "coupling": ")" + t.coupling + R"(", "drag": )" + std::to_string(drag) +
         R"(, "fluid": [{"box": {"min": )" + vec(t.min) + R"(, "max": )" + vec(top) + "}}]}]}";
}

// The volume the body's surface triangles enclose [m^3].
Real mesh_volume(const Simulation& sim) {
  const BodyWorkspace& bw = sim.ws.bodies[0];
  Real v = 0;
  for (const auto& t : sim.model.bodies[0].tessellation.triangles) {
    v += bw.x[t[0]].dot(bw.x[t[1]].cross(bw.x[t[2]])) / 6;
  }
  return v;
}

// A sphere's cap below a plane `d` above its lowest point [m^3].
Real cap_volume(Real r, Real d) {
  d = std::clamp(d, 0.0, 2 * r);
  return std::numbers::pi * d * d * (3 * r - d) / 3;
}

const Tank kTank{{0, 0, 0}, {1, 1, 0.8}, 16, 16, 16, 0.47};
// The book's assumption (16.4): the bodies feel the liquid, the liquid does not see them.
const Tank kOneWayTank{{0, 0, 0}, {1, 1, 0.8}, 16, 16, 16, 0.47, "height_field", "one_way"};

TEST(LiquidCoupling, PressureOverTheSurfaceIsArchimedesAtEveryDepth) {
  const Real r = 0.1;
  for (int rings : {12, 24}) {
    Real worst = 0;
    for (Real centre : {0.2, 0.4, 0.44, 0.47, 0.5, 0.55, 0.62}) {
      const std::string body = body_json(r, Vec3::Ones(), 1, 1, Vec3(0.5, 0.5, centre), rings);
      Simulation sim(parse_scene(scene_json(kTank, body, 0), "tank.json"));
      const Real v_mesh = mesh_volume(sim);
      const Real v_sphere = 4 * std::numbers::pi * r * r * r / 3;
      // The mesh's own submerged volume, from the sphere's cap scaled by the mesh's shrinkage.
      const Real submerged = cap_volume(r, kTank.depth - (centre - r)) * v_mesh / v_sphere;
      const Vec3 f = sim.stats.liquids.at(0).body_force;
      EXPECT_NEAR(f.x(), 0, 1e-9);
      EXPECT_NEAR(f.y(), 0, 1e-9);
      const Real expected = kRho * kG * submerged;
      if (centre + r < kTank.depth) {
        // Wholly under the surface: the rule is exact for a pressure linear in depth.
        EXPECT_NEAR(f.z() / (kRho * kG * v_mesh), 1, 1e-6) << "centre " << centre;
      }
      if (expected > 0) worst = std::max(worst, std::abs(f.z() / expected - 1));
      if (centre - r > kTank.depth) {
        EXPECT_EQ(f.z(), 0);
      }
    }
    std::printf("rings %d: worst relative error of the buoyancy %.4f\n", rings, worst);
    EXPECT_LT(worst, rings == 12 ? 0.1 : 0.03) << "rings " << rings;
  }
}

TEST(LiquidCoupling, AHalfDensityBoxFloatsHalfSubmergedADenserOneSinks) {
  // A flat box 0.3 x 0.3 x 0.1 m (metacentrically stable flat at any density).
  const Real a0 = 0.1, half_height = 0.05;
  const Vec3 aspect(1.5, 1.5, 0.5);
  for (Real density : {0.5, 2.0}) {
    // Its mass from its mesh's volume, found on a first build.
    const std::string probe_body = body_json(a0, aspect, 0.2, 1, Vec3(0.5, 0.5, 0.6), 16);
    const Real v =
        mesh_volume(Simulation(parse_scene(scene_json(kOneWayTank, probe_body, 1), "t.json")));
    const std::string body =
        body_json(a0, aspect, 0.2, density * kRho * v, Vec3(0.5, 0.5, 0.6), 16);
    Simulation sim(parse_scene(scene_json(kOneWayTank, body, 1), "tank.json"));
    // Its height over the 2nd and the 5th second: the bobbing's range, and its mean.
    Real early_lo = 1e300, early_hi = -1e300, late_lo = 1e300, late_hi = -1e300, late_sum = 0;
    for (int f = 0; f < 150; ++f) {
      const FrameResult res = advance_frame(sim);
      ASSERT_TRUE(res.ok) << "density " << density << " frame " << f << ": " << res.message;
      const Real z = sim.state.q[sim.model.bodies[0].q_offset + 2];
      if (f >= 30 && f < 60) {
        early_lo = std::min(early_lo, z);
        early_hi = std::max(early_hi, z);
      } else if (f >= 120) {
        late_lo = std::min(late_lo, z);
        late_hi = std::max(late_hi, z);
        late_sum += z;
      }
    }
    const Real z = sim.state.q[sim.model.bodies[0].q_offset + 2];
    if (density < 1) {
      // Half its height under the surface: its centre at the surface, within 5% of its height.
      // The one-way liquid radiates no waves, so only the quadratic drag damps its bobbing, the
      // more slowly the smaller it gets: its range at least halves from the 2nd to the 5th s.
      const Real mean = late_sum / 30;
      std::printf("bobbing: range %.4f m in the 2nd second, %.4f m in the 5th, mean %.4f m\n",
                  early_hi - early_lo, late_hi - late_lo, mean);
      EXPECT_NEAR(mean, kOneWayTank.depth, 0.05 * 2 * half_height) << "density " << density;
      EXPECT_LT(late_hi - late_lo, 0.5 * (early_hi - early_lo));
    } else {
      EXPECT_NEAR(z, half_height, 0.01) << "density " << density;  // on the floor
    }
  }
}

TEST(LiquidCoupling, ASinkingBallReachesItsDragsTerminalVelocity) {
  const Tank deep{{0, 0, 0}, {1, 1, 4}, 8, 8, 32, 3.9};
  const Real r = 0.05, cd = 0.5;
  const std::string probe_body = body_json(r, Vec3::Ones(), 1, 1, Vec3(0.5, 0.5, 3.7), 16);
  Simulation probe(parse_scene(scene_json(deep, probe_body, cd), "deep.json"));
  const Real v = mesh_volume(probe);
  // Its frontal area: the mesh's projection on the horizontal plane.
  Real frontal = 0;
  const BodyWorkspace& bw = probe.ws.bodies[0];
  for (const auto& t : probe.model.bodies[0].tessellation.triangles) {
    const Real az = 0.5 * (bw.x[t[1]] - bw.x[t[0]]).cross(bw.x[t[2]] - bw.x[t[0]]).z();
    frontal += std::max(0.0, -az);
  }
  const Real m = 3 * kRho * v;
  const Real terminal = std::sqrt(2 * (m - kRho * v) * kG / (kRho * cd * frontal));
  Simulation sim(parse_scene(
      scene_json(deep, body_json(r, Vec3::Ones(), 1, m, Vec3(0.5, 0.5, 3.7), 16), cd), "d.json"));
  for (int f = 0; f < 36; ++f) ASSERT_TRUE(advance_frame(sim).ok);
  const Real vz = sim.state.v[sim.model.bodies[0].v_offset + 2];
  std::printf("terminal velocity %.4f m/s, reached %.4f m/s\n", terminal, -vz);
  EXPECT_NEAR(-vz / terminal, 1, 0.01);
}

TEST(LiquidCoupling, ALightBallReleasedUnderWaterFloatsAtItsDraft) {
  const Real r = 0.08, density = 0.2;
  const std::string probe_body = body_json(r, Vec3::Ones(), 1, 1, Vec3(0.5, 0.5, 0.25), 16);
  const Real v = mesh_volume(Simulation(parse_scene(scene_json(kTank, probe_body, 1), "t.json")));
  const std::string body =
      body_json(r, Vec3::Ones(), 1, density * kRho * v, Vec3(0.5, 0.5, 0.25), 16);
  const Scene scene = parse_scene(scene_json(kTank, body, 1), "tank.json");
  Simulation sim(scene), again(scene);
  for (int f = 0; f < 240; ++f) {
    const FrameResult res = advance_frame(sim);
    ASSERT_TRUE(res.ok) << "frame " << f << ": " << res.message;
    ASSERT_TRUE(advance_frame(again).ok);
  }
  EXPECT_EQ(hash_state(sim.state), hash_state(again.state));
  // The draft d of a sphere displacing its own weight: cap(d) = density V, by bisection.
  Real lo = 0, hi = 2 * r;
  for (int k = 0; k < 60; ++k) {
    const Real mid = 0.5 * (lo + hi);
    (cap_volume(r, mid) < density * cap_volume(r, 2 * r) ? lo : hi) = mid;
  }
  const Real z = sim.state.q[sim.model.bodies[0].q_offset + 2];
  EXPECT_NEAR(z, kTank.depth - lo + r, 0.05 * r);
}

}  // namespace
}  // namespace pbm
