// Scene: the parsed, validated content of a scene file (scenes/README.md documents the format).
// The aggregate of every subsystem's definitions (each subsystem owns its Def structs, data below
// the algorithms: deform/body_def.h, collide/obstacle_def.h, constrain/constraint_def.h,
// figure/figure_def.h, liquid/liquid_def.h) and the
// scene-wide ones below. Plain definitions with defaults. sim/model.h compiles a Scene into a
// Model.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "collide/obstacle_def.h"
#include "constrain/constraint_def.h"
#include "core/keyframes.h"
#include "core/types.h"
#include "deform/body_def.h"
#include "figure/figure_def.h"
#include "integrate/integrators.h"
#include "liquid/liquid_def.h"

namespace pbm {

// A keyframed value. target is one of the targets of scene/track_targets.h in its index form,
// e.g. "bodies[0].q_s0[6]" (the reader rewrites the other accepted forms).
struct TrackDef {
  std::string target;
  Interpolation interpolation = Interpolation::linear;
  std::vector<Keyframe> keys;  // strictly increasing times, at least one
};

struct SolverDef {
  Real dt = 0.001;  // substep [s], > 0
  IntegratorKind integrator = IntegratorKind::euler;
  Real tolerance = 1e-6;  // rk45 local error tolerance, > 0
  // The implicit integrator's adaptive step (sim/adaptive_step.h): each substep's length chosen
  // from a local error estimate, kept under adaptive_tolerance [m], between dt and dt / 2^10.
  bool adaptive = false;
  Real adaptive_tolerance = 1e-3;  // [m], > 0
  // Time scale tau of the shape parameters' inertia floor eta_i = k_s,i tau^2 [s], > 0 (absent:
  // dt). Part of the model, not of the step: fixed, it leaves dt a knob that converges.
  std::optional<Real> shape_inertia_time;
  Real fps = 30.0;                      // frames per second of the timeline, > 0
  Real duration = 10.0;                 // default length of a run [s], > 0
  bool contact_step_reduction = false;  // end of sec. 5.2.2
  Real contact_dt_factor = 0.25;        // dt multiplier while in contact, (0, 1]
  int max_retries = 4;                  // stability guard: halvings per frame
  Real energy_growth_bound = 10.0;      // max (E_after / E_before) for one frame
  // The run-level guard: the energy may grow beyond the inputs' work by this fraction of the
  // run's largest kinetic + elastic energy (docs/architecture.md, "Stability guard").
  Real energy_tolerance = 0.25;
  Real constraint_alpha = 10.0;         // Baumgarte alpha of (7.14) [1/s], >= 0
  std::optional<Real> constraint_beta;  // Baumgarte beta [1/s], >= 0; absent: = alpha (7.16)
  ConstraintSolverKind constraint_solver = ConstraintSolverKind::dense;
  // After the collision stages, C and C-dot are restored to their values before them
  // (constrain/constraint_projection.h); false: Baumgarte's feedback alone closes what a
  // collision opens.
  bool constraint_projection = true;
  // Collisions between bodies (sec. 5.2.2); parts joined by a constraint never collide.
  bool body_collisions = true;
  bool self_collision = false;   // a local body with itself (collide/self_collision.h)
  Real body_friction = 0.3;      // b_f of (5.13) between bodies, in [0, 1]
  Real body_elasticity = 0;      // a of (5.11) between bodies, >= 0; 0: inelastic impulses only
  Real collision_margin = 0.02;  // contact band [m], > 0
};

// Where the renderer looks from (position, target, up) and its vertical field of view. Scenes
// without one are framed automatically.
struct CameraDef {
  Vec3 position{6, -8, 4};
  Vec3 target = Vec3::Zero();
  Vec3 up{0, 0, 1};
  Real fov = 40;  // vertical field of view [degrees], in (0, 180)
};

struct Scene {
  std::string file;  // where it was loaded from (for messages)
  std::string name;
  Vec3 gravity{0, 0, -9.81};
  SolverDef solver;
  std::vector<BodyDef> bodies;
  std::vector<ObstacleDef> obstacles;
  std::vector<ForceFieldDef> force_fields;
  std::vector<SpringDef> springs;
  std::vector<TrackDef> tracks;
  std::vector<ConstraintDef> constraints;
  std::vector<FigureDef> figures;  // articulated figures (ch. 15)
  std::vector<LiquidDef> liquids;  // liquid grids (ch. 16)
  std::optional<CameraDef> camera;
};

}  // namespace pbm
