#include "figure/mocap_clip.h"

#include <assimp/scene.h>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <stdexcept>

#include "core/quaternion.h"

namespace pbm {

namespace {

// Depth first from the root, so that each parent comes before its children.
void add_joints(const aiNode* node, int parent, MocapClip& clip) {
  MocapJoint joint;
  joint.name = node->mName.C_Str();
  joint.parent = parent;
  const aiMatrix4x4& m = node->mTransformation;
  joint.offset = Vec3(m.a4, m.b4, m.c4);
  const int index = static_cast<int>(clip.joints.size());
  clip.joints.push_back(std::move(joint));
  for (unsigned int c = 0; c < node->mNumChildren; ++c) add_joints(node->mChildren[c], index, clip);
}

// The key of `keys` at frame k: assimp keeps one key per frame for an animated channel and a
// single key for a constant one.
template <class Key>
const Key& key_at(const Key* keys, unsigned int count, int k) {
  return keys[std::min<unsigned int>(static_cast<unsigned int>(k), count - 1)];
}

}  // namespace

int MocapClip::find(const std::string& name) const {
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].name == name) return static_cast<int>(j);
  }
  return -1;
}

MocapClip load_mocap_clip(const std::string& path, int max_frames) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr) throw std::runtime_error(importer.GetErrorString());
  if (scene->mNumAnimations == 0 || scene->mAnimations[0]->mNumChannels == 0) {
    throw std::runtime_error("the file has no animation");
  }
  const aiAnimation& animation = *scene->mAnimations[0];
  if (!(animation.mTicksPerSecond > 0) || !std::isfinite(animation.mTicksPerSecond)) {
    throw std::runtime_error("the animation has no frame time");
  }
  MocapClip clip;
  clip.frame_time = 1 / animation.mTicksPerSecond;
  const double frames = std::round(animation.mDuration) + 1;
  if (!(frames >= 1) || frames > max_frames) {
    throw std::runtime_error("the animation has " + std::to_string(frames) + " frames; at most " +
                             std::to_string(max_frames) + " are read");
  }
  clip.frames = static_cast<int>(frames);
  add_joints(scene->mRootNode, -1, clip);
  // A joint without a channel keeps its file rotation (identity in BVH) in every frame.
  for (MocapJoint& joint : clip.joints) joint.rotation.assign(clip.frames, Vec4(1, 0, 0, 0));
  for (unsigned int c = 0; c < animation.mNumChannels; ++c) {
    const aiNodeAnim& channel = *animation.mChannels[c];
    const int j = clip.find(channel.mNodeName.C_Str());
    if (j < 0 || channel.mNumRotationKeys == 0) continue;
    MocapJoint& joint = clip.joints[j];
    for (int k = 0; k < clip.frames; ++k) {
      const aiQuaternion& q = key_at(channel.mRotationKeys, channel.mNumRotationKeys, k).mValue;
      joint.rotation[k] = Vec4(q.w, q.x, q.y, q.z).normalized();
    }
    if (joint.parent < 0 && channel.mNumPositionKeys > 0) {
      joint.position.resize(clip.frames);
      for (int k = 0; k < clip.frames; ++k) {
        const aiVector3D& p = key_at(channel.mPositionKeys, channel.mNumPositionKeys, k).mValue;
        joint.position[k] = Vec3(p.x, p.y, p.z);
      }
    }
  }
  for (const MocapJoint& joint : clip.joints) {
    for (const Vec4& q : joint.rotation) {
      if (!q.allFinite()) throw std::runtime_error("joint '" + joint.name + "' has a NaN rotation");
    }
    for (const Vec3& p : joint.position) {
      if (!p.allFinite()) throw std::runtime_error("joint '" + joint.name + "' has a NaN position");
    }
  }
  return clip;
}

void mocap_pose(const MocapClip& clip, int frame, std::vector<Mat3>& rotation,
                std::vector<Vec3>& position) {
  rotation.resize(clip.joints.size());
  position.resize(clip.joints.size());
  for (std::size_t j = 0; j < clip.joints.size(); ++j) {
    const MocapJoint& joint = clip.joints[j];
    const Mat3 local = rotation_from_quaternion(joint.rotation[frame]);
    if (joint.parent < 0) {
      rotation[j] = local;
      position[j] = joint.position.empty() ? joint.offset : joint.position[frame];
    } else {
      rotation[j] = rotation[joint.parent] * local;
      position[j] = position[joint.parent] + rotation[joint.parent] * joint.offset;
    }
  }
}

}  // namespace pbm
