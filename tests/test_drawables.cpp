// The renderer draws every drawable kind of draw/snapshot.h generically, so a new kind of object
// needs no renderer change: a snapshot made by hand (no engine) with primitives and a height
// field shows each in its material's colour where it projects and nothing where it does not;
// the unit shapes behind them have the surfaces they claim; and ui/ includes no engine header.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "drawable_geometry.h"
#include "osmesa_context.h"
#include "renderer.h"

namespace pbm {
namespace {

using draw::Vec3f;
namespace fs = std::filesystem;

constexpr int kWidth = 320, kHeight = 240;

// Straight down on the z = 0 plane from 12 m, +y up the image.
Camera top_view() {
  Camera c;
  c.position = {0, 0, 12};
  c.target = {0, 0, 0};
  c.up = {0, 1, 0};
  c.fov = 40;
  return c;
}

// Pixel (column, row from the top) where x lands in the image.
std::array<int, 2> project(const Camera& camera, const Vec3f& x) {
  const Eigen::Vector4f clip =
      perspective_matrix(camera.fov, static_cast<float>(kWidth) / kHeight, 0.05f, 500.0f) *
      view_matrix(camera) * x.homogeneous();
  const float nx = clip.x() / clip.w(), ny = clip.y() / clip.w();
  return {static_cast<int>(std::floor(0.5f * (nx + 1) * kWidth)),
          static_cast<int>(std::floor(0.5f * (1 - ny) * kHeight))};
}

struct Rgb {
  int r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

Rgb pixel(const std::vector<unsigned char>& rgb, const std::array<int, 2>& p) {
  const std::size_t k = 3 * (static_cast<std::size_t>(p[1]) * kWidth + p[0]);
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

// The hand-made scene: a capsule lying along x, a box turned 30 degrees, an upright cylinder, a
// sphere, and a height field with a bump, each in a colour of its own; no planes, no focus.
draw::Snapshot hand_made() {
  draw::Snapshot s;
  const Eigen::Matrix3f z_to_x =
      Eigen::AngleAxisf(0.5f * std::numbers::pi_v<float>, Vec3f::UnitY()).toRotationMatrix();
  s.primitives.push_back({.shape = draw::PrimitiveShape::capsule,
                          .center = {-3, 2, 0.5f},
                          .rotation = z_to_x,
                          .half_size = {0.4f, 0, 1.0f},
                          .material = {{0.1f, 0.8f, 0.15f}, 0.6f}});
  s.primitives.push_back({.shape = draw::PrimitiveShape::box,
                          .center = {2.5f, 2, 0.5f},
                          .rotation = Eigen::AngleAxisf(0.5236f, Vec3f::UnitZ()).toRotationMatrix(),
                          .half_size = {0.8f, 0.5f, 0.5f},
                          .material = {{0.15f, 0.25f, 0.9f}, 0.6f}});
  s.primitives.push_back({.shape = draw::PrimitiveShape::cylinder,
                          .center = {4, -1, 0.5f},
                          .half_size = {0.4f, 0, 0.5f},
                          .material = {{0.1f, 0.7f, 0.8f}, 0.6f}});
  s.primitives.push_back({.shape = draw::PrimitiveShape::sphere,
                          .center = {0, 0.5f, 0.5f},
                          .half_size = {0.5f, 0, 0},
                          .material = {{0.8f, 0.1f, 0.7f}, 0.6f}});
  draw::HeightField field{.origin = {-2, -4, 0}, .cell = {0.1f, 0.1f}, .nx = 41, .ny = 21};
  for (int j = 0; j < field.ny; ++j) {
    for (int i = 0; i < field.nx; ++i) {
      const float x = -2 + 0.1f * i, y = -4 + 0.1f * j;
      field.heights.push_back(0.4f * std::exp(-(x * x + (y + 3) * (y + 3)) / 0.5f));
    }
  }
  field.material = {{0.9f, 0.45f, 0.1f}, 0.9f};
  s.height_fields.push_back(field);
  return s;
}

TEST(Drawables, AHandMadeSnapshotOfPrimitivesAndAHeightFieldIsDrawn) {
  OsmesaContext context;
  Renderer renderer(context.functions());
  RenderOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.shadows = false;
  const Camera camera = top_view();
  std::vector<unsigned char> empty, drawn;
  renderer.render(draw::Snapshot{}, camera, options);
  renderer.read_rgb(empty);
  renderer.render(hand_made(), camera, options);
  renderer.read_rgb(drawn);

  auto at = [&](const Vec3f& x) { return pixel(drawn, project(camera, x)); };
  auto background = [&](const Vec3f& x) {
    const auto p = project(camera, x);
    return pixel(drawn, p) == pixel(empty, p);
  };
  auto print = [](const char* what, const Rgb& c) {
    std::printf("%-22s (%3d, %3d, %3d)\n", what, c.r, c.g, c.b);
  };
  // Each at its centre's top, in its colour (lit, so by its strongest channels).
  const Rgb capsule = at({-3, 2, 0.9f}), box = at({2.5f, 2, 1}), cylinder = at({4, -1, 1}),
            sphere = at({0, 0.5f, 1}), field = at({0, -3, 0.4f});
  print("capsule", capsule);
  print("box", box);
  print("cylinder", cylinder);
  print("sphere", sphere);
  print("height field", field);
  EXPECT_TRUE(capsule.g > capsule.r + 40 && capsule.g > capsule.b + 40);
  EXPECT_TRUE(box.b > box.r + 40 && box.b > box.g + 40);
  EXPECT_TRUE(cylinder.g > cylinder.r + 40 && cylinder.b > cylinder.r + 40);
  EXPECT_TRUE(sphere.r > sphere.g + 40 && sphere.b > sphere.g + 40);
  EXPECT_TRUE(field.r > field.g + 20 && field.g > field.b + 20);
  // The capsule's ends are hemispheres moved out by its half length (1 m) along x: its surface
  // 0.24 m past each segment end is drawn, 0.56 m past it is not.
  for (const float side : {-1.0f, 1.0f}) {
    const float in = -3 + side * 1.24f, out = -3 + side * 1.56f;
    const Rgb end = at({in, 2, 0.5f + std::sqrt(0.16f - 0.24f * 0.24f)});
    print("capsule end", end);
    EXPECT_TRUE(end.g > end.r + 40 && end.g > end.b + 40) << side;
    EXPECT_TRUE(background({out, 2, 0.5f})) << side;
  }
  // The box is turned: its corner's direction is covered, the unturned corner is not.
  const Vec3f corner_turned =
      Vec3f(2.5f, 2, 1) + Eigen::AngleAxisf(0.5236f, Vec3f::UnitZ()) * Vec3f(0.7f, 0.4f, 0);
  EXPECT_FALSE(background(corner_turned));
  EXPECT_TRUE(background({2.5f + 0.75f, 2 - 0.45f, 1}));
  // Nothing between them, nor beside the height field (whose edge is at x = 2).
  for (const Vec3f& x : {Vec3f(0, 2.5f, 0), Vec3f(-4.5f, -1.5f, 0), Vec3f(2.3f, -3, 0),
                         Vec3f(1, -1.5f, 0), Vec3f(4, 1, 0)}) {
    EXPECT_TRUE(background(x)) << x.transpose();
  }

  // Scene-layer solids cast shadows: where the sphere's shadow falls on the height field, the
  // field is darker with shadows than without. The key light (renderer.cpp) points along k.
  const Vec3f k = Vec3f(0.45f, -0.35f, 0.82f).normalized();
  const Vec3f shadow(0, -3, 0.4f);  // the bump's top
  draw::Snapshot shadowed = hand_made();
  shadowed.primitives[3].center = shadow + (1.2f / k.z()) * k;  // 1.2 m above it, towards k
  std::vector<unsigned char> lit, dark;
  renderer.render(shadowed, camera, options);
  renderer.read_rgb(lit);
  options.shadows = true;
  renderer.render(shadowed, camera, options);
  renderer.read_rgb(dark);
  const Rgb a = pixel(lit, project(camera, shadow)), b = pixel(dark, project(camera, shadow));
  print("field, no shadows", a);
  print("field, shadows", b);
  EXPECT_LT(b.r + b.g + b.b, a.r + a.g + a.b - 60);
}

// The unit shapes are the surfaces they claim once scaled and stretched as the shaders do
// (drawable_geometry.h): a capsule of radius r and half length h is every point at r from the
// segment between (0, 0, -h) and (0, 0, h), and reaches h + r.
TEST(Drawables, UnitShapesHaveTheirSurfaces) {
  const float r = 0.3f, h = 0.8f;
  const std::vector<float> capsule = unit_primitive_vertices(draw::PrimitiveShape::capsule);
  ASSERT_EQ(capsule.size() % kPrimitiveFloats, 0u);
  float worst = 0, top = -1e9f, bottom = 1e9f;
  for (std::size_t v = 0; v < capsule.size(); v += kPrimitiveFloats) {
    const Vec3f p(capsule[v], capsule[v + 1], capsule[v + 2]);
    const Vec3f n(capsule[v + 3], capsule[v + 4], capsule[v + 5]);
    const float s = capsule[v + 6];
    ASSERT_TRUE(s == 1 || s == -1);
    EXPECT_GE(s * p.z(), -1e-6f) << "a vertex moved with the wrong hemisphere";
    const Vec3f x = r * p + Vec3f(0, 0, h * s);
    const Vec3f axis_point(0, 0, std::clamp(x.z(), -h, h));
    worst = std::max(worst, std::abs((x - axis_point).norm() - r));
    EXPECT_LT((n - p).norm(), 1e-6f);  // the unit sphere's normal, unchanged by the stretch
    top = std::max(top, x.z());
    bottom = std::min(bottom, x.z());
  }
  EXPECT_LT(worst, 1e-6f);
  EXPECT_FLOAT_EQ(top, h + r);
  EXPECT_FLOAT_EQ(bottom, -h - r);
  const PrimitiveTransform t =
      primitive_transform({.shape = draw::PrimitiveShape::capsule, .half_size = {r, 0, h}});
  EXPECT_EQ(t.scale, Vec3f::Constant(r));
  EXPECT_EQ(t.stretch, h);
  // Box: the cube's corners; cylinder: radius 1 between z = -1 and 1.
  const std::vector<float> box = unit_primitive_vertices(draw::PrimitiveShape::box);
  EXPECT_EQ(box.size(), 36u * kPrimitiveFloats);
  for (std::size_t v = 0; v < box.size(); v += kPrimitiveFloats) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::abs(box[v + k]), 1.0f);
  }
  const std::vector<float> cylinder = unit_primitive_vertices(draw::PrimitiveShape::cylinder);
  for (std::size_t v = 0; v < cylinder.size(); v += kPrimitiveFloats) {
    const float radial = std::hypot(cylinder[v], cylinder[v + 1]);
    EXPECT_TRUE(std::abs(cylinder[v + 2]) == 1 || std::abs(radial - 1) < 1e-6f);
    EXPECT_LE(radial, 1 + 1e-6f);
  }
  // A capsule turned onto x spans its length along x in its bounds.
  const Eigen::Matrix3f z_to_x =
      Eigen::AngleAxisf(0.5f * std::numbers::pi_v<float>, Vec3f::UnitY()).toRotationMatrix();
  const draw::Bounds b = primitive_bounds({.shape = draw::PrimitiveShape::capsule,
                                           .center = {1, 0, 0},
                                           .rotation = z_to_x,
                                           .half_size = {r, 0, h}});
  EXPECT_NEAR(b.max.x(), 1 + h + r, 1e-6f);
  EXPECT_NEAR(b.max.z(), r, 1e-6f);
}

// A tilted height field h = a x has the normal (-a, 0, 1) / |.| at every vertex, border too.
TEST(Drawables, HeightFieldNormalsFollowTheSlope) {
  const float a = 0.5f;
  draw::HeightField f{.origin = {1, 2, 3}, .cell = {0.2f, 0.3f}, .nx = 5, .ny = 4};
  for (int j = 0; j < f.ny; ++j) {
    for (int i = 0; i < f.nx; ++i) f.heights.push_back(a * 0.2f * static_cast<float>(i));
  }
  std::vector<float> v;
  height_field_vertices(f, v);
  ASSERT_EQ(v.size(), static_cast<std::size_t>(kSolidFloats * 20));
  const Vec3f expected = Vec3f(-a, 0, 1).normalized();
  for (int k = 0; k < 20; ++k) {
    const Vec3f n(v[kSolidFloats * k + 3], v[kSolidFloats * k + 4], v[kSolidFloats * k + 5]);
    EXPECT_LT((n - expected).norm(), 1e-5f) << k;
  }
  // Vertex (i, j) = 4 + 5 * 3 at origin + (i dx, j dy, h).
  EXPECT_EQ(Vec3f(v[kSolidFloats * 19], v[kSolidFloats * 19 + 1], v[kSolidFloats * 19 + 2]),
            Vec3f(1 + 4 * 0.2f, 2 + 3 * 0.3f, 3 + a * 0.8f));
  EXPECT_EQ(height_field_triangles(5, 4).size(), 2u * 4 * 3);
}

// The renderer depends on draw/snapshot.h alone (ui/CMakeLists.txt links no engine): every
// quoted include in ui/ names a file of ui/ itself or of draw/.
std::vector<std::string> foreign_includes(const std::string& text) {
  static const std::regex include(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<std::string> out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, include)) continue;
    const std::string path = m[1];
    if (path.find('/') != std::string::npos && !path.starts_with("draw/")) out.push_back(path);
  }
  return out;
}

TEST(Drawables, UiIncludesNoEngineHeader) {
  // The check can fail: an engine include is found.
  EXPECT_EQ(foreign_includes("#include \"renderer.h\"\n#include \"sim/snapshot.h\"\n"),
            std::vector<std::string>{"sim/snapshot.h"});
  EXPECT_EQ(foreign_includes("  #  include \"core/types.h\""),
            std::vector<std::string>{"core/types.h"});
  EXPECT_TRUE(foreign_includes("#include \"draw/snapshot.h\"\n#include <Eigen/Core>\n").empty());
  int files = 0;
  for (const auto& entry : fs::directory_iterator(std::string(PBM_SOURCE_DIR) + "/ui")) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".h" && ext != ".cpp") continue;
    ++files;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const std::string& path : foreign_includes(text)) {
      ADD_FAILURE() << entry.path().filename().string() << " includes \"" << path << "\"";
    }
  }
  EXPECT_GT(files, 10);
}

}  // namespace
}  // namespace pbm
