// A look-at camera with a vertical field of view; the scene's, or one framing everything.
#pragma once

#include <Eigen/Core>

#include "scene/scene.h"
#include "sim/snapshot.h"
#include "sim/tracks.h"

namespace pbm {

struct Camera {
  Eigen::Vector3f position{6, -8, 4};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up{0, 0, 1};
  float fov = 40;  // vertical [degrees]
};

Camera camera_from_scene(const CameraDef& def);
// The scene's camera as its tracks move it at the drive's time (sim/tracks.h).
Camera camera_from_drive(const Drive& drive);

// Looks at the bodies' bounding box from the front-right and above, far enough that the box
// fits the vertical field of view at the given aspect (width / height).
Camera frame_bodies(const Snapshot& snapshot, float aspect);

Eigen::Matrix4f view_matrix(const Camera& camera);
Eigen::Matrix4f perspective_matrix(float fov_degrees, float aspect, float near, float far);
Eigen::Matrix4f orthographic_matrix(float left, float right, float bottom, float top, float near,
                                    float far);

}  // namespace pbm
