#include "sim/snapshot.h"

#include <algorithm>

#include "deform/body_dynamics.h"
#include "sim/tracks.h"

namespace pbm {
namespace {

// Colours of the overlay layer and of the obstacles, as the renderer drew them before they
// became drawables (the golden images hold them).
const draw::Vec3f kSpringColor(0.95f, 0.85f, 0.2f);
const draw::Material kObstacleMaterial{{0.45f, 0.52f, 0.62f}, 0.6f};
constexpr float kConstraintRedViolation = 0.01f;  // [m]: |C| drawn fully red
constexpr float kConstraintEndSize = 5;           // [pixels], smaller than a spring's ends

// Green while held, turning red as |C| reaches kConstraintRedViolation.
draw::Vec3f constraint_color(float violation) {
  const float t = std::clamp(violation / kConstraintRedViolation, 0.0f, 1.0f);
  return {0.25f + 0.7f * t, 0.9f - 0.7f * t, 0.35f - 0.15f * t};
}

}  // namespace

draw::Snapshot make_snapshot(const Model& model, const State& state, const Inputs& inputs,
                             Workspace& ws) {
  draw::Snapshot snap;
  snap.time = state.time;
  evaluate_drive(model, state.time, ws.drive);
  const SnapshotGeometry& geometry = model.snapshot_geometry;

  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, state.q.segment(body.q_offset, body.q_size),
                            state.v.segment(body.v_offset, body.v_size), bw, false);
    auto positions = std::make_shared<std::vector<draw::Vec3f>>(bw.x.size());
    for (std::size_t i = 0; i < bw.x.size(); ++i) {
      (*positions)[i] = bw.x[i].cast<float>();
      snap.focus.add((*positions)[i]);
    }
    draw::Mesh& mesh = snap.meshes.emplace_back();
    mesh.name = body.name;
    mesh.pick = static_cast<int>(b);
    mesh.positions = std::move(positions);
    mesh.topology = geometry.body_topology[b];
    mesh.material = {body.color.cast<float>(), static_cast<float>(body.roughness)};
    mesh.shading = draw::Shading::smooth;
  }

  // Where the tracks put each obstacle at this time (evaluate_drive above placed them).
  for (std::size_t k = 0; k < ws.drive.obstacles.size(); ++k) {
    const ObstacleModel& o = ws.drive.obstacles[k];
    switch (o.kind) {
      case ObstacleKind::plane:
        snap.planes.push_back(
            {o.point.cast<float>(), o.normal.cast<float>(), o.size.cast<float>()});
        break;
      case ObstacleKind::box:
        snap.primitives.push_back({.shape = draw::PrimitiveShape::box,
                                   .center = o.point.cast<float>(),
                                   .rotation = o.rotation.cast<float>(),
                                   .half_size = o.half_extents.cast<float>(),
                                   .material = kObstacleMaterial});
        break;
      case ObstacleKind::mesh: {
        draw::Mesh& mesh = snap.meshes.emplace_back();
        mesh.name = o.name;
        mesh.positions = geometry.obstacle_positions[k];
        mesh.topology = geometry.obstacle_topology[k];
        mesh.material = kObstacleMaterial;
        mesh.shading = draw::Shading::flat;
        // x = R R0^T (x0 - p0) + p: the load placement's vertices carried to the current one.
        const Mat3 motion = o.rotation * o.mesh->rotation.transpose();
        mesh.rotation = motion.cast<float>();
        mesh.offset = (o.point - motion * o.mesh->position).cast<float>();
        break;
      }
    }
  }

  // Springs active at this time and the mouse springs, from the body point to the target.
  draw::Lines springs{.end_points = true, .layer = draw::Layer::overlay};
  auto add_spring = [&](const Vec3& from, const Vec3& to) {
    springs.points.push_back(from.cast<float>());
    springs.points.push_back(to.cast<float>());
    springs.colors.push_back(kSpringColor);
  };
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& spring = model.springs[s];
    if (state.time < spring.t_begin || state.time > spring.t_end) continue;
    add_spring(ws.bodies[spring.body].x[spring.node], ws.drive.spring_target[s]);
  }
  for (const MouseSpring& spring : inputs.springs) {
    if (spring.body < 0 || spring.body >= static_cast<int>(model.bodies.size())) continue;
    const auto& x = ws.bodies[spring.body].x;
    if (spring.node < 0 || spring.node >= static_cast<int>(x.size())) continue;
    add_spring(x[spring.node], spring.target);
  }
  if (!springs.points.empty()) snap.lines.push_back(std::move(springs));

  // Where each end of a point constraint is now (the kinematics above are current): a node, a
  // point fixed in the body frame, or a world anchor. Drawn over the parts they join.
  auto end_point = [&](const ConstraintPoint& end) -> Vec3 {
    if (end.body < 0) return end.point;
    const BodyModel& body = model.bodies[end.body];
    if (end.node >= 0) return ws.bodies[end.body].x[end.node];
    const auto q = state.q.segment(body.q_offset, 7);
    return q.head<3>() + rotation_from_quaternion(q.segment<4>(3)) * end.point;
  };
  draw::Lines constraints{
      .end_points = true, .end_point_size = kConstraintEndSize, .layer = draw::Layer::overlay};
  for (const PointConstraintModel& c : model.constraints.points) {
    const Vec3 a = end_point(c.ends[0]), b = end_point(c.ends[1]);
    constraints.points.push_back(a.cast<float>());
    constraints.points.push_back(b.cast<float>());
    constraints.colors.push_back(constraint_color(static_cast<float>((a - b).norm())));
  }
  if (!constraints.points.empty()) snap.lines.push_back(std::move(constraints));

  if (model.scene.camera) {
    snap.camera = draw::CameraView{.position = ws.drive.camera_position.cast<float>(),
                                   .target = ws.drive.camera_target.cast<float>(),
                                   .up = ws.drive.camera_up.cast<float>(),
                                   .fov = static_cast<float>(ws.drive.camera_fov)};
  }
  return snap;
}

}  // namespace pbm
