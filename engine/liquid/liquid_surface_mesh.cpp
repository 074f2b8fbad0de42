#include "liquid/liquid_surface_mesh.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "liquid/cell_labels.h"

namespace pbm {

namespace {

// The narrow band's half width in voxels: OpenVDB's default, enough for the filter's stencils.
constexpr float kHalfWidth = 3.0f;

// The markers as the particle list ParticlesToLevelSet reads (its documented interface). A 2D
// liquid's markers lie on its middle plane: they are repeated across the thin axis at their own
// spacing, so its surface is a slab as thick as the grid.
class MarkerList {
 public:
  using PosType = openvdb::Vec3R;  // what ParticlesToLevelSet's partitioner reads
  MarkerList(const LiquidModel& model, const std::vector<Vec3>& markers, Real spacing, Real radius)
      : markers_(markers), radius_(radius) {
    if (model.thin_axis >= 0) {
      const int a = model.thin_axis;
      const Real thickness = model.grid.h[a];
      const int copies = std::max(1, static_cast<int>(std::lround(thickness / spacing)));
      for (int k = 0; k < copies; ++k) {
        Vec3 d = Vec3::Zero();
        d[a] = model.grid.origin[a] + (k + 0.5) * thickness / copies;
        offsets_.push_back(d);
      }
      thin_axis_ = a;
    } else {
      offsets_.push_back(Vec3::Zero());
    }
  }
  std::size_t size() const { return markers_.size() * offsets_.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& xyz) const {
    Vec3 x = markers_[n / offsets_.size()];
    if (thin_axis_ >= 0) x[thin_axis_] = offsets_[n % offsets_.size()][thin_axis_];
    xyz = openvdb::Vec3R(x.x(), x.y(), x.z());
  }
  void getPosRad(std::size_t n, openvdb::Vec3R& xyz, openvdb::Real& radius) const {
    getPos(n, xyz);
    radius = radius_;
  }

 private:
  const std::vector<Vec3>& markers_;
  Real radius_;
  std::vector<Vec3> offsets_;
  int thin_axis_ = -1;
};

openvdb::FloatGrid::Ptr markers_level_set(const LiquidModel& model, const LiquidState& state,
                                          Real voxel) {
  const MacGrid& g = model.grid;
  Real cell = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (a != model.thin_axis) cell = std::min(cell, g.h[a]);
  }
  const Real spacing = cell / model.def.markers_per_axis;
  // Spheres of one spacing's radius overlap their neighbours along the diagonals (sqrt(3) / 2 of
  // a spacing away) so the union has no holes; the liquid a marker stands for ends half a spacing
  // beyond it, so the union is then eroded by the other half.
  const Real radius = spacing;
  auto grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, kHalfWidth);
  openvdb::tools::ParticlesToLevelSet<openvdb::FloatGrid> raster(*grid);
  raster.setRmin(0.5);  // in voxels: no marker is dropped as too small for the grid
  raster.rasterizeSpheres(MarkerList(model, state.markers, spacing, radius));
  raster.finalize(true);
  // The union's values inside are the nearest sphere's, barely negative between the markers: an
  // offset straight on them would open bubbles there. Rebuilt as the distance to the union's
  // surface first, it erodes cleanly.
  openvdb::FloatGrid::Ptr distance = openvdb::tools::levelSetRebuild(*grid, 0.0f, kHalfWidth);
  openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*distance);
  // The spheres over a face of markers on a square lattice stand r at their centres but less
  // between them: their union's face lies on average 0.911 r out (the mean of sqrt(r^2 - d^2)
  // over a lattice cell, d the distance to the nearest marker), which the erosion allows for.
  constexpr Real kMeanBump = 0.911;
  filter.offset(static_cast<float>(kMeanBump * radius - 0.5 * spacing));  // > 0: inwards
  return distance;
}

// A height field's liquid as a closed mesh: the surface through the columns' corners (each the
// mean of the columns around it), the domain's floor below, and the walls between them.
openvdb::FloatGrid::Ptr height_field_level_set(const LiquidModel& model, const LiquidState& state,
                                               Real voxel) {
  const MacGrid& g = model.grid;
  const ColumnAxes axes = column_axes(model);
  const int n0 = g.n[axes.h0], n1 = g.n[axes.h1];
  const Real bottom = g.origin[axes.v];
  auto height = [&](int i0, int i1) {
    i0 = std::clamp(i0, 0, n0 - 1);
    i1 = std::clamp(i1, 0, n1 - 1);
    return state.height[static_cast<std::size_t>(i0 + n0 * i1)];
  };
  const int c0 = n0 + 1, c1 = n1 + 1;  // corners per axis
  std::vector<openvdb::Vec3s> points;
  points.reserve(static_cast<std::size_t>(2 * c0 * c1));
  for (int level = 0; level < 2; ++level) {
    for (int j = 0; j < c1; ++j) {
      for (int i = 0; i < c0; ++i) {
        Vec3 x;
        x[axes.h0] = g.origin[axes.h0] + i * g.h[axes.h0];
        x[axes.h1] = g.origin[axes.h1] + j * g.h[axes.h1];
        x[axes.v] = level == 0 ? bottom
                               : 0.25 * (height(i - 1, j - 1) + height(i, j - 1) +
                                         height(i - 1, j) + height(i, j));
        points.emplace_back(static_cast<float>(x.x()), static_cast<float>(x.y()),
                            static_cast<float>(x.z()));
      }
    }
  }
  auto corner = [&](int level, int i, int j) {
    return static_cast<openvdb::Index32>(level * c0 * c1 + i + c0 * j);
  };
  // Quads wound so that their normals point out of the liquid when (h0, h1, v) is right-handed;
  // a left-handed frame flips every one, which the level set's sign (by winding) does not mind.
  std::vector<openvdb::Vec4I> quads;
  for (int j = 0; j + 1 < c1; ++j) {
    for (int i = 0; i + 1 < c0; ++i) {
      quads.emplace_back(corner(1, i, j), corner(1, i + 1, j), corner(1, i + 1, j + 1),
                         corner(1, i, j + 1));
      quads.emplace_back(corner(0, i, j), corner(0, i, j + 1), corner(0, i + 1, j + 1),
                         corner(0, i + 1, j));
    }
  }
  for (int i = 0; i + 1 < c0; ++i) {
    quads.emplace_back(corner(0, i, 0), corner(0, i + 1, 0), corner(1, i + 1, 0), corner(1, i, 0));
    quads.emplace_back(corner(0, i + 1, c1 - 1), corner(0, i, c1 - 1), corner(1, i, c1 - 1),
                       corner(1, i + 1, c1 - 1));
  }
  for (int j = 0; j + 1 < c1; ++j) {
    quads.emplace_back(corner(0, 0, j + 1), corner(0, 0, j), corner(1, 0, j), corner(1, 0, j + 1));
    quads.emplace_back(corner(0, c0 - 1, j), corner(0, c0 - 1, j + 1), corner(1, c0 - 1, j + 1),
                       corner(1, c0 - 1, j));
  }
  const openvdb::math::Transform::Ptr transform =
      openvdb::math::Transform::createLinearTransform(voxel);
  const std::vector<openvdb::Vec3I> no_triangles;
  return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*transform, points, no_triangles, quads,
                                                            kHalfWidth);
}

void write_vdb(openvdb::FloatGrid::Ptr grid, const std::string& path) {
  namespace fs = std::filesystem;
  const std::string temporary = path + ".tmp";
  try {
    openvdb::io::File file(temporary);
    file.write({grid});
    file.close();
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(temporary, ec);
    throw std::runtime_error(path + ": cannot write the level set: " + e.what());
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw std::runtime_error(path + ": cannot write the level set: " + ec.message());
  }
}

}  // namespace

LiquidSurfaceMesh liquid_surface_mesh(const LiquidModel& model, const LiquidState& state,
                                      const LiquidSurfaceOptions& options,
                                      const std::string& vdb_path) {
  static std::once_flag initialized;
  std::call_once(initialized, [] { openvdb::initialize(); });
  const MacGrid& g = model.grid;
  Real cell = 1e300;
  for (int a = 0; a < 3; ++a) {
    if (a != model.thin_axis) cell = std::min(cell, g.h[a]);
  }
  const bool markers = model.def.surface == SurfaceMethod::markers;
  const Real fraction = options.voxel > 0 ? options.voxel
                        : markers         ? 0.5 / model.def.markers_per_axis
                                          : 0.5;
  Real voxel = fraction * cell;
  // A 2D liquid's slab is one cell thick: four voxels across it at least (its four long edges'
  // rounding then takes 9% of its volume, 5% at eight voxels, tests/test_liquid_surface_mesh.cpp).
  if (options.voxel <= 0 && model.thin_axis >= 0) {
    voxel = std::min(voxel, g.h[model.thin_axis] / 4);
  }
  LiquidSurfaceMesh mesh;
  mesh.voxel_size = voxel;
  if (markers && state.markers.empty()) return mesh;
  openvdb::FloatGrid::Ptr grid = markers ? markers_level_set(model, state, voxel)
                                         : height_field_level_set(model, state, voxel);
  if (options.smoothing > 0) {
    openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*grid);
    for (int pass = 0; pass < options.smoothing; ++pass) filter.meanCurvature();
  }
  grid->setName(model.def.name.empty() ? "liquid" : model.def.name);
  mesh.active_voxels = static_cast<long>(grid->activeVoxelCount());
  if (!vdb_path.empty()) write_vdb(grid, vdb_path);

  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, triangles, quads, 0.0, 0.0);
  mesh.positions.reserve(points.size());
  for (const openvdb::Vec3s& p : points) mesh.positions.emplace_back(p.x(), p.y(), p.z());
  // volumeToMesh winds its polygons clockwise seen from outside (negative inside, OpenVDB's
  // convention); the renderer and the exporters want counter-clockwise.
  auto index = [](openvdb::Index32 i) { return static_cast<int>(i); };
  for (const openvdb::Vec3I& t : triangles) {
    mesh.triangles.push_back({index(t[0]), index(t[2]), index(t[1])});
  }
  for (const openvdb::Vec4I& q : quads) {
    mesh.triangles.push_back({index(q[0]), index(q[2]), index(q[1])});
    mesh.triangles.push_back({index(q[0]), index(q[3]), index(q[2])});
  }
  return mesh;
}

}  // namespace pbm
