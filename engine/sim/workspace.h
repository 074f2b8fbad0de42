// Workspace: every subsystem's scratch, sized for one Model by init_workspace (sim/world.h).
// Nothing in it changes a later frame (docs/architecture.md, "Determinism"): it may be thrown
// away and rebuilt at any time, and the next frame is bit-identical. What does carry from one
// step to the next lives in State.
#pragma once

#include <optional>
#include <vector>

#include "collide/body_collisions.h"
#include "constrain/constraint_forces.h"
#include "constrain/constraint_projection.h"
#include "deform/body_workspace.h"
#include "figure/figure_impact.h"
#include "figure/figure_impulse.h"
#include "figure/figure_workspace.h"
#include "figure/segment_surface.h"
#include "figure/stable_pd.h"
#include "integrate/integrators.h"
#include "liquid/liquid_step.h"
#include "sim/figure_collisions.h"
#include "sim/frame_stats.h"
#include "sim/segment_body_collisions.h"
#include "sim/state.h"
#include "sim/step_stage.h"
#include "sim/tracks.h"

namespace pbm {

// A body's bounding sphere and how far it may move in a lookahead (sim/level_of_detail.h).
struct BodyReach {
  Vec3 centre = Vec3::Zero();
  Real radius = 0;  // of the nodes about the centre [m]
  Real travel = 0;  // how far a point of it may move in the lookahead [m]
};

// One figure's actuators (sim/stages_figure_control.h), each vector n_v: the actuators' forces
// of this evaluation (MRAC and PD, the site actuators' J^T F, then the stable PD's), and the
// stable PD's gains, targets, other joint forces, accelerations and servo forces.
struct FigureControlWorkspace {
  VecX tau;
  VecX Kp, Kd, q_target, v_target, tau_ext, qdd, tau_pd;
  StablePdWorkspace pd;
};

// The figures' scratch (sim/stages_figures.h): each figure's recursions, the joint forces of the
// one being evaluated, its segments' world transforms, the contact stage's forces on each segment,
// the explicit controllers' forces, the stable PD's system and the impact stage's system.
struct FiguresWorkspace {
  std::vector<FigureWorkspace> each;
  VecX tau;
  std::vector<FigureControlWorkspace> control;  // per figure; empty without controllers
  // The step length the stable PD servos and the joint damping (under euler and implicit) are
  // implicit over: the substep under way.
  Real step = 0;
  VecX armature;  // one figure's dt d per DOF: its implicit joint damping (forward_dynamics)
  std::vector<SpatialTransform> world;
  std::vector<std::vector<ForceVector>> contact_forces;  // per figure, per segment (own frame)
  std::vector<ImpactContact> impacts;
  ImpactWorkspace impact;
  VecX q, v;  // one figure's slices, for resolve_impact
  // Collisions between segments (sim/figure_collisions.h): every figure's world transforms at
  // once, the detection's scratch and its contacts.
  std::vector<std::vector<SpatialTransform>> worlds;
  SegmentCollisionScratch collision;
  std::vector<SegmentContact> segment_contacts;
  // Collisions of segments with deformable bodies (sim/segment_body_collisions.h).
  SegmentBodyWorkspace bodies;
  // The site actuators' forces on each segment of the figure being evaluated (own frames), and the
  // impulse events' scratch.
  std::vector<ForceVector> site_forces;
  ImpulseScratch impulse;
  // A liquid's push on the segments (sim/liquid_segment_loads.h): each segment's surface patches
  // (per figure, per segment; sized where a scene has liquids), the power of the last rate
  // evaluation's liquid forces at its velocities [W], for the guard's work, and one figure's
  // forces when they are measured.
  std::vector<std::vector<std::vector<SurfacePatch>>> liquid_patches;
  Real liquid_power = 0;
  std::vector<ForceVector> liquid_measured;
};

struct Workspace {
  // Bodies (deform/): per-body dynamics and contact scratch; the velocities first-order bodies
  // (3.51) solved for in the last rate evaluation (n_v).
  std::vector<BodyWorkspace> bodies;
  VecX first_order_velocity;
  // The tracks' values at the time of the last evaluation (rates, measurement, snapshot), and at
  // a frame's end for the guard.
  Drive drive, end_drive;
  std::vector<ObstacleModel> placed;  // obstacles placed at other times (the guard's allowance)
  IntegratorWorkspace integrator;
  // Present only when the scene has the subsystem (docs/architecture.md: a scene pays only for
  // what it uses).
  std::optional<ConstraintWorkspace> constraints;
  // Only where collisions can open the constraints (sim/stages_constraints.h).
  std::optional<ConstraintProjectionWorkspace> constraint_projection;
  std::optional<BodyCollisionWorkspace> body_collisions;
  std::optional<FiguresWorkspace> figures;
  // Per liquid (empty without any): its scratch, and what its substeps cost since the last
  // measurement (sim/stages_liquid.h).
  std::vector<LiquidWorkspace> liquids;
  std::vector<LiquidStepStats> liquid_steps;
  Drive liquid_drive;  // the tracks at a liquid's own time (sim/stages_liquid.cpp)
  // Per body in a scene with liquids and bodies: the liquids' nodal forces at the last rate
  // evaluation [N] (sim/liquid_body_loads.h), whose power the guard counts.
  std::vector<std::vector<Vec3>> liquid_body_force;
  std::vector<Vec3> liquid_measure_force;  // measure_liquids' scratch, one body's nodes
  // Two-way coupling (liquid/moving_solids.h), in scenes with liquids: each body's surface as
  // the liquids see it (kinematics of its own, computed from the State, so the bodies' stages'
  // are never disturbed), and one liquid's obstacle cells at a time.
  std::vector<BodyWorkspace> liquid_kinematics;
  std::vector<SolidSurface> liquid_surfaces;
  std::vector<SolidCell> liquid_obstacle_cells;
  // Per liquid and cell, the first obstacle that no track moves holding the cell's centre (-1:
  // none): found once from the Model, so each substep tests only the moving obstacles.
  std::vector<std::vector<int>> liquid_static_obstacle;
  BodyCollisionStats body_collision_stats;  // of the last substep
  SegmentBodyStats segment_body_stats;      // of the last substep
  int contacts = 0;  // touching nodes counted in the substep under way (-> State::contact_nodes)
  // Whether the substep under way is the last of its frame (advance_frame sets it before each;
  // a substep advanced alone ends its own frame). The mean-axis split of bodies without an
  // obstacle stage is restored only then (sim/stages_bodies.h).
  bool substep_ends_frame = true;
  std::vector<BodyReach> level_reach;  // levels of detail chosen at a frame's start
  StageClock clock;
  // advance_frame's own: the frame's start (its retry point) and the guard's measurements.
  State frame_start;
  State adaptive_save;  // the state before an adaptive substep, restored when it is rejected
  FrameStats before, after;
  // The frame's start state measured with the drive of its end, and its end state with the drive
  // of its start: the run-level guard's trapezoid for the work a time-dependent drive does
  // (sim/world.cpp). Only when tracks or springs make the drive depend on time.
  FrameStats start_at_end_drive, end_at_start_drive;
  // The measurement that ended the last frame, and the state it measured: the next frame starts
  // from it unless the state was changed in between (a seek, an edit). A cache: equal to what
  // measuring that state again gives.
  struct Measured {
    bool valid = false;
    Real time = 0;
    VecX q, v;
    FrameStats stats;
  } last_measured;
};

}  // namespace pbm
