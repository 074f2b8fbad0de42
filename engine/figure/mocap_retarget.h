// Retargeting a motion-capture clip onto a figure (sec. 15.4: joint and site trajectories, here
// from recorded motion): the scene's name map pairs clip joints with figure joints, whose angles
// become keyframed joint trajectories for servos, and clip joints with figure sites, whose world
// positions become the paths of site actuators. The clip's rest pose is taken to be the figure's
// neutral pose (every joint at q = 0), placed in the scene by the mocap's position, orientation
// and scale.
#pragma once

#include <string>
#include <vector>

#include "control/controller_def.h"
#include "figure/figure_def.h"
#include "figure/figure_model.h"
#include "figure/mocap_clip.h"

namespace pbm {

struct MocapTracks {
  std::vector<ControllerDef> controllers;       // one per mapped DOF
  std::vector<SiteActuatorDef> site_actuators;  // one per mapped site
};

// The tracks *def.mocap asks of `clip` on `figure`. Refusals name `file` and the key under `path`
// (the figure's JSON path): a clip joint or figure joint or site that does not exist, a joint
// that is not revolute, universal or spherical, a DOF that already has a controller.
MocapTracks retarget_mocap(const FigureDef& def, const FigureModel& figure, const MocapClip& clip,
                           const std::string& file, const std::string& path);

// The clip of a figure's mocap, its file relative to the scene file's folder; refusals at
// `path`.mocap.file.
MocapClip load_figure_mocap(const MocapDef& mocap, const std::string& file,
                            const std::string& path);

// Frames a clip may have: the longest trajectory a controller may hold.
inline constexpr int kMaxMocapFrames = 216000;

}  // namespace pbm
