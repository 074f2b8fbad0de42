// The "figures[i]" section of a scene file (scenes/README.md, ch. 15): each figure's segments, the
// joint that joins each to its parent, its shape and its sites. A figure is compiled once it is
// read (figure/figure_build.h), so a cycle, a missing parent or a massless segment is refused by
// the reader with the path of the key at fault.
#include "figure/figure_build.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

// How many items each list may hold (scenes/README.md, "Limits"): far above a humanoid or the
// crane, low enough that the recursions' workspaces stay small.
constexpr Real kMaxSegments = 1024;
constexpr Real kMaxSites = 64;
constexpr Real kMaxJointCoordinates = 7;            // a free joint's q: position and quaternion
constexpr Real kMaxControllers = 6 * kMaxSegments;  // one per DOF

constexpr std::uint32_t kHasAxis =
    kind_bit(JointKind::revolute) | kind_bit(JointKind::prismatic) | kind_bit(JointKind::universal);
constexpr std::uint32_t kUniversal = kind_bit(JointKind::universal);
constexpr std::uint32_t kHasSpring = kHasAxis | kind_bit(JointKind::spherical);

// A controller's live keys: [time, value] or [time, value, rate], times strictly increasing
// (control/controller_def.h, LiveKey).
std::vector<LiveKey> read_live_keys(const FieldFormat& format, const JsonNode& node) {
  const std::size_t n = require_array(node);
  if (n == 0) fail(node, "must have at least one key [time, value]");
  if (static_cast<Real>(n) > format.limit) {
    fail(node,
         "must have at most " + bound_text(format.limit) + " keys (got " + std::to_string(n) + ")");
  }
  std::vector<LiveKey> keys;
  keys.reserve(n);
  for (std::size_t j = 0; j < n; ++j) {
    const JsonNode key = element(node, j);
    if (!key.value->is_array() || key.value->size() < 2 || key.value->size() > 3) {
      fail(key, "must be [time, value] or [time, value, rate], numbers");
    }
    LiveKey k{read_real(element(key, 0)), read_real(element(key, 1)), 0};
    if (key.value->size() == 3) k.rate = read_real(element(key, 2));
    if (!(k.time >= 0)) fail(element(key, 0), "must be >= 0");
    if (j > 0 && !(k.time > keys.back().time)) {
      fail(key, "time " + format_real(k.time) + " must be greater than the previous key's time " +
                    format_real(keys.back().time));
    }
    keys.push_back(k);
  }
  return keys;
}

// A joint's q0 or v0: as many numbers as the joint has coordinates (checked when the figure is
// compiled, which knows the kind); empty, the default, is not written.
template <auto Member>
constexpr Field<JointDef> joint_numbers(FieldFormat format) {
  format.type = ValueType::numbers;
  format.limit = kMaxJointCoordinates;
  return {format,
          [](const FieldFormat& f, const JsonNode& node, JointDef& joint, const ReadContext&) {
            const std::size_t n = require_array(node);
            if (static_cast<Real>(n) > f.limit) {
              fail(node, "may have at most " + bound_text(f.limit) + " numbers");
            }
            const VecX values = read_reals(node, static_cast<int>(n));
            (joint.*Member).assign(values.data(), values.data() + values.size());
          },
          [](const FieldFormat& f, const JointDef& joint, OrderedJson& object) {
            if (!(joint.*Member).empty()) object[f.key] = joint.*Member;
          }};
}

constexpr auto kJointFields = std::to_array<Field<JointDef>>({
    choice<&JointDef::kind, kJointKindNames>(
        {.key = "kind",
         .description = "Revolute and prismatic (1 DOF), universal (2), spherical (3, a "
                        "quaternion), fixed (0), free (6: position and quaternion)."}),
    unit_vector<&JointDef::axis>({.key = "axis",
                                  .kinds = kHasAxis,
                                  .description = "The axis in the joint frame (universal: the "
                                                 "first, on the parent; normalized on load)."}),
    unit_vector<&JointDef::axis2>(
        {.key = "axis2",
         .kinds = kUniversal,
         .description = "Universal: the second axis, on the child (normalized on load)."}),
    value<&JointDef::position>(
        {.key = "position",
         .unit = "m",
         .description = "The joint frame's origin in the parent's frame (a root: in the world)."}),
    unit_vector<&JointDef::orientation>(
        {.key = "orientation",
         .description = "The joint frame's axes in the parent's, a quaternion (w, x, y, z)."}),
    value<&JointDef::damping>({.key = "damping",
                               .unit = "N m s/rad or N s/m",
                               .range = kNonNegative,
                               .description = "Joint damping: tau = -damping q-dot."}),
    value<&JointDef::stiffness>(
        {.key = "stiffness",
         .unit = "N m/rad or N/m",
         .range = kNonNegative,
         .kinds = kHasSpring,
         .description = "A joint spring toward rest: tau = -stiffness (q - rest) (spherical: "
                        "times the rotation vector from the rest orientation)."}),
    joint_numbers<&JointDef::rest>(
        {.key = "rest",
         .unit = "rad or m",
         .kinds = kHasSpring,
         .default_note = "at rest",
         .description = "The spring's rest coordinates, as many as q0 has (spherical: a "
                        "quaternion w, x, y, z)."}),
    joint_numbers<&JointDef::lower>(
        {.key = "lower",
         .unit = "rad or m",
         .kinds = kHasAxis,
         .default_note = "unlimited",
         .description = "Joint limits: the least q per DOF (with upper, one number per DOF)."}),
    joint_numbers<&JointDef::upper>({.key = "upper",
                                     .unit = "rad or m",
                                     .kinds = kHasAxis,
                                     .default_note = "unlimited",
                                     .description = "The greatest q per DOF, each above lower's."}),
    value<&JointDef::swing_limit>(
        {.key = "swing_limit",
         .unit = "rad",
         .range = kNonNegative,
         .kinds = kind_bit(JointKind::spherical),
         .description = "A swing cone: the angle between the child's z axis and the joint "
                        "frame's stays within it (0: none; below pi)."}),
    value<&JointDef::twist_limit>(
        {.key = "twist_limit",
         .unit = "rad",
         .range = kNonNegative,
         .kinds = kind_bit(JointKind::spherical),
         .description = "The twist about the child's z axis (its swing aside) stays within "
                        "[-twist_limit, twist_limit] (0: none; below pi)."}),
    value<&JointDef::limit_restitution>(
        {.key = "limit_restitution",
         .range = kUnitInterval,
         .kinds = kHasSpring,
         .description = "e of (15.2) when a DOF strikes its limit (or a swing its cone, a "
                        "twist its limit): "
                        "q-dot+ = -e q-dot-."}),
    joint_numbers<&JointDef::q0>(
        {.key = "q0",
         .unit = "rad or m",
         .default_note = "at rest",
         .description = "Initial coordinates: 1 (revolute, prismatic), 2 (universal), 4 "
                        "(spherical: w, x, y, z), 7 (free: x, y, z, w, qx, qy, qz)."}),
    joint_numbers<&JointDef::v0>(
        {.key = "v0",
         .unit = "rad/s or m/s",
         .default_note = "zero",
         .description = "Initial velocities, one per DOF (spherical, free: angular velocity "
                        "in the child's frame, then the free joint's linear velocity)."}),
});

constexpr auto kSegmentShapeFields = std::to_array<Field<SegmentShapeDef>>({
    choice<&SegmentShapeDef::kind, kSegmentShapeKindNames>(
        {.key = "kind", .description = "The segment's solid, of uniform density."}),
    value<&SegmentShapeDef::size>(
        {.key = "size",
         .unit = "m",
         .range = kPositive,
         .description = "Box: half extents; sphere: x = radius; cylinder, capsule: x = radius, "
                        "z = half length of the straight part along the shape's z."}),
    value<&SegmentShapeDef::center>({.key = "center",
                                     .unit = "m",
                                     .description = "The shape's centre in the segment's frame."}),
    unit_vector<&SegmentShapeDef::orientation>(
        {.key = "orientation",
         .description = "The shape's axes in the segment's frame, a quaternion (w, x, y, z)."}),
});

constexpr auto kSiteFields = std::to_array<Field<SiteDef>>({
    value<&SiteDef::name>({.key = "name", .non_empty = true, .default_note = "site<i>"}),
    value<&SiteDef::position>(
        {.key = "position", .unit = "m", .description = "In the segment's frame."}),
    unit_vector<&SiteDef::orientation>(
        {.key = "orientation",
         .description = "The site's axes in the segment's frame, a quaternion (w, x, y, z)."}),
});

constexpr std::uint32_t kMrac = kind_bit(ControllerKind::mrac);
constexpr std::uint32_t kPdServos =
    kind_bit(ControllerKind::pd) | kind_bit(ControllerKind::stable_pd);

// A trajectory is a few keys per second of motion; a recorded hour at 60 keys a second fits.
constexpr Real kMaxTrajectoryKeys = 216000;

constexpr auto kControllerFields = std::to_array<Field<ControllerDef>>({
    choice<&ControllerDef::kind, kControllerKindNames>(
        {.key = "kind",
         .description = "mrac: model reference adaptive control (15.10)-(15.17); pd: an explicit "
                        "PD servo; stable_pd: the PD servo taken at the step's end, stable at any "
                        "gain."}),
    value<&ControllerDef::joint>(
        {.key = "joint",
         .required = true,
         .non_empty = true,
         .description = "The segment whose parent joint it drives (revolute, prismatic, "
                        "universal or spherical)."}),
    value<&ControllerDef::dof>(
        {.key = "dof",
         .range = kNonNegative,
         .limit = 2,
         .description = "Which of the joint's DOFs (universal: 0 or 1; spherical: the component "
                        "0, 1 or 2 of its rotation vector)."}),
    choice<&ControllerDef::interpolation, kInterpolationNames>(
        {.key = "interpolation",
         .description = "Of the trajectory between keys; its derivatives give the desired "
                        "velocity and acceleration."}),
    keyframes<&ControllerDef::keys>(
        {.key = "keys",
         .unit = "rad or m",
         .limit = kMaxTrajectoryKeys,
         .required = true,
         .description = "The desired joint position: [time s, value] pairs, strictly increasing "
                        "in time (sec. 15.1.2)."}),
    {{.key = "live",
      .type = ValueType::keys,
      .unit = "rad or m",
      .limit = kMaxTrajectoryKeys,
      .default_note = "none",
      .description = "Targets set live from the studio's control panel (fig. 15.11), recorded: "
                     "[time s, value] or [time s, value, rate /s] keys that replace keys from "
                     "the first one's time on; each sets the desired position value + rate "
                     "(t - time) until the next (a nonzero rate is a jog)."},
     [](const FieldFormat& f, const JsonNode& node, ControllerDef& def, const ReadContext&) {
       def.live = read_live_keys(f, node);
     },
     [](const FieldFormat& f, const ControllerDef& def, OrderedJson& object) {
       if (def.live.empty()) return;
       OrderedJson keys = OrderedJson::array();
       for (const LiveKey& key : def.live) {
         keys.push_back(key.rate == 0 ? OrderedJson{key.time, key.value}
                                      : OrderedJson{key.time, key.value, key.rate});
       }
       object[f.key] = std::move(keys);
     }},
    value<&ControllerDef::settling_time>(
        {.key = "settling_time",
         .unit = "s",
         .range = kPositive,
         .kinds = kMrac,
         .description = "t_s of the reference model: lambda = 4 / t_s (15.11)."}),
    value<&ControllerDef::alpha>({.key = "alpha",
                                  .range = kNonNegative,
                                  .kinds = kMrac,
                                  .description = "Integral adaptation gain (15.16), (15.17)."}),
    value<&ControllerDef::beta>({.key = "beta",
                                 .range = kNonNegative,
                                 .kinds = kMrac,
                                 .description = "Proportional adaptation gain (15.16), (15.17)."}),
    value<&ControllerDef::adaptive_bias>(
        {.key = "adaptive_bias",
         .kinds = kMrac,
         .description = "Beyond the book: a bias torque adapted with the gains, so the DOF holds "
                        "where gravity pulls it without a steady error."}),
    value<&ControllerDef::kp>({.key = "kp",
                               .unit = "N m/rad or N/m",
                               .range = kNonNegative,
                               .kinds = kPdServos,
                               .description = "Stiffness of the servo."}),
    value<&ControllerDef::kd>({.key = "kd",
                               .unit = "N m s/rad or N s/m",
                               .range = kNonNegative,
                               .kinds = kPdServos,
                               .description = "Damping of the servo."}),
    value<&ControllerDef::max_output>(
        {.key = "max_output",
         .unit = "N m or N",
         .range = kPositive,
         .default_note = "unlimited",
         .description = "The actuator's limit |u|; MRAC's integrals freeze while it holds "
                        "(sec. 15.4.2)."}),
});

// Far above any scene's events and strings; low enough that a figure's lists stay small.
constexpr Real kMaxImpulses = 4096;
constexpr Real kMaxSiteActuators = 256;

constexpr auto kImpulseFields = std::to_array<Field<ImpulseDef>>({
    value<&ImpulseDef::time>({.key = "time",
                              .unit = "s",
                              .range = kNonNegative,
                              .required = true,
                              .description = "When: applied at the start of the substep that "
                                             "holds it."}),
    value<&ImpulseDef::segment>({.key = "segment",
                                 .required = true,
                                 .non_empty = true,
                                 .description = "The segment struck."}),
    value<&ImpulseDef::site>({.key = "site",
                              .default_note = "the segment's frame origin",
                              .description = "Where: one of the segment's sites."}),
    value<&ImpulseDef::linear>(
        {.key = "impulse", .unit = "N s", .description = "The impulse at the site."}),
    value<&ImpulseDef::angular>(
        {.key = "angular", .unit = "N m s", .description = "An impulsive couple on the segment."}),
    choice<&ImpulseDef::frame, kImpulseFrameNames>(
        {.key = "frame",
         .description = "The axes of impulse and angular: the world's or the site's at that "
                        "time."}),
});

constexpr auto kSiteActuatorFields = std::to_array<Field<SiteActuatorDef>>({
    value<&SiteActuatorDef::segment>({.key = "segment",
                                      .required = true,
                                      .non_empty = true,
                                      .description = "The segment pulled."}),
    value<&SiteActuatorDef::site>({.key = "site",
                                   .default_note = "the segment's frame origin",
                                   .description = "The site pulled: one of the segment's."}),
    choice<&SiteActuatorDef::interpolation, kInterpolationNames>(
        {.key = "interpolation",
         .description = "Of the path between keys; its derivative gives the desired velocity."}),
    keyframes<&SiteActuatorDef::x>({.key = "x",
                                    .unit = "m",
                                    .limit = kMaxTrajectoryKeys,
                                    .required = true,
                                    .description = "The path's world x: [time s, value] pairs."}),
    keyframes<&SiteActuatorDef::y>({.key = "y",
                                    .unit = "m",
                                    .limit = kMaxTrajectoryKeys,
                                    .required = true,
                                    .description = "The path's world y."}),
    keyframes<&SiteActuatorDef::z>({.key = "z",
                                    .unit = "m",
                                    .limit = kMaxTrajectoryKeys,
                                    .required = true,
                                    .description = "The path's world z."}),
    value<&SiteActuatorDef::stiffness>({.key = "stiffness",
                                        .unit = "N/m",
                                        .range = kPositive,
                                        .description = "The string's spring toward the path."}),
    value<&SiteActuatorDef::damping>({.key = "damping",
                                      .unit = "N s/m",
                                      .range = kNonNegative,
                                      .description = "Its damper on the velocity relative to "
                                                     "the path's."}),
    value<&SiteActuatorDef::max_force>({.key = "max_force",
                                        .unit = "N",
                                        .range = kPositive,
                                        .default_note = "unlimited",
                                        .description = "The actuator's limit |F|."}),
    value<&SiteActuatorDef::t_begin>({.key = "t_begin",
                                      .unit = "s",
                                      .range = kNonNegative,
                                      .description = "When it starts pulling."}),
    value<&SiteActuatorDef::t_end>({.key = "t_end",
                                    .unit = "s",
                                    .range = kNonNegative,
                                    .default_note = "forever",
                                    .description = "When it lets go, >= t_begin."}),
    value<&SiteActuatorDef::ramp>({.key = "ramp",
                                   .unit = "s",
                                   .range = kNonNegative,
                                   .description = "Its gains grow linearly from 0 over this "
                                                  "time from t_begin (a grab without a jolt)."}),
});

constexpr auto kMocapJointFields = std::to_array<Field<MocapJointDef>>({
    value<&MocapJointDef::bvh>(
        {.key = "bvh", .required = true, .non_empty = true, .description = "The clip's joint."}),
    value<&MocapJointDef::joint>({.key = "joint",
                                  .required = true,
                                  .non_empty = true,
                                  .description = "The segment whose parent joint (revolute, "
                                                 "universal or spherical) takes its angles."}),
});

constexpr auto kMocapSiteFields = std::to_array<Field<MocapSiteDef>>({
    value<&MocapSiteDef::bvh>({.key = "bvh",
                               .required = true,
                               .non_empty = true,
                               .description = "The clip's joint whose position is the marker."}),
    value<&MocapSiteDef::segment>({.key = "segment",
                                   .required = true,
                                   .non_empty = true,
                                   .description = "The segment pulled."}),
    value<&MocapSiteDef::site>({.key = "site",
                                .default_note = "the segment's frame origin",
                                .description = "The site pulled: one of the segment's."}),
});

}  // namespace

constexpr Section<MocapJointDef> kMocapJointSection{
    .name = "mocap_joint", .noun = "mocap joint", .fields = kMocapJointFields};
constexpr Section<MocapSiteDef> kMocapSiteSection{
    .name = "mocap_site", .noun = "mocap site", .fields = kMocapSiteFields};

namespace {

// A clip may map every joint of the largest figure.
constexpr Real kMaxMocapMaps = kMaxSegments;

constexpr auto kMocapFields = std::to_array<Field<MocapDef>>({
    value<&MocapDef::file>({.key = "file",
                            .required = true,
                            .non_empty = true,
                            .description = "A BVH file (or any skeleton animation assimp reads), "
                                           "relative to the scene file."}),
    value<&MocapDef::scale>({.key = "scale",
                             .unit = "m",
                             .range = kPositive,
                             .description = "The clip's length unit (BVH: usually cm)."}),
    value<&MocapDef::position>(
        {.key = "position", .unit = "m", .description = "Where the clip's origin sits."}),
    unit_vector<&MocapDef::orientation>(
        {.key = "orientation",
         .description = "The clip's axes in the world's, a quaternion (w, x, y, z); a Y-up "
                        "clip stands up with [0.7071, 0.7071, 0, 0]."}),
    value<&MocapDef::start>({.key = "start",
                             .unit = "s",
                             .range = kNonNegative,
                             .description = "The scene time of the clip's first frame."}),
    list<&MocapDef::joints, kMocapJointSection>(
        {.key = "joints",
         .limit = kMaxMocapMaps,
         .section = "mocap_joint",
         .description = "Clip joints whose angles the figure's joints follow, by servos."}),
    list<&MocapDef::sites, kMocapSiteSection>(
        {.key = "sites",
         .limit = kMaxMocapMaps,
         .section = "mocap_site",
         .description = "Clip joints whose positions the figure's sites follow, by site "
                        "actuators."}),
    choice<&MocapDef::controller, kControllerKindNames>(
        {.key = "controller", .description = "The law of the joints' servos."}),
    value<&MocapDef::kp>({.key = "kp",
                          .unit = "N m/rad",
                          .range = kNonNegative,
                          .description = "pd, stable_pd: the servos' stiffness."}),
    value<&MocapDef::kd>({.key = "kd",
                          .unit = "N m s/rad",
                          .range = kNonNegative,
                          .description = "pd, stable_pd: their damping."}),
    value<&MocapDef::settling_time>({.key = "settling_time",
                                     .unit = "s",
                                     .range = kPositive,
                                     .description = "mrac: t_s of the reference model."}),
    value<&MocapDef::alpha>(
        {.key = "alpha", .range = kNonNegative, .description = "mrac: integral adaptation gain."}),
    value<&MocapDef::beta>({.key = "beta",
                            .range = kNonNegative,
                            .description = "mrac: proportional adaptation gain."}),
    value<&MocapDef::adaptive_bias>(
        {.key = "adaptive_bias",
         .description = "mrac: an adaptive bias torque (beyond the book)."}),
    value<&MocapDef::max_output>({.key = "max_output",
                                  .unit = "N m",
                                  .range = kPositive,
                                  .default_note = "unlimited",
                                  .description = "The servos' limit |u|."}),
    value<&MocapDef::stiffness>({.key = "stiffness",
                                 .unit = "N/m",
                                 .range = kPositive,
                                 .description = "The site actuators' spring."}),
    value<&MocapDef::damping>(
        {.key = "damping", .unit = "N s/m", .range = kNonNegative, .description = "Their damper."}),
    value<&MocapDef::max_force>({.key = "max_force",
                                 .unit = "N",
                                 .range = kPositive,
                                 .default_note = "unlimited",
                                 .description = "Their limit |F|."}),
});

}  // namespace

constexpr Section<MocapDef> kMocapSection{.name = "mocap", .noun = "mocap", .fields = kMocapFields};

constexpr Section<ImpulseDef> kImpulseSection{
    .name = "impulse", .noun = "impulse", .fields = kImpulseFields};

constexpr Section<SiteActuatorDef> kSiteActuatorSection{
    .name = "site_actuator", .noun = "site actuator", .fields = kSiteActuatorFields};

constexpr Section<ControllerDef> kControllerSection{
    .name = "controller",
    .noun = "controller",
    .fields = kControllerFields,
    .kind_of = [](const ControllerDef& c) { return static_cast<int>(c.kind); },
    .kind_names = kNameList<kControllerKindNames>};

constexpr Section<JointDef> kJointSection{
    .name = "joint",
    .noun = "joint",
    .fields = kJointFields,
    .kind_of = [](const JointDef& j) { return static_cast<int>(j.kind); },
    .kind_names = kNameList<kJointKindNames>};

constexpr Section<SegmentShapeDef> kSegmentShapeSection{
    .name = "segment_shape", .noun = "segment shape", .fields = kSegmentShapeFields};

constexpr Section<SiteDef> kSiteSection{.name = "site",
                                        .noun = "site",
                                        .fields = kSiteFields,
                                        .init = [](SiteDef& s, const ReadContext& context) {
                                          s.name = "site" + std::to_string(context.index);
                                        }};

namespace {

constexpr auto kSegmentFields = std::to_array<Field<SegmentDef>>({
    value<&SegmentDef::name>({.key = "name", .non_empty = true, .default_note = "segment<i>"}),
    value<&SegmentDef::parent>(
        {.key = "parent",
         .description = "The parent segment's name, an earlier segment; \"\": the root, "
                        "joined to the world."}),
    object<&SegmentDef::joint, kJointSection>(
        {.key = "joint", .section = "joint", .description = "The joint to the parent."}),
    object<&SegmentDef::shape, kSegmentShapeSection>(
        {.key = "shape", .section = "segment_shape", .description = "Its geometry."}),
    {{.key = "mass",
      .unit = "kg",
      .range = kNonNegative,
      .default_note = "density times the shape's volume",
      .description = "The segment's mass (centre and inertia from the shape)."},
     read_value<&SegmentDef::mass>,
     [](const FieldFormat& f, const SegmentDef& s, OrderedJson& object) {
       if (s.mass > 0) object[f.key] = s.mass;
     }},
    value<&SegmentDef::density>(
        {.key = "density", .unit = "kg/m^3", .range = kPositive, .description = "Without mass."}),
    value<&SegmentDef::color>({.key = "color", .range = kUnitInterval, .description = "RGB."}),
    list<&SegmentDef::sites, kSiteSection>({.key = "sites",
                                            .limit = kMaxSites,
                                            .section = "site",
                                            .description = "Attachment frames (sec. 15.1.1)."}),
});

}  // namespace

constexpr Section<SegmentDef> kSegmentSection{
    .name = "segment",
    .noun = "segment",
    .fields = kSegmentFields,
    .init = [](SegmentDef& s, const ReadContext& context) {
      s.name = "segment" + std::to_string(context.index);
    }};

namespace {

constexpr auto kSegmentPairFields = std::to_array<Field<SegmentPairDef>>({
    value<&SegmentPairDef::a>(
        {.key = "a", .required = true, .non_empty = true, .description = "A segment's name."}),
    value<&SegmentPairDef::b>({.key = "b",
                               .required = true,
                               .non_empty = true,
                               .description = "Another segment's name."}),
});

}  // namespace

constexpr Section<SegmentPairDef> kSegmentPairSection{
    .name = "segment_pair", .noun = "segment pair", .fields = kSegmentPairFields};

namespace {

// A figure has at most kMaxSegments (kMaxSegments - 1) / 2 pairs.
constexpr Real kMaxSegmentPairs = kMaxSegments * (kMaxSegments - 1) / 2;

constexpr auto kFigureFields = std::to_array<Field<FigureDef>>({
    value<&FigureDef::name>({.key = "name", .non_empty = true, .default_note = "figure<i>"}),
    list<&FigureDef::segments, kSegmentSection>({.key = "segments",
                                                 .range = {.lo = 1},
                                                 .limit = kMaxSegments,
                                                 .required = true,
                                                 .section = "segment",
                                                 .description = "Parents before children."}),
    value<&FigureDef::restitution>({.key = "restitution",
                                    .range = kUnitInterval,
                                    .description = "e of (15.2) at impacts (two figures: the "
                                                   "smaller of theirs)."}),
    value<&FigureDef::impact_speed>(
        {.key = "impact_speed",
         .unit = "m/s",
         .range = kNonNegative,
         .description = "Approaches faster than this are impacts (15.1)-(15.8); slower ones are "
                        "left to the contact springs."}),
    value<&FigureDef::contact_stiffness>(
        {.key = "contact_stiffness",
         .unit = "N/m",
         .range = kPositive,
         .description = "The contact stage's spring, per contact point."}),
    value<&FigureDef::contact_damping>({.key = "contact_damping",
                                        .unit = "N s/m",
                                        .range = kNonNegative,
                                        .description = "Its damper, per contact point."}),
    value<&FigureDef::self_collisions>(
        {.key = "self_collisions",
         .description = "Its segments collide with each other (never a segment with its parent "
                        "or children, nor the non_colliding pairs, nor pairs that overlap at "
                        "the initial pose)."}),
    value<&FigureDef::figure_collisions>(
        {.key = "figure_collisions",
         .description = "Its segments collide with other figures' (unless theirs do not)."}),
    value<&FigureDef::body_collisions>(
        {.key = "body_collisions",
         .description = "Its segments collide with the deformable bodies: they dent them and are "
                        "pushed back (both ways)."}),
    list<&FigureDef::non_colliding, kSegmentPairSection>(
        {.key = "non_colliding",
         .limit = kMaxSegmentPairs,
         .section = "segment_pair",
         .description = "Pairs of its segments that never collide."}),
    value<&FigureDef::friction>(
        {.key = "friction",
         .range = kNonNegative,
         .description = "Coulomb's mu between segments (two figures: the geometric mean of "
                        "theirs); with obstacles, the obstacle's friction holds."}),
    list<&FigureDef::controllers, kControllerSection>(
        {.key = "controllers",
         .limit = kMaxControllers,
         .section = "controller",
         .description = "Joint controllers following trajectories (sec. 15.4), one per DOF at "
                        "most."}),
    list<&FigureDef::site_actuators, kSiteActuatorSection>(
        {.key = "site_actuators",
         .limit = kMaxSiteActuators,
         .section = "site_actuator",
         .description = "Site trajectories (sec. 15.4): springs pulling sites along paths, "
                        "like marionette strings."}),
    list<&FigureDef::impulses, kImpulseSection>(
        {.key = "impulses",
         .limit = kMaxImpulses,
         .section = "impulse",
         .description = "Impulses at sites at given times (sec. 15.3, fig. 15.6)."}),
    object<&FigureDef::mocap, kMocapSection>(
        {.key = "mocap",
         .section = "mocap",
         .default_note = "none",
         .description = "Motion capture driving joints and sites, by a name map."}),
});

// The whole figure compiled as soon as it is read: its tree, masses, inertias, axes and initial
// state are refused here, at the path of the key at fault, rather than when a Model is built.
void check_figure(const JsonNode& node, FigureDef& figure, const ReadContext& context) {
  (void)build_figure_model(figure, *node.file, node.path);
  if (earlier_with(context.scene.figures, context.index, &FigureDef::name, figure.name) >= 0) {
    const std::optional<JsonNode> name = find_child(node, "name");
    fail(name ? *name : node, "'" + figure.name + "' names an earlier figure");
  }
}

}  // namespace

// A pendulum of one capsule hanging from a hinge 2 m up, for the studio's "add".
constexpr Section<FigureDef> kFigureSection{
    .name = "figure",
    .noun = "figure",
    .fields = kFigureFields,
    .init = [](FigureDef& f,
               const ReadContext& context) { f.name = "figure" + std::to_string(context.index); },
    .check = check_figure,
    .new_item = R"({"segments": [{"joint": {"kind": "revolute", "axis": [0, 1, 0],
                    "position": [0, 0, 2], "q0": [0.5]},
                    "shape": {"kind": "capsule", "size": [0.05, 0.05, 0.25],
                    "center": [0, 0, -0.35]}}]})"};

}  // namespace pbm
