// What a track may drive, described once: the table of track targets that the scene reader
// (checking and storing a track's "target"), the Model (sim/model.cpp, compiling a track), the
// recorded mouse drags (sim/runner.cpp), the studio (which field under edit can be keyed) and the
// schema's pattern (tests) all read.
//
// A target's text is a pattern over the scene: "{i}" is an item of the owner's list, "{k}" a
// component or shape parameter index, "{name}" a shape parameter by name. Tracks are stored in
// the index form (`text`); the reader also accepts a parameter by name and an obstacle's point
// under its kind's own key, and rewrites them.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace pbm {

enum class TrackTarget {
  body_rest_parameter,
  gravity,
  spring_target,
  spring_stiffness,
  camera_position,
  camera_target,
  camera_fov,
  obstacle_point,     // obstacles[i].point[k]: plane point, box centre, mesh origin
  obstacle_rotation,  // obstacles[i].rotation[k]: rotation vector applied before the orientation
  liquid_surface_pressure,  // liquids[i].surface_pressure (16.6.2)
  liquid_inflow_velocity    // liquids[i].inflow_velocity[k]: every inflow of liquid i (16.6.1)
};

// TrackTargetFormat::components of a target indexed by the body's shape parameters.
inline constexpr int kShapeParameterComponents = -1;

struct TrackTargetFormat {
  TrackTarget target = TrackTarget::gravity;
  // The list of the scene whose item {i} is ("bodies", "springs", "obstacles", "liquids"),
  // "camera", or ""
  // for the scene itself.
  std::string_view owner{};
  std::string_view text{};        // as stored: "bodies[{i}].q_s0[{k}]"
  std::string_view named_text{};  // by parameter name, stored as `text`: "bodies[{i}].q_s0.{name}"
  // The point under the key that holds it for an obstacle's kind ("center" of a box, "position"
  // of a mesh), accepted where the obstacle has that key and stored as `text`.
  std::array<std::string_view, 2> kind_texts{};
  // The key of the file it drives (RFC 6901 into scene_to_json's output), where the studio keys
  // the field under edit; a kind text's key is its text as a pointer.
  std::string_view pointer{};
  int components = 0;            // k < components; 0: no k; kShapeParameterComponents: k < n_s
  std::string_view component{};  // what k counts, for messages
  std::string_view description{};
};

inline constexpr std::array<TrackTargetFormat, 11> kTrackTargets{{
    {.target = TrackTarget::body_rest_parameter,
     .owner = "bodies",
     .text = "bodies[{i}].q_s0[{k}]",
     .named_text = "bodies[{i}].q_s0.{name}",
     .pointer = "/bodies/{i}/shape/rest/{name}",
     .components = kShapeParameterComponents,
     .component = "shape parameter",
     .description = "Rest value of shape parameter k of body i (morphing, fig. 6.7)."},
    {.target = TrackTarget::gravity,
     .text = "gravity[{k}]",
     .pointer = "/gravity/{k}",
     .components = 3,
     .component = "gravity component",
     .description = "Component k of gravity."},
    {.target = TrackTarget::spring_target,
     .owner = "springs",
     .text = "springs[{i}].target[{k}]",
     .pointer = "/springs/{i}/target/{k}",
     .components = 3,
     .component = "target component",
     .description = "Component k of spring i's target (recorded drags)."},
    {.target = TrackTarget::spring_stiffness,
     .owner = "springs",
     .text = "springs[{i}].stiffness",
     .pointer = "/springs/{i}/stiffness",
     .description = "Stiffness of spring i."},
    {.target = TrackTarget::camera_position,
     .owner = "camera",
     .text = "camera.position[{k}]",
     .pointer = "/camera/position/{k}",
     .components = 3,
     .component = "camera component",
     .description = "Component k of the camera's position."},
    {.target = TrackTarget::camera_target,
     .owner = "camera",
     .text = "camera.target[{k}]",
     .pointer = "/camera/target/{k}",
     .components = 3,
     .component = "camera component",
     .description = "Component k of the point the camera looks at."},
    {.target = TrackTarget::camera_fov,
     .owner = "camera",
     .text = "camera.fov",
     .pointer = "/camera/fov",
     .description = "The camera's vertical field of view [degrees]."},
    {.target = TrackTarget::obstacle_point,
     .owner = "obstacles",
     .text = "obstacles[{i}].point[{k}]",
     .kind_texts = {"obstacles[{i}].center[{k}]", "obstacles[{i}].position[{k}]"},
     .pointer = "/obstacles/{i}/point/{k}",
     .components = 3,
     .component = "point component",
     .description = "Component k of obstacle i's position: a plane's point, a box's centre, a "
                    "mesh's origin."},
    {.target = TrackTarget::obstacle_rotation,
     .owner = "obstacles",
     .text = "obstacles[{i}].rotation[{k}]",
     .components = 3,
     .component = "rotation component",
     .description = "Component k of a rotation vector r [rad], world frame, turning obstacle i "
                    "about its point: R(t) = exp(r(t)) R_orientation."},
    {.target = TrackTarget::liquid_surface_pressure,
     .owner = "liquids",
     .text = "liquids[{i}].surface_pressure",
     .pointer = "/liquids/{i}/surface_pressure",
     .description = "The pressure applied on liquid i's free surface [Pa] (a surface pressure "
                    "history, 16.6.2)."},
    {.target = TrackTarget::liquid_inflow_velocity,
     .owner = "liquids",
     .text = "liquids[{i}].inflow_velocity[{k}]",
     .components = 3,
     .component = "velocity component",
     .description = "Component k of the velocity of every inflow of liquid i [m/s] (time-dependent "
                    "inflow, 16.6.1); markers are released in proportion to it."},
}};

// A stored target taken apart: which value, of which item, which component.
struct TrackTargetRef {
  TrackTarget target = TrackTarget::gravity;
  int object = 0;  // body, spring or obstacle index (0 when the target has no {i})
  int index = 0;   // component or shape parameter (0 when the target has no {k})
};

// `text` in the index form, taken apart; nullopt if it is no stored target's form. Does not
// check the indices against a scene.
std::optional<TrackTargetRef> parse_track_target(std::string_view text);

// The index form of `target` for item i, component k: ("springs[{i}].target[{k}]", 2, 1) ->
// "springs[2].target[1]".
std::string format_track_target(TrackTarget target, int i, int k);

// Checks `text` against `scene` and returns it in the index form; "" with `problem` set (why,
// naming the expected forms) when it drives nothing of the scene.
std::string resolve_track_target(const Scene& scene, std::string_view text, std::string& problem);

// The target that drives the file's key at `pointer` ("/bodies/0/shape/rest/a1" ->
// "bodies[0].q_s0[1]", "/obstacles/1/center/2" -> "obstacles[1].point[2]" for a box), or "".
std::string track_target_of_key(const Scene& scene, std::string_view pointer);

// A regular expression (ECMA, as JSON Schema's "pattern") matching every accepted form.
std::string track_target_pattern();

}  // namespace pbm
