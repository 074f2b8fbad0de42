// The liquid's surface as a triangle mesh for display and export (16.3), from a narrow-band level
// set of the liquid built with OpenVDB: its markers rasterized as spheres
// (tools::ParticlesToLevelSet), its height field's closed column mesh converted
// (tools::meshToLevelSet), or its chains' signed distance set in the narrow band
// (tools::signedFloodFill beyond); then smoothed (tools::LevelSetFilter) and meshed at its zero
// crossing (tools::volumeToMesh). The level set can also be written as a .vdb file that Blender and
// Houdini open. Display only: nothing here changes a later frame.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "liquid/liquid_state.h"

namespace pbm {

struct LiquidSurfaceOptions {
  // The level set's voxel as a fraction of the grid's smallest cell; 0: the markers' spacing
  // (a cell over markers_per_axis), or half a cell for a height field.
  Real voxel = 0;
  // Mean-curvature flow passes over the level set (each ~ one voxel's smoothing), which takes
  // off the bumps of the markers' spheres and keeps the volume (a Gaussian would shrink it).
  int smoothing = 2;
};

struct LiquidSurfaceMesh {
  std::vector<Vec3> positions;                // [m]
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from the air
  Real voxel_size = 0;                        // the level set's [m]
  long active_voxels = 0;                     // its narrow band's size
};

// The surface of liquid `model` in `state`; when vdb_path is not empty the level set (a
// FloatGrid named after the liquid, class level set) is also written there, through a temporary
// file renamed over it. Throws std::runtime_error naming vdb_path when it cannot be written.
LiquidSurfaceMesh liquid_surface_mesh(const LiquidModel& model, const LiquidState& state,
                                      const LiquidSurfaceOptions& options,
                                      const std::string& vdb_path = {});

}  // namespace pbm
