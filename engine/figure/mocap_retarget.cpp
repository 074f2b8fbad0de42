#include "figure/mocap_retarget.h"

#include <cmath>
#include <filesystem>
#include <numbers>

#include "control/ball_coordinates.h"
#include "core/error.h"
#include "core/quaternion.h"
#include "figure/figure_impact.h"
#include "figure/figure_kinematics.h"
#include "figure/site_ref.h"

namespace pbm {

namespace {

constexpr Real kTwoPi = 2 * std::numbers::pi_v<Real>;

// The angle of R's twist about the unit axis a (swing-twist decomposition): 2 atan2(v . a, w).
Real twist_angle(const Mat3& R, const Vec3& a) {
  const Vec4 q = quaternion_from_rotation(R);
  return 2 * std::atan2(q.tail<3>().dot(a), q[0]);
}

// The angle about the unit axis a from u to v, both projected on the plane normal to a.
Real angle_about(const Vec3& a, const Vec3& u, const Vec3& v) {
  const Vec3 pu = u - u.dot(a) * a, pv = v - v.dot(a) * a;
  return std::atan2(a.dot(pu.cross(pv)), pu.dot(pv));
}

// theta moved by whole turns to lie within half a turn of the previous key's value.
Real unwrapped(Real theta, const std::vector<Keyframe>& keys) {
  if (keys.empty()) return theta;
  return theta + kTwoPi * std::round((keys.back().value - theta) / kTwoPi);
}

int segment_named(const FigureModel& figure, const std::string& name) {
  for (int i = 0; i < figure.size(); ++i) {
    if (figure.segments[i].name == name) return i;
  }
  return -1;
}

}  // namespace

MocapClip load_figure_mocap(const MocapDef& mocap, const std::string& file,
                            const std::string& path) {
  std::filesystem::path clip_path = mocap.file;
  if (clip_path.is_relative() && !file.empty()) {
    clip_path = std::filesystem::path(file).parent_path() / clip_path;
  }
  try {
    return load_mocap_clip(clip_path.string(), kMaxMocapFrames);
  } catch (const std::exception& e) {
    throw Error(file, path + ".mocap.file",
                "cannot use motion capture '" + clip_path.string() + "': " + e.what());
  }
}

MocapTracks retarget_mocap(const FigureDef& def, const FigureModel& figure, const MocapClip& clip,
                           const std::string& file, const std::string& path) {
  const MocapDef& mocap = *def.mocap;
  const std::string at = path + ".mocap";
  const Mat3 place = rotation_from_quaternion(mocap.orientation.normalized());
  // The joint frames at the neutral pose, in the world.
  FigureWorkspace ws;
  size_figure_workspace(figure, ws);
  VecX q0(figure.n_q);
  figure_neutral_q(figure, q0.data());
  figure_kinematics(figure, q0.data(), nullptr, ws);
  std::vector<SpatialTransform> world;
  segment_world_transforms(figure, ws, world);
  std::vector<std::vector<Mat3>> rotations(clip.frames);
  std::vector<std::vector<Vec3>> positions(clip.frames);
  for (int k = 0; k < clip.frames; ++k) mocap_pose(clip, k, rotations[k], positions[k]);
  const auto time_of = [&](int k) { return mocap.start + k * clip.frame_time; };
  const auto clip_joint = [&](const std::string& name, const std::string& key) {
    const int j = clip.find(name);
    if (j < 0) throw Error(file, key, "'" + name + "' names no joint of the motion capture");
    return j;
  };
  MocapTracks out;
  for (std::size_t m = 0; m < mocap.joints.size(); ++m) {
    const MocapJointDef& map = mocap.joints[m];
    const std::string key = at + ".joints[" + std::to_string(m) + "]";
    const int j = clip_joint(map.bvh, key + ".bvh");
    const int s = segment_named(figure, map.joint);
    if (s < 0) {
      throw Error(file, key + ".joint",
                  "'" + map.joint + "' names no segment of figure '" + figure.name + "'");
    }
    const SegmentModel& segment = figure.segments[s];
    const JointKind kind = segment.joint.kind;
    if (kind != JointKind::revolute && kind != JointKind::universal &&
        kind != JointKind::spherical) {
      throw Error(file, key + ".joint",
                  "segment '" + map.joint +
                      "' hangs on a joint that is not revolute, universal or spherical; map a "
                      "site instead");
    }
    for (const ControllerDef& c : def.controllers) {
      if (c.joint == map.joint) {
        throw Error(file, key + ".joint", "'" + map.joint + "' already has a controller");
      }
    }
    for (std::size_t earlier = 0; earlier < m; ++earlier) {
      if (mocap.joints[earlier].joint == map.joint) {
        throw Error(
            file, key + ".joint",
            "'" + map.joint + "' is already mapped (joints[" + std::to_string(earlier) + "])");
      }
    }
    // The joint frame's axes in the world at rest, and the clip's parent axes in the world.
    const SpatialTransform joint =
        segment.parent >= 0 ? segment.X_tree * world[segment.parent] : segment.X_tree;
    const Mat3 to_joint = joint.E * place;  // clip (world-aligned) axes -> joint axes
    const int dofs = kind == JointKind::spherical ? 3 : kind == JointKind::universal ? 2 : 1;
    std::vector<ControllerDef> dof(dofs);
    for (int d = 0; d < dofs; ++d) {
      ControllerDef& c = dof[d];
      c.kind = mocap.controller;
      c.joint = map.joint;
      c.dof = d;
      c.interpolation = Interpolation::smooth;
      c.keys.reserve(static_cast<std::size_t>(clip.frames));
      c.settling_time = mocap.settling_time;
      c.alpha = mocap.alpha;
      c.beta = mocap.beta;
      c.adaptive_bias = mocap.adaptive_bias;
      c.kp = mocap.kp;
      c.kd = mocap.kd;
      c.max_output = mocap.max_output;
    }
    for (int k = 0; k < clip.frames; ++k) {
      const Mat3 local = rotation_from_quaternion(clip.joints[j].rotation[k]);
      const Mat3 M = to_joint * local * to_joint.transpose();  // the rotation in joint axes
      if (kind == JointKind::spherical) {
        // The rotation vector of M (control/ball_coordinates.h), continued from the last key's.
        const Vec4 u = quaternion_from_rotation(M);
        Vec3 r = ball_rotation_vector(u.data());
        if (k > 0) {
          r = ball_rotation_vector_near(r, Vec3(dof[0].keys.back().value, dof[1].keys.back().value,
                                                dof[2].keys.back().value));
        }
        for (int d = 0; d < 3; ++d) dof[d].keys.push_back({time_of(k), r[d]});
        continue;
      }
      Real theta = 0, theta2 = 0;
      if (kind == JointKind::revolute) {
        theta = twist_angle(M, segment.joint.axis);
      } else {
        // R = Rot(a1, q0) Rot(a2, q1): q0 carries a2 where M does, q1 is what is left about a2.
        const Vec3& a1 = segment.joint.axis;
        const Vec3& a2 = segment.joint.axis2;
        theta = angle_about(a1, a2, M * a2);
        theta2 =
            twist_angle(Eigen::AngleAxis<Real>(theta, a1).toRotationMatrix().transpose() * M, a2);
      }
      dof[0].keys.push_back({time_of(k), unwrapped(theta, dof[0].keys)});
      if (dofs == 2) dof[1].keys.push_back({time_of(k), unwrapped(theta2, dof[1].keys)});
    }
    for (ControllerDef& c : dof) out.controllers.push_back(std::move(c));
  }
  for (std::size_t m = 0; m < mocap.sites.size(); ++m) {
    const MocapSiteDef& map = mocap.sites[m];
    const std::string key = at + ".sites[" + std::to_string(m) + "]";
    const int j = clip_joint(map.bvh, key + ".bvh");
    (void)find_site(def, figure, map.segment, map.site, file, key);
    SiteActuatorDef a;
    a.segment = map.segment;
    a.site = map.site;
    a.interpolation = Interpolation::smooth;
    a.stiffness = mocap.stiffness;
    a.damping = mocap.damping;
    a.max_force = mocap.max_force;
    for (int k = 0; k < clip.frames; ++k) {
      const Vec3 x = mocap.position + place * (mocap.scale * positions[k][j]);
      a.x.push_back({time_of(k), x.x()});
      a.y.push_back({time_of(k), x.y()});
      a.z.push_back({time_of(k), x.z()});
    }
    out.site_actuators.push_back(std::move(a));
  }
  return out;
}

}  // namespace pbm
