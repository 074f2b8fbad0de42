// make_snapshot: one moment of a simulation as plain drawables (draw/snapshot.h), what the
// renderer, the studio's picking and the exporters read (docs/architecture.md, "Snapshot").
// Every present subsystem adds its own drawables (its add_drawables hook, sim/subsystem.h):
//   bodies       one smooth Mesh each (pick = body index; positions of this moment, topology
//                shared from Model::snapshot_geometry); springs as overlay Lines with end points
//   obstacles    planes, boxes as Primitives, mesh obstacles as flat Meshes where their tracks
//                put them
//   constraints  overlay Lines from end a to end b, green when held, red at |C| >= 1 cm
// The bodies' element edges are their topology's edges (the renderer's overlay pass). The
// scene's camera with its tracks applied; focus = the bodies' nodes.
#pragma once

#include "draw/snapshot.h"
#include "sim/inputs.h"
#include "sim/simulation.h"
#include "sim/state.h"
#include "sim/world.h"

namespace pbm {

// The engine's name for it (runner, tests); the type lives in draw/ with no engine types.
using Snapshot = draw::Snapshot;

// The snapshot of state with the inputs of the moment. Computes the kinematics and the drive in
// ws (results of later steps do not depend on it: docs/architecture.md, "Determinism").
draw::Snapshot make_snapshot(const World& world, const Inputs& inputs, const State& state,
                             Workspace& ws);
draw::Snapshot make_snapshot(Simulation& sim);

}  // namespace pbm
