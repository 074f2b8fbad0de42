#include "sim/snapshot.h"

#include "deform/body_dynamics.h"
#include "sim/tracks.h"

namespace pbm {

Vec3f Snapshot::bodies_min() const {
  Vec3f lo = Vec3f::Constant(1e30f);
  for (const BodySnapshot& b : bodies) {
    for (const Vec3f& x : b.positions) lo = lo.cwiseMin(x);
  }
  return lo;
}

Vec3f Snapshot::bodies_max() const {
  Vec3f hi = Vec3f::Constant(-1e30f);
  for (const BodySnapshot& b : bodies) {
    for (const Vec3f& x : b.positions) hi = hi.cwiseMax(x);
  }
  return hi;
}

Snapshot make_snapshot(const Model& model, const State& state, const Inputs& inputs,
                       Workspace& ws) {
  Snapshot snap;
  snap.time = state.time;
  evaluate_drive(model, inputs, state.time, ws.drive);
  snap.bodies.resize(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyModel& body = model.bodies[b];
    BodyWorkspace& bw = ws.bodies[b];
    bw.q_s_rest = ws.drive.q_s0[b];
    compute_body_kinematics(body, state.q.segment(body.q_offset, body.q_size),
                            state.v.segment(body.v_offset, body.v_size), bw, false);
    BodySnapshot& out = snap.bodies[b];
    out.name = body.name;
    out.positions.resize(bw.x.size());
    for (std::size_t i = 0; i < bw.x.size(); ++i) out.positions[i] = bw.x[i].cast<float>();
    out.triangles = body.tessellation.triangles;
    out.edges = body.tessellation.edges;
    out.color = body.color.cast<float>();
    out.roughness = static_cast<float>(model.scene.bodies[b].material.roughness);
  }
  // Where the tracks put each obstacle at this time (evaluate_drive above placed them).
  for (const ObstacleModel& o : ws.drive.obstacles) {
    ObstacleSnapshot out;
    out.kind = o.kind;
    out.point = o.point.cast<float>();
    out.normal = o.normal.cast<float>();
    out.size = o.size.cast<float>();
    out.rotation = o.rotation.cast<float>();
    out.half_extents = o.half_extents.cast<float>();
    out.mesh = o.mesh;
    if (o.mesh) {
      // x = R R0^T (x0 - p0) + p: the load placement's triangles carried to the current one.
      const Mat3 motion = o.rotation * o.mesh->rotation.transpose();
      out.mesh_rotation = motion.cast<float>();
      out.mesh_offset = (o.point - motion * o.mesh->position).cast<float>();
    }
    snap.obstacles.push_back(out);
  }
  for (std::size_t s = 0; s < model.springs.size(); ++s) {
    const SpringModel& spring = model.springs[s];
    if (state.time < spring.t_begin || state.time > spring.t_end) continue;
    snap.springs.push_back({ws.bodies[spring.body].x[spring.node].cast<float>(),
                            ws.drive.spring_target[s].cast<float>()});
  }
  // Where each end of a constraint is now (the kinematics above are current): a node, a point
  // fixed in the body frame, or a world anchor.
  auto end_point = [&](const ConstraintPoint& end) -> Vec3 {
    if (end.body < 0) return end.point;
    const BodyModel& body = model.bodies[end.body];
    if (end.node >= 0) return ws.bodies[end.body].x[end.node];
    const auto q = state.q.segment(body.q_offset, 7);
    return q.head<3>() + rotation_from_quaternion(q.segment<4>(3)) * end.point;
  };
  for (const PointConstraintModel& c : model.constraints.points) {
    const Vec3 a = end_point(c.ends[0]), b = end_point(c.ends[1]);
    snap.constraints.push_back(
        {a.cast<float>(), b.cast<float>(), static_cast<float>((a - b).norm()), c.source});
  }
  return snap;
}

}  // namespace pbm
