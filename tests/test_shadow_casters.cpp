// The shadow pass's coarse copy of a dense body (ui/shadow_casters.h): within its triangle
// budget, still a closed surface of the same shape.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

#include "shadow_casters.h"

namespace pbm {
namespace {

struct Sphere {
  std::vector<Eigen::Vector3f> positions;
  std::vector<std::array<int, 3>> triangles;
};

// A latitude-longitude sphere of radius r: 2 + (rings-1)·segments vertices, counter-clockwise
// seen from outside.
Sphere lat_long_sphere(int rings, int segments, float r) {
  Sphere s;
  const float pi = std::numbers::pi_v<float>;
  s.positions.emplace_back(0.0f, 0.0f, r);
  for (int i = 1; i < rings; ++i) {
    const float theta = pi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j < segments; ++j) {
      const float phi = 2 * pi * static_cast<float>(j) / static_cast<float>(segments);
      s.positions.emplace_back(r * std::sin(theta) * std::cos(phi),
                               r * std::sin(theta) * std::sin(phi), r * std::cos(theta));
    }
  }
  s.positions.emplace_back(0.0f, 0.0f, -r);
  const int south = static_cast<int>(s.positions.size()) - 1;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    s.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    s.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      s.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      s.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  }
  return s;
}

// Enclosed volume by the divergence theorem: Σ (a · (b × c)) / 6.
double volume(const std::vector<Eigen::Vector3f>& p, const std::vector<std::array<int, 3>>& t) {
  double v = 0;
  for (const auto& f : t) {
    const Eigen::Vector3d a = p[f[0]].cast<double>(), b = p[f[1]].cast<double>(),
                          c = p[f[2]].cast<double>();
    v += a.dot(b.cross(c));
  }
  return v / 6;
}

TEST(ShadowCasters, SmallMeshesAreKeptAsTheyAre) {
  const Sphere s = lat_long_sphere(32, 64, 1.0f);
  ASSERT_LE(s.triangles.size(), 4096u);
  EXPECT_EQ(shadow_caster_triangles(s.positions, s.triangles, 4096), s.triangles);
}

TEST(ShadowCasters, DenseSphereFitsTheBudgetAndKeepsItsVolume) {
  const Sphere s = lat_long_sphere(128, 128, 0.5f);  // 32,512 triangles, like 16k nodes
  const auto coarse = shadow_caster_triangles(s.positions, s.triangles, 4096);
  EXPECT_LE(coarse.size(), 4096u);
  EXPECT_GE(coarse.size(), 1024u) << "coarser than the budget needs";
  const double exact = 4.0 / 3.0 * std::numbers::pi * 0.125;
  EXPECT_NEAR(volume(s.positions, s.triangles) / exact, 1.0, 1e-3);
  // Chords of a ~1/40 cell on a unit-radius scale cut off well under 1% of the volume.
  EXPECT_NEAR(volume(s.positions, coarse) / exact, 1.0, 0.01);
  std::printf("coarse: %zu triangles, volume ratio %.5f\n", coarse.size(),
              volume(s.positions, coarse) / exact);
}

TEST(ShadowCasters, CoarseSurfaceStaysClosed) {
  // Every directed edge a→b of a closed oriented surface is matched by one b→a: a hole would
  // let light through the shadow.
  const Sphere s = lat_long_sphere(128, 128, 0.5f);
  const auto coarse = shadow_caster_triangles(s.positions, s.triangles, 4096);
  std::map<std::pair<int, int>, int> balance;
  for (const auto& f : coarse) {
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  }
  int open = 0;
  for (const auto& [edge, count] : balance) open += count != 0;
  EXPECT_EQ(open, 0);
}

}  // namespace
}  // namespace pbm
