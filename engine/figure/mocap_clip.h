// A motion-capture clip (sec. 15.4's trajectories from recorded motion): a skeleton of named
// joints, each with its offset from its parent and, per frame, its rotation relative to the
// parent (and the root's position), as a BVH file holds them. assimp reads the file; this keeps
// what the retargeting needs (figure/mocap_retarget.h) in plain arrays, and gives each joint's
// world position and orientation per frame by forward kinematics.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace pbm {

struct MocapJoint {
  std::string name;
  int parent = -1;             // an earlier joint; -1: the root
  Vec3 offset = Vec3::Zero();  // from the parent, in the parent's axes (file units)
  std::vector<Vec4> rotation;  // per frame: relative to the parent (w, x, y, z)
  std::vector<Vec3> position;  // per frame: the root's position (file units); else empty
};

struct MocapClip {
  Real frame_time = 0;  // [s]
  int frames = 0;
  std::vector<MocapJoint> joints;           // parents first
  int find(const std::string& name) const;  // -1 when none is so named
};

// Reads a BVH (or any skeleton animation assimp reads). Throws std::runtime_error saying why: an
// unreadable file, no animation, more than `max_frames` frames.
MocapClip load_mocap_clip(const std::string& path, int max_frames);

// Every joint's orientation (to the clip's world) and position (file units) at frame k.
void mocap_pose(const MocapClip& clip, int frame, std::vector<Mat3>& rotation,
                std::vector<Vec3>& position);

}  // namespace pbm
