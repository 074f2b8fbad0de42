// make_snapshot: one moment of a simulation as plain drawables (draw/snapshot.h), what the
// renderer, the studio's picking and the exporters read (docs/architecture.md, "Snapshot").
//
// Scene layer: one smooth Mesh per body (pick = body index; positions of this moment, topology
// shared from Model::snapshot_geometry), planes, boxes as Primitives, mesh obstacles as flat
// Meshes placed by their tracks. Overlay layer: springs and mouse springs (yellow Lines with end
// points), point constraints (a Line with end points from end a to end b, green when held, red
// at |C| >= 1 cm); the bodies' element edges are their topology's edges. The scene's camera
// with its tracks applied; focus = the bodies' nodes.
#pragma once

#include "draw/snapshot.h"
#include "sim/inputs.h"
#include "sim/model.h"
#include "sim/state.h"
#include "sim/world.h"

namespace pbm {

// The engine's name for it (runner, tests); the type lives in draw/ with no engine types.
using Snapshot = draw::Snapshot;

// The snapshot of state. Computes the kinematics and the drive in ws (its caches stay valid).
draw::Snapshot make_snapshot(const Model& model, const State& state, const Inputs& inputs,
                             Workspace& ws);

}  // namespace pbm
