// Model: everything constant while time runs (docs/architecture.md), compiled once from a Scene.
// A thin aggregate: each subsystem owns its model (deform/body_model.h, collide/obstacle_model.h,
// collide/body_collision_model.h, constrain/constraint_model.h, figure/figure_model.h); what lives
// here is what spans them (tracks, whose targets are in any subsystem) and the scene-wide settings.
// State layout: every body owns a slice of State::q and State::v (BodyModel::q_offset, v_offset;
// its blocks in deform/body_layout.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "collide/body_collision_model.h"
#include "collide/obstacle_model.h"
#include "constrain/constraint_model.h"
#include "core/keyframes.h"
#include "core/types.h"
#include "deform/body_model.h"
#include "figure/figure_build.h"
#include "liquid/liquid_model.h"
#include "scene/scene.h"
#include "scene/track_targets.h"
#include "sim/snapshot_geometry.h"

namespace pbm {

struct TrackModel {
  TrackTarget target = TrackTarget::gravity;
  int object = 0;  // body, spring or obstacle index
  int index = 0;   // parameter or vector component
  Interpolation interpolation = Interpolation::linear;
  std::vector<Keyframe> keys;
};

struct Model {
  Scene scene;  // the source, kept for saving and for messages
  Vec3 gravity{0, 0, -9.81};
  SolverDef solver;
  std::vector<BodyModel> bodies;
  std::vector<ObstacleModel> obstacles;
  std::vector<ForceFieldDef> force_fields;
  std::vector<SpringModel> springs;
  std::vector<TrackModel> tracks;
  ConstraintSystemModel constraints;   // ch. 7
  BodyCollisionModel body_collisions;  // 5.2.2, from the solver's keys and the constraints
  // Articulated figures (ch. 15), each with its initial state; their slices of State follow the
  // bodies' (FigureModel::state_q_offset, state_v_offset).
  std::vector<CompiledFigure> figures;
  // Liquid grids (ch. 16), each with its own state (State::liquids) on its own CFL clock.
  std::vector<LiquidModel> liquids;
  // Some pair of segments may collide (sim/figure_collisions.h).
  bool segment_collisions = false;
  int n_q = 0, n_v = 0;
  // The longest substep advance_frame may take [s]: solver.dt, or shorter where a body's explicit
  // stability limit (deform/stability_limit.h) with the configured integrator needs it (the
  // shortening is one of the notes). rk45 chooses its own steps inside each substep.
  Real substep = 0;  // every body at its own level ("auto" bodies awake): stable_substep
  // Warnings about the solvers for every frame's stats, '; '-separated (constraints.notes).
  std::string notes;
  SnapshotGeometry snapshot_geometry;  // shared by every snapshot (sim/snapshot.h), drawing only
};

// Throws pbm::Error (file, path) when the scene cannot be compiled.
// Fraction of the explicit stability limit a substep may take.
inline constexpr Real kStabilitySafety = 0.9;

// The longest substep no body's explicit limit forbids (solver.dt when none does), the bodies
// marked in `dormant` (an empty span: none) limited by their global block alone
// (sim/level_of_detail.h); `limiting`, when given, is set to the body that limits it.
Real stable_substep(const Model& model, std::span<const std::uint8_t> dormant,
                    const BodyModel** limiting = nullptr);

Model build_model(const Scene& scene);

}  // namespace pbm
