#include "sim/snapshot.h"

#include "sim/tracks.h"

namespace pbm {

draw::Snapshot make_snapshot(const World& world, const Inputs& inputs, const State& state,
                             Workspace& ws) {
  const Model& model = *world.model;
  draw::Snapshot snap;
  snap.time = state.time;
  evaluate_drive(model, inputs, state.time, ws.drive);
  for (const Subsystem* subsystem : world.subsystems) {
    if (subsystem->add_drawables) subsystem->add_drawables(model, inputs, state, ws, snap);
  }
  if (model.scene.camera) {
    snap.camera = draw::CameraView{.position = ws.drive.camera_position.cast<float>(),
                                   .target = ws.drive.camera_target.cast<float>(),
                                   .up = ws.drive.camera_up.cast<float>(),
                                   .fov = static_cast<float>(ws.drive.camera_fov)};
  }
  return snap;
}

draw::Snapshot make_snapshot(Simulation& sim) {
  return make_snapshot(sim.world, sim.inputs, sim.state, sim.ws);
}

}  // namespace pbm
