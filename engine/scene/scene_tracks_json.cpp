// The "tracks[i]" section of a scene file (scenes/README.md): keyframed values, each driving one
// target of scene/track_targets.h.
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"
#include "scene/track_targets.h"

namespace pbm {

namespace {

// A recorded drag keys its targets at every mouse event: 100,000 keys are half an hour of
// dragging at 60 events a second.
constexpr Real kMaxKeysPerTrack = 100000;

// Two tracks driving one value would fight; the later one is refused.
void check_track(const JsonNode& node, TrackDef& track, const ReadContext& context) {
  const int same =
      earlier_with(context.scene.tracks, context.index, &TrackDef::target, track.target);
  if (same >= 0) {
    fail(JsonNode{node.value, child_path(node.path, "target"), node.file},
         "'" + track.target + "' is already driven by tracks[" + std::to_string(same) + "]");
  }
}

constexpr auto kTrackFields = std::to_array<Field<TrackDef>>({
    {{.key = "target",
      .type = ValueType::track_target,
      .required = true,
      .description = "The value driven (scene/track_targets.h); stored in index form."},
     [](const FieldFormat&, const JsonNode& node, TrackDef& track, const ReadContext& context) {
       std::string problem;
       track.target = resolve_track_target(context.scene, read_string(node), problem);
       if (track.target.empty()) fail(node, problem);
     },
     write_value<&TrackDef::target>},
    choice<&TrackDef::interpolation, kInterpolationNames>(
        {.key = "interpolation",
         .description = "Between keys; step holds a key's value until the next (recorded "
                        "drags)."}),
    keyframes<&TrackDef::keys>(
        {.key = "keys",
         .limit = kMaxKeysPerTrack,
         .required = true,
         .description = "[time s, value] pairs, at least one, strictly increasing in time."}),
});

}  // namespace

constexpr Section<TrackDef> kTrackSection{
    .name = "track", .noun = "track", .fields = kTrackFields, .check = check_track};

}  // namespace pbm
