// A look-at camera with a vertical field of view: the snapshot's (the scene's camera at the
// snapshot's time), or one framing what the snapshot says to frame.
#pragma once

#include <Eigen/Core>

#include "draw/snapshot.h"

namespace pbm {

struct Camera {
  Eigen::Vector3f position{6, -8, 4};
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  Eigen::Vector3f up{0, 0, 1};
  float fov = 40;  // vertical [degrees]
};

// The view as a camera, its field of view clamped to [1, 179] degrees.
Camera camera_from_view(const draw::CameraView& view);

// Looks at the box from the front-right and above, far enough that it fits the vertical field
// of view at the given aspect (width / height); the default camera for an empty box.
Camera frame_bounds(const draw::Bounds& bounds, float aspect);
// frame_bounds of the snapshot's focus (its moving objects).
Camera frame_focus(const draw::Snapshot& snapshot, float aspect);

Eigen::Matrix4f view_matrix(const Camera& camera);
Eigen::Matrix4f perspective_matrix(float fov_degrees, float aspect, float near, float far);
Eigen::Matrix4f orthographic_matrix(float left, float right, float bottom, float top, float near,
                                    float far);

}  // namespace pbm
