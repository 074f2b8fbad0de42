// What a renderer needs of one moment, as plain drawables (docs/architecture.md, "Snapshot").
//
// The engine fills a Snapshot from (Model, State); the renderer (ui/), the studio's picking and
// the exporters read it and nothing else: this header includes no engine header, so a renderer
// never depends on the engine's types, and a new subsystem draws itself by adding drawables of
// these kinds (a figure's segments as capsules and boxes, a liquid's surface as a height field)
// without a renderer change. Plain data in float, copyable across threads. Constant geometry
// (a body's triangles, a mesh obstacle's vertices) is shared between snapshots, not copied.
// Every field has a default, so drawables are made with designated initializers.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace pbm::draw {

using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Mat3f = Eigen::Matrix3f;

// The picture itself, or the editor's overlays (spring lines, constraint markers, the finite
// elements' wireframe): `pbm render` draws overlays only with --overlays, the studio by its View
// menu. Overlay lines and points are drawn over everything (a marker inside a body stays
// visible); overlay solids and the meshes' edges are hidden by what is in front of them.
// Scene-layer solids cast shadows; overlay ones do not.
enum class Layer { scene, overlay };

struct Material {
  Vec3f color{0.8f, 0.3f, 0.3f};  // linear RGB in [0, 1]
  float roughness = 0.5f;         // 0 = mirror-like highlight, 1 = matte
  // Below 1: drawn after everything opaque, blended over it without writing depth (a liquid's
  // surface shows what lies under it); it casts no shadow.
  float opacity = 1.0f;
};

// Triangles and element edges over a mesh's vertices: constant while time runs.
struct MeshTopology {
  std::vector<std::array<int, 3>> triangles{};  // counter-clockwise seen from outside
  std::vector<std::array<int, 2>> edges{};      // wireframe (overlay layer); may be empty
};

enum class Shading {
  smooth,  // normals averaged at the vertices, recomputed every frame (deforming bodies)
  flat     // one normal per triangle (polyhedral obstacles)
};

// A triangle mesh: vertex i is drawn at rotation * positions[i] + offset [m], world frame.
struct Mesh {
  std::string name{};
  int pick = -1;  // what a click selects: a body index, or -1 (not pickable)
  std::shared_ptr<const std::vector<Vec3f>> positions{};
  std::shared_ptr<const MeshTopology> topology{};
  Material material{};
  Shading shading = Shading::smooth;
  Mat3f rotation = Mat3f::Identity();
  Vec3f offset = Vec3f::Zero();
};

// An infinite plane drawn as a finite gridded quad of `size` around `point`.
struct Plane {
  Vec3f point = Vec3f::Zero();
  Vec3f normal{0, 0, 1};  // unit
  Vec2f size{20, 20};     // drawn extent [m]
};

// Solids given by a few numbers. `half_size` is per shape:
//   box       half extents along the local axes
//   sphere    x = radius
//   capsule   x = radius, z = half the length of the segment between the two hemispheres' centres
//   cylinder  x = radius, z = half the height
// The local z axis is the long axis of capsules and cylinders.
enum class PrimitiveShape { box, sphere, capsule, cylinder };
struct Primitive {
  PrimitiveShape shape = PrimitiveShape::box;
  Vec3f center = Vec3f::Zero();        // world [m]
  Mat3f rotation = Mat3f::Identity();  // local -> world
  Vec3f half_size{1, 1, 1};            // [m], see above
  Material material{{0.55f, 0.55f, 0.6f}, 0.8f};
  int pick = -1;
  // A figure's segment (what the mouse spring grabs: its figure and segment index), or -1.
  int figure = -1, segment = -1;
  Layer layer = Layer::scene;
};

// Regular grid of heights over the plane z = origin.z: vertex (i, j) at origin + (i dx, j dy,
// heights[j nx + i]). A liquid's surface, a terrain.
struct HeightField {
  Vec3f origin = Vec3f::Zero();
  Vec2f cell{1, 1};  // dx, dy [m]
  int nx = 0, ny = 0;
  std::vector<float> heights{};  // nx * ny, row by row [m]
  Material material{};
  Layer layer = Layer::scene;
};

// Line segments: segment k runs from points[2k] to points[2k + 1] in colors[k].
struct Lines {
  std::vector<Vec3f> points{};
  std::vector<Vec3f> colors{};
  bool end_points = false;   // also a dot at each end (springs, constraint ends)
  float end_point_size = 7;  // [pixels]
  Layer layer = Layer::overlay;
};

struct Points {
  std::vector<Vec3f> positions{};
  std::vector<Vec3f> colors{};  // one per point
  float size = 6;               // [pixels]
  Layer layer = Layer::overlay;
};

// A scalar field sampled over a rectangle in space (a liquid's pressure or speed across a
// section of its grid), drawn in false colour from `low` (blue) to `high` (red) with a colour bar
// naming it: sample (i, j) at corner + (i + 0.5) / nu * u + (j + 0.5) / nv * v; a NaN sample
// (no liquid there) is not drawn.
struct FieldSection {
  std::string label{};  // what the colour bar names, with its unit: "pressure [Pa]"
  Vec3f corner = Vec3f::Zero();
  Vec3f u{1, 0, 0}, v{0, 1, 0};  // the rectangle's edges [m]
  int nu = 0, nv = 0;
  std::vector<float> values{};  // nu * nv, row by row (i fastest)
  float low = 0, high = 1;      // the colour bar's range
  Layer layer = Layer::scene;
};

// Where the scene's camera is at the snapshot's time (its tracks applied).
struct CameraView {
  Vec3f position{6, -8, 4};
  Vec3f target = Vec3f::Zero();
  Vec3f up{0, 0, 1};
  float fov = 40;  // vertical field of view [degrees]
};

struct Bounds {
  Vec3f min = Vec3f::Constant(1e30f), max = Vec3f::Constant(-1e30f);
  bool empty() const { return !(min.x() <= max.x()); }
  void add(const Vec3f& x) {
    min = min.cwiseMin(x);
    max = max.cwiseMax(x);
  }
};

struct Snapshot {
  double time = 0;  // [s]
  std::vector<Mesh> meshes{};
  std::vector<Plane> planes{};
  std::vector<Primitive> primitives{};
  std::vector<HeightField> height_fields{};
  std::vector<Lines> lines{};
  std::vector<Points> points{};
  std::vector<FieldSection> sections{};
  std::optional<CameraView> camera{};  // absent: the scene has none (views frame `focus`)
  Bounds focus{};                      // what an automatic camera frames: the moving objects
};

}  // namespace pbm::draw
