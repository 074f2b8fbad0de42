// The read-only view of the format's tables (scene/scene_format.h).
#include "scene/scene_format.h"

#include "scene/scene_sections.h"

namespace pbm {

std::vector<SectionDescription> describe_scene_format() {
  return {describe_section(kSceneSection),        describe_section(kSolverSection),
          describe_section(kCameraSection),       describe_section(kBodySection),
          describe_section(kShapeSection),        describe_section(kTessellationSection),
          describe_section(kMaterialSection),     describe_section(kObstacleSection),
          describe_section(kForceFieldSection),   describe_section(kSpringSection),
          describe_section(kConstraintSection),   describe_section(kConstraintEndSection),
          describe_section(kTrackSection),        describe_section(kFigureSection),
          describe_section(kSegmentSection),      describe_section(kJointSection),
          describe_section(kSegmentShapeSection), describe_section(kSiteSection),
          describe_section(kControllerSection),   describe_section(kSegmentPairSection),
          describe_section(kImpulseSection),      describe_section(kSiteActuatorSection),
          describe_section(kMocapSection),        describe_section(kMocapJointSection),
          describe_section(kMocapSiteSection),    describe_section(kLiquidSection),
          describe_section(kFluidRegionSection),  describe_section(kLiquidBoxSection),
          describe_section(kInflowSection),       describe_section(kSurfaceWaveSection)};
}

const SectionDescription* find_section(const std::vector<SectionDescription>& sections,
                                       std::string_view name) {
  for (const SectionDescription& section : sections) {
    if (section.name == name) return &section;
  }
  return nullptr;
}

std::optional<FieldDescription> describe_scene_key(const std::vector<SectionDescription>& sections,
                                                   std::string_view json_pointer) {
  const SectionDescription* section = find_section(sections, "");
  const FieldDescription* field = nullptr;  // the key the pointer has reached
  bool in_list = false;                     // the next token is an item of field's list
  if (!json_pointer.starts_with("/")) return std::nullopt;
  json_pointer.remove_prefix(1);
  while (true) {
    const std::size_t slash = json_pointer.find('/');
    const std::string_view token = json_pointer.substr(0, slash);
    if (field && (in_list || field->format.type != ValueType::object)) {
      // An item of a list leads to its section's keys; an entry of a vector is described by
      // the vector's key.
      const bool is_index =
          !token.empty() && token.find_first_not_of("0123456789") == std::string_view::npos;
      if (!is_index) return std::nullopt;
      if (field->format.type == ValueType::list) {
        section = find_section(sections, field->format.section);
        field = nullptr;
      }
    } else {
      if (field) section = find_section(sections, field->format.section);
      if (!section) return std::nullopt;
      field = nullptr;
      for (const FieldDescription& candidate : section->fields) {
        if (candidate.format.key == token) field = &candidate;
      }
      if (!field) return std::nullopt;
      in_list = field->format.type == ValueType::list;
    }
    if (slash == std::string_view::npos) break;
    json_pointer.remove_prefix(slash + 1);
  }
  if (!field) return std::nullopt;
  return *field;
}

}  // namespace pbm
