#include "liquid/liquid_surface_mesh.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetRebuild.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "liquid/cell_labels.h"
#include "liquid/surface_chains.h"

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

// The chains' liquid as a level set: the signed distance to the loops in the plane (negative
// where their winding is positive, by the crossings of each row of voxels), intersected with the
// grid's slab across the thin axis; set in the narrow band, the signs beyond flood-filled.
openvdb::FloatGrid::Ptr chains_level_set(const LiquidModel& model, const LiquidState& state,
                                         Real voxel) {
  const ChainPlane plane = chain_plane(model);
  const MacGrid& g = model.grid;
  const Real band = kHalfWidth * voxel;
  auto grid = openvdb::createLevelSet<openvdb::FloatGrid>(voxel, kHalfWidth);
  const std::vector<Vec3>& x = state.chain;
  const std::vector<int>& next = state.chain_next;
  // Voxel (i, j, k) sits at (i, j, k) * voxel (the transform's); the plane's pixels cover the
  // domain and a band beyond it.
  auto lowest = [&](Real at) { return static_cast<int>(std::floor((at - band) / voxel)) - 1; };
  auto highest = [&](Real at) { return static_cast<int>(std::ceil((at + band) / voxel)) + 1; };
  const int i0 = lowest(g.origin[plane.a0]),
            i1 = highest(g.origin[plane.a0] + g.n[plane.a0] * g.h[plane.a0]);
  const int j0 = lowest(g.origin[plane.a1]),
            j1 = highest(g.origin[plane.a1] + g.n[plane.a1] * g.h[plane.a1]);
  const Real t0 = g.origin[plane.thin], t1 = t0 + g.h[plane.thin];
  const int k0 = lowest(t0), k1 = highest(t1);
  const int ni = i1 - i0 + 1, nj = j1 - j0 + 1;
  std::vector<Real> distance(static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj), band);
  for (std::size_t m = 0; m < x.size(); ++m) {
    const Vec3& a = x[m];
    const Vec3& b = x[static_cast<std::size_t>(next[m])];
    const Real ax = a[plane.a0], ay = a[plane.a1], bx = b[plane.a0], by = b[plane.a1];
    if (!std::isfinite(ax + ay + bx + by)) continue;
    const Real dx = bx - ax, dy = by - ay, length2 = dx * dx + dy * dy;
    const int pi0 = std::max(i0, static_cast<int>(std::floor((std::min(ax, bx) - band) / voxel)));
    const int pi1 = std::min(i1, static_cast<int>(std::ceil((std::max(ax, bx) + band) / voxel)));
    const int pj0 = std::max(j0, static_cast<int>(std::floor((std::min(ay, by) - band) / voxel)));
    const int pj1 = std::min(j1, static_cast<int>(std::ceil((std::max(ay, by) + band) / voxel)));
    for (int j = pj0; j <= pj1; ++j) {
      for (int i = pi0; i <= pi1; ++i) {
        const Real px = i * voxel - ax, py = j * voxel - ay;
        const Real t = length2 > 0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
        const Real d = std::hypot(px - t * dx, py - t * dy);
        Real& stored = distance[static_cast<std::size_t>((i - i0) + ni * (j - j0))];
        stored = std::min(stored, d);
      }
    }
  }
  // Inside where the loops wind positively: along each row, the winding right of a pixel is the
  // sum of the directions of the crossings right of it.
  std::vector<std::pair<Real, int>> crossings;
  openvdb::FloatGrid::Accessor access = grid->getAccessor();
  for (int j = j0; j <= j1; ++j) {
    const Real y = j * voxel;
    crossings.clear();
    for (std::size_t m = 0; m < x.size(); ++m) {
      const Vec3& a = x[m];
      const Vec3& b = x[static_cast<std::size_t>(next[m])];
      const Real ay = a[plane.a1], by = b[plane.a1];
      if ((ay <= y) == (by <= y)) continue;  // a NaN never crosses
      const Real at = a[plane.a0] + (y - ay) / (by - ay) * (b[plane.a0] - a[plane.a0]);
      crossings.emplace_back(at, by > ay ? 1 : -1);
    }
    std::sort(crossings.begin(), crossings.end());
    int winding = 0;
    for (const auto& c : crossings) winding += c.second;
    std::size_t passed = 0;
    for (int i = i0; i <= i1; ++i) {
      const Real px = i * voxel;
      while (passed < crossings.size() && crossings[passed].first < px) {
        winding -= crossings[passed++].second;
      }
      const Real d = distance[static_cast<std::size_t>((i - i0) + ni * (j - j0))];
      const Real in_plane = winding > 0 ? -d : d;
      for (int k = k0; k <= k1; ++k) {
        const Real t = k * voxel;
        const Real across = std::max(t0 - t, t - t1);  // negative inside the slab
        const Real value =
            in_plane > 0 && across > 0 ? std::hypot(in_plane, across) : std::max(in_plane, across);
        if (std::abs(value) >= band) continue;
        openvdb::Coord ijk;
        ijk[plane.a0] = i;
        ijk[plane.a1] = j;
        ijk[plane.thin] = k;
        access.setValue(ijk, static_cast<float>(value));
      }
    }
  }
  openvdb::tools::signedFloodFill(grid->tree());
  return grid;
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
  const bool chains = model.def.surface == SurfaceMethod::chains;
  // Chains: half their spacing (a distance to the links, no spheres to round off).
  const Real fraction = options.voxel > 0   ? options.voxel
                        : markers || chains ? 0.5 / model.def.markers_per_axis
                                            : 0.5;
  Real voxel = fraction * cell;
  // A 2D liquid's slab is one cell thick: four voxels across it at least (its four long edges'
  // rounding then takes 9% of its volume, 5% at eight voxels, tests/test_liquid_surface_mesh.cpp).
  if (options.voxel <= 0 && model.thin_axis >= 0) {
    voxel = std::min(voxel, g.h[model.thin_axis] / 4);
  }
  LiquidSurfaceMesh mesh;
  mesh.voxel_size = voxel;
  if ((markers && state.markers.empty()) || (chains && state.chain.empty())) return mesh;
  openvdb::FloatGrid::Ptr grid = markers  ? markers_level_set(model, state, voxel)
                                 : chains ? chains_level_set(model, state, voxel)
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
