// The scene's description of an articulated figure (sec. 15.1.1): plain data with defaults, as a
// scene file states it. build_figure_model (figure/figure_build.h) checks it and compiles it into
// the FigureModel the recursions run on.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "control/controller_def.h"
#include "core/keyframes.h"
#include "core/types.h"
#include "figure/joint.h"

namespace pbm {

enum class SegmentShapeKind {
  box,       // size: half extents along x, y, z
  sphere,    // size.x: radius
  cylinder,  // size.x: radius, size.z: half length, axis along z
  capsule,   // size.x: radius, size.z: half length of the straight part, axis along z
};

// A segment's geometry, uniform density: its mass, centre and inertia follow from it (sec.
// 15.1.1: "the center of mass and inertia tensor of each segment can be automatically computed
// from the segment's geometry").
struct SegmentShapeDef {
  SegmentShapeKind kind = SegmentShapeKind::box;
  Vec3 size = Vec3::Constant(0.1);      // [m], see SegmentShapeKind
  Vec3 center = Vec3::Zero();           // the shape's centre in the segment's frame [m]
  Vec4 orientation = Vec4(1, 0, 0, 0);  // the shape's axes in the segment's frame (w, x, y, z)
};

// The segment's parent joint: where it sits on the parent (a site of the parent), its axes, its
// damping, and its initial position and velocity.
struct JointDef {
  JointKind kind = JointKind::revolute;
  Vec3 axis = Vec3::UnitZ();            // revolute, prismatic, universal's first (joint frame)
  Vec3 axis2 = Vec3::UnitY();           // universal's second
  Vec3 position = Vec3::Zero();         // the joint frame's origin in the parent's frame [m]
  Vec4 orientation = Vec4(1, 0, 0, 0);  // the joint frame's axes in the parent's (w, x, y, z)
  Real damping = 0;                     // joint damping [N m s/rad or N s/m], tau = -damping qdot
  // A joint spring toward `rest` [N m/rad or N/m]: tau = -stiffness (q - rest) per DOF; on a
  // spherical joint, -stiffness times the rotation vector from the rest orientation.
  Real stiffness = 0;
  std::vector<Real> rest;  // the spring's rest q (empty: the joint at rest, as q0)
  // Joint limits (revolute, prismatic, universal): per DOF, q stays within [lower, upper] (both
  // empty: unlimited). A DOF reaching its limit faster than the figure's impact_speed has an
  // impact of its own, q-dot+ = -limit_restitution q-dot- on that DOF (15.2); past it, a stiff
  // spring-damper pushes it back (figure/joint_limits.h).
  std::vector<Real> lower, upper;  // [rad or m]
  // Spherical joints: a swing cone, the angle between the child's z axis and the joint frame's
  // kept within swing_limit (0: none) [rad], in (0, pi).
  Real swing_limit = 0;
  // Spherical joints: the twist about the child's z axis (the swing-twist decomposition, the
  // swing leaving it) kept within [-twist_limit, twist_limit] (0: none) [rad], in (0, pi).
  Real twist_limit = 0;
  Real limit_restitution = 0;  // in [0, 1]
  std::vector<Real> q0;        // initial q (empty: at rest; a quaternion as w, x, y, z)
  std::vector<Real> v0;        // initial v (empty: zero)
};

// An attachment frame on a segment (sec. 15.1.1), for joints of children, actuators and drawing.
struct SiteDef {
  std::string name;
  Vec3 position = Vec3::Zero();
  Vec4 orientation = Vec4(1, 0, 0, 0);
};

struct SegmentDef {
  std::string name;
  std::string parent;  // empty: the figure's root, joined to the inertial frame
  JointDef joint;
  SegmentShapeDef shape;
  Real mass = 0;        // [kg]; 0: density times the shape's volume
  Real density = 1000;  // [kg/m^3], when mass is 0
  std::vector<SiteDef> sites;
  Vec3 color = Vec3(0.8, 0.75, 0.6);
};

// Two segments of one figure that never collide (by name).
struct SegmentPairDef {
  std::string a, b;
};

// The axes an impulse's vectors are given in.
enum class ImpulseFrame {
  world,  // the inertial frame's
  site,   // the site's, as it is at the impulse's time
};

// An impulse at a site at a time, a scene event (sec. 15.3: the wounded soldier of fig. 15.6
// falls from "a large initial impulse on the chest"). The figure's velocities jump by
// H dv = J^T P, its positions stay (figure/figure_impulse.h).
struct ImpulseDef {
  Real time = 0;        // [s], >= 0: applied in the substep whose interval holds it
  std::string segment;  // the segment struck
  std::string site;     // where on it: one of its sites; empty: its frame's origin (root site)
  Vec3 linear = Vec3::Zero();   // the impulse [N s], at the site
  Vec3 angular = Vec3::Zero();  // an impulsive couple [N m s]
  ImpulseFrame frame = ImpulseFrame::world;
};

// A site trajectory (sec. 15.4): a site actuator pulls its site along a keyframed path in the
// world, as a marionette's string pulls the puppet's hand, with the spring-damper
// F = stiffness (p(t) - x) + damping (p-dot(t) - x-dot), capped at max_force, acting at the
// site. Its work counts as the actuators' (the stability guard's input work).
struct SiteActuatorDef {
  std::string segment;  // the segment pulled
  std::string site;     // one of its sites; empty: its frame's origin
  Interpolation interpolation = Interpolation::smooth;
  std::vector<Keyframe> x, y, z;  // the path's world coordinates p(t) [m], each with keys
  Real stiffness = 1000;          // [N/m], > 0
  Real damping = 50;              // [N s/m], >= 0
  std::optional<Real> max_force;  // [N], > 0; none when absent
  // When it pulls [s]: from t_begin, its stiffness and damping growing linearly over `ramp`
  // seconds (a grab that must not jolt the figure), until t_end. The studio's mouse spring on a
  // figure is such an actuator, recorded into the scene.
  Real t_begin = 0;
  std::optional<Real> t_end;  // none: forever
  Real ramp = 0;
};

// Motion capture driving the figure (sec. 15.4's trajectories from recorded motion; issue:
// "a BVH file drives joint trajectories mapped by joint name, or site trajectories from marker
// positions; retargeting by a name map"). figure/mocap_retarget.h turns it into servos and site
// actuators when the figure is compiled.
struct MocapJointDef {
  std::string bvh;  // the clip's joint
  std::string
      joint;  // the segment whose parent joint (revolute, universal or spherical) follows it
};
struct MocapSiteDef {
  std::string bvh;      // the clip's joint, whose position is the marker
  std::string segment;  // the segment pulled
  std::string site;     // one of its sites; empty: its frame's origin
};
struct MocapDef {
  std::string file;   // BVH (or any skeleton animation assimp reads), relative to the scene file
  Real scale = 0.01;  // the clip's length unit in m (BVH: usually cm)
  Vec3 position = Vec3::Zero();         // where the clip's origin sits in the world [m]
  Vec4 orientation = Vec4(1, 0, 0, 0);  // the clip's axes in the world's (w, x, y, z)
  Real start = 0;                       // the scene time of the clip's first frame [s]
  std::vector<MocapJointDef> joints;
  std::vector<MocapSiteDef> sites;
  // The servos of the mapped joints (as ControllerDef's) and the site actuators' springs (as
  // SiteActuatorDef's).
  ControllerKind controller = ControllerKind::stable_pd;
  Real kp = 200, kd = 20;
  Real settling_time = 0.3, alpha = 10, beta = 2;
  bool adaptive_bias = false;  // mrac: ControllerDef::adaptive_bias
  std::optional<Real> max_output;
  Real stiffness = 1000, damping = 50;
  std::optional<Real> max_force;
};

struct FigureDef {
  std::string name;
  std::vector<SegmentDef> segments;
  // Contacts with obstacles, in the book's two stages (sec. 15.3): a segment reaching an obstacle
  // faster than impact_speed has an impact, its velocities jumping by (15.1)-(15.8) with
  // restitution e (15.2) and the obstacle's friction as Coulomb's mu; while it stays in contact,
  // a mild spring-damper at each contact point holds it out.
  Real restitution = 0;          // e of (15.2), in [0, 1]
  Real impact_speed = 0.1;       // [m/s], >= 0: slower approaches are left to the springs
  Real contact_stiffness = 2e4;  // [N/m] per contact point, > 0
  Real contact_damping = 200;    // [N s/m] per contact point, >= 0
  // Collisions between segments (sec. 15.3), in the same two stages: of this figure with each
  // other (never a segment with its parent or its children, nor the pairs in non_colliding), and
  // with other figures' segments unless either figure turns them off. Two figures' contact
  // combines their settings: the smaller restitution, impact_speed, stiffness and damping, and
  // the geometric mean of their friction.
  bool self_collisions = true;
  bool figure_collisions = true;
  // Collisions of its segments with the deformable bodies (sec. 15.3 with 5.2.2): a segment dents
  // a body and is pushed back by it (sim/segment_body_collisions.h).
  bool body_collisions = true;
  std::vector<SegmentPairDef> non_colliding;
  Real friction = 0.5;  // Coulomb's mu between segments, >= 0
  // Joint controllers (sec. 15.4), at most one per DOF.
  std::vector<ControllerDef> controllers;
  // Impulse events (any order; applied in time order) and site actuators.
  std::vector<ImpulseDef> impulses;
  std::vector<SiteActuatorDef> site_actuators;
  std::optional<MocapDef> mocap;
};

}  // namespace pbm
