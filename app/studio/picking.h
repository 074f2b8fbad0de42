// Mouse picking in the viewport: a ray through a pixel against every triangle of the snapshot's
// pickable meshes (draw::Mesh::pick >= 0: the bodies) and against figures' segment shapes, and
// the drag plane of the mouse spring
// (sec. 6.4).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "camera.h"
#include "draw/snapshot.h"

namespace pbm {

struct Ray {
  Eigen::Vector3f origin, direction;  // direction unit
};

// The ray from `camera` through pixel (x, y) of a width x height image (y down, pixel centres at
// +0.5).
Ray pixel_ray(const Camera& camera, float x, float y, int width, int height);

struct Pick {
  int body = -1;          // the mesh's pick
  int node = -1;          // the hit triangle's corner nearest to the hit (a mesh vertex)
  Eigen::Vector3f point;  // world hit point
  float distance = 0;     // along the ray
};

// The nearest hit of the ray on any pickable mesh (Moller-Trumbore), if any.
std::optional<Pick> pick_body(const draw::Snapshot& snapshot, const Ray& ray);

// A figure's segment under the ray: its figure and segment index (draw::Primitive::figure,
// segment), the world hit point and the distance along the ray.
struct FigurePick {
  int figure = -1, segment = -1;
  Eigen::Vector3f point;
  float distance = 0;
};

// The nearest hit of the ray on a figure's segment shape (box, sphere, capsule, cylinder), if
// any: sphere tracing of each shape's exact distance function in its own frame.
std::optional<FigurePick> pick_figure(const draw::Snapshot& snapshot, const Ray& ray);

// World bounds of the meshes whose pick is `pick` (empty if there are none): what F frames.
draw::Bounds pick_bounds(const draw::Snapshot& snapshot, int pick);

// Where the ray meets the plane through `point` facing the camera (normal = view direction):
// the mouse spring's target while dragging.
Eigen::Vector3f drag_target(const Camera& camera, const Ray& ray, const Eigen::Vector3f& point);

}  // namespace pbm
