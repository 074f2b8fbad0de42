// The sections of a scene file, each defined beside the code that only it needs
// (scene_<section>_json.cpp); the scene's own table (scene_json.cpp) holds them together and
// describe_scene_format() lists them. Only the scene reader's files include this.
#pragma once

#include <string_view>

#include "scene/scene_fields.h"

namespace pbm {

extern const Section<Scene> kSceneSection;                     // scene_json.cpp
extern const Section<SolverDef> kSolverSection;                // scene_solver_json.cpp
extern const Section<CameraDef> kCameraSection;                // scene_solver_json.cpp
extern const Section<BodyDef> kBodySection;                    // scene_bodies_json.cpp
extern const Section<BodyDef> kShapeSection;                   // scene_bodies_json.cpp
extern const Section<TessellationDef> kTessellationSection;    // scene_bodies_json.cpp
extern const Section<MaterialDef> kMaterialSection;            // scene_bodies_json.cpp
extern const Section<ObstacleDef> kObstacleSection;            // scene_obstacles_json.cpp
extern const Section<ForceFieldDef> kForceFieldSection;        // scene_springs_json.cpp
extern const Section<SpringDef> kSpringSection;                // scene_springs_json.cpp
extern const Section<ConstraintDef> kConstraintSection;        // scene_constraints_json.cpp
extern const Section<ConstraintEndDef> kConstraintEndSection;  // scene_constraints_json.cpp
extern const Section<TrackDef> kTrackSection;                  // scene_tracks_json.cpp
extern const Section<FigureDef> kFigureSection;                // scene_figures_json.cpp
extern const Section<SegmentDef> kSegmentSection;              // scene_figures_json.cpp
extern const Section<JointDef> kJointSection;                  // scene_figures_json.cpp
extern const Section<SegmentShapeDef> kSegmentShapeSection;    // scene_figures_json.cpp
extern const Section<SiteDef> kSiteSection;                    // scene_figures_json.cpp
extern const Section<ControllerDef> kControllerSection;        // scene_figures_json.cpp
extern const Section<SegmentPairDef> kSegmentPairSection;      // scene_figures_json.cpp
extern const Section<ImpulseDef> kImpulseSection;              // scene_figures_json.cpp
extern const Section<SiteActuatorDef> kSiteActuatorSection;    // scene_figures_json.cpp
extern const Section<MocapDef> kMocapSection;                  // scene_figures_json.cpp
extern const Section<MocapJointDef> kMocapJointSection;        // scene_figures_json.cpp
extern const Section<MocapSiteDef> kMocapSiteSection;          // scene_figures_json.cpp
extern const Section<LiquidDef> kLiquidSection;                // scene_liquids_json.cpp
extern const Section<FluidRegionDef> kFluidRegionSection;      // scene_liquids_json.cpp
extern const Section<LiquidBoxDef> kLiquidBoxSection;          // scene_liquids_json.cpp
extern const Section<InflowDef> kInflowSection;                // scene_liquids_json.cpp
extern const Section<SurfaceWaveDef> kSurfaceWaveSection;      // scene_liquids_json.cpp

// Whether an obstacle of `kind` has the key (its point is "point", "center" or "position").
bool obstacle_has_key(ObstacleKind kind, std::string_view key);

}  // namespace pbm
