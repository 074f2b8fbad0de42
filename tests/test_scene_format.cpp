// The format's tables (scene/scene_format.h) against everything else that describes the format:
// scenes/scene.schema.json has exactly their keys, types, ranges, limits, defaults and required
// keys; the parser's defaults are the tables' defaults; scenes/README.md documents every key and
// track target, and its full example loads and conforms to the schema.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "scene/scene_format.h"
#include "scene/track_targets.h"
#include "schema_validator.h"

namespace pbm::scene_test {
namespace {

// `node` with its "$ref"s followed: the referenced definition's keywords under the node's own.
json resolved(const json& root, json node) {
  while (node.contains("$ref")) {
    const std::string ref = node["$ref"];
    node.erase("$ref");
    for (const auto& [key, value] : root["$defs"][ref.substr(ref.rfind('/') + 1)].items()) {
      if (!node.contains(key)) node[key] = value;
    }
  }
  return node;
}

// The bounds JSON Schema states for `range` and `limit` ({"minimum": 0, "exclusiveMaximum": 1}).
json bounds_of(const Range& range, Real limit) {
  json bounds = json::object();
  if (std::isfinite(range.lo)) bounds[range.lo_open ? "exclusiveMinimum" : "minimum"] = range.lo;
  if (std::isfinite(range.hi)) bounds[range.hi_open ? "exclusiveMaximum" : "maximum"] = range.hi;
  if (std::isfinite(limit)) bounds["maximum"] = limit;
  return bounds;
}

json bounds_in(const json& schema) {
  json bounds = json::object();
  for (const char* key : {"minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum"}) {
    if (schema.contains(key)) bounds[key] = schema[key];
  }
  return bounds;
}

std::string ref_to(std::string_view section) {
  return "#/$defs/" + std::string(section);
}

// Whether the property `schema` (resolved) describes the row `format`; "" or what differs.
std::string compare(const json& root, const json& property, const FieldFormat& format) {
  const json p = resolved(root, property);
  const auto type_is = [&](const char* type) { return p.value("type", "") == type; };
  const auto vector_of = [&](int size, const Range& range) -> std::string {
    if (!type_is("array") || p.value("minItems", -1) != size || p.value("maxItems", -1) != size) {
      return "not an array of " + std::to_string(size);
    }
    const json items = resolved(root, p["items"]);
    if (items.value("type", "") != "number") return "items are not numbers";
    if (bounds_in(items) != bounds_of(range, kUnbounded)) return "item bounds " + items.dump();
    return "";
  };
  switch (format.type) {
    case ValueType::number:
    case ValueType::integer:
      if (!type_is(format.type == ValueType::number ? "number" : "integer")) return "type";
      if (bounds_in(p) != bounds_of(format.range, format.limit)) return "bounds " + p.dump();
      return "";
    case ValueType::boolean:
      return type_is("boolean") ? "" : "type";
    case ValueType::string:
      if (!type_is("string")) return "type";
      return p.value("minLength", 0) == (format.non_empty ? 1 : 0) ? "" : "minLength";
    case ValueType::choice: {
      json names = json::array();
      for (const std::string_view name : format.choices) names.push_back(name);
      return p.value("enum", json()) == names ? "" : "enum " + p.value("enum", json()).dump();
    }
    case ValueType::vector:
      return vector_of(format.size, format.range);
    case ValueType::quaternion:
    case ValueType::direction:
      return vector_of(format.size, kAny);
    case ValueType::material_point:
      return vector_of(2, kAny);
    case ValueType::object:
      return property.value("$ref", "") == ref_to(format.section) ? "" : "not the section's $ref";
    case ValueType::list: {
      if (!type_is("array") || p["items"].value("$ref", "") != ref_to(format.section)) {
        return "not an array of the section";
      }
      json counts = json::object();
      if (p.contains("minItems")) counts["minimum"] = p["minItems"];
      if (p.contains("maxItems")) counts["maximum"] = p["maxItems"];
      return counts == bounds_of(format.range, format.limit) ? "" : "item counts " + p.dump();
    }
    case ValueType::shape_vector:
      return property.value("$ref", "") == ref_to("shape_vector") ? "" : "not a shape_vector";
    case ValueType::body_reference:
      return property.value("$ref", "") == ref_to("body_reference") ? "" : "not a body_reference";
    case ValueType::body_references:
      return type_is("array") && p["items"].value("$ref", "") == ref_to("body_reference")
                 ? ""
                 : "not an array of body references";
    case ValueType::node_index:
      return type_is("integer") && p.value("minimum", -1) == 0 ? "" : "not a node index";
    case ValueType::track_target:
      return type_is("string") && p.value("pattern", "") == track_target_pattern()
                 ? ""
                 : "pattern differs from track_target_pattern(): " + track_target_pattern();
    case ValueType::numbers:
      return type_is("array") && !p.contains("minItems") &&
                     p.value("maxItems", 0.0) == format.limit &&
                     resolved(root, p["items"]).value("type", "") == "number"
                 ? ""
                 : "numbers " + p.dump();
    case ValueType::counts: {
      if (!type_is("array") || p.value("minItems", -1) != format.size ||
          p.value("maxItems", -1) != format.size) {
        return "not an array of " + std::to_string(format.size);
      }
      const json items = resolved(root, p["items"]);
      if (items.value("type", "") != "integer") return "items are not integers";
      if (bounds_in(items) != bounds_of(format.range, format.limit)) {
        return "item bounds " + items.dump();
      }
      return "";
    }
    case ValueType::keys:
      return type_is("array") && p.value("minItems", 0) == 1 &&
                     p.value("maxItems", 0.0) == format.limit
                 ? ""
                 : "keys " + p.dump();
  }
  return "unknown type";
}

TEST(SceneFormat, SchemaHasTheTablesKeysTypesRangesAndDefaults) {
  const json schema = load_schema();
  const std::vector<SectionDescription> sections = describe_scene_format();
  for (const SectionDescription& section : sections) {
    SCOPED_TRACE("section '" + std::string(section.name) + "'");
    const json& node = section.name.empty() ? schema : schema["$defs"][std::string(section.name)];
    ASSERT_TRUE(node.is_object());
    EXPECT_EQ(node.value("additionalProperties", json(true)), false);
    std::set<std::string> keys, schema_keys, required;
    for (const auto& [key, value] : node["properties"].items()) schema_keys.insert(key);
    for (const FieldDescription& field : section.fields) {
      const FieldFormat& format = field.format;
      const std::string key(format.key);
      keys.insert(key);
      if (format.required && format.kinds == kAllKinds) required.insert(key);
      if (!node["properties"].contains(key)) continue;
      const json& property = node["properties"][key];
      EXPECT_EQ(compare(schema, property, format), "") << key;
      const json stated = resolved(schema, property).value("default", json());
      EXPECT_EQ(stated, field.default_value) << key << ": the schema's default";
    }
    EXPECT_EQ(schema_keys, keys);
    std::set<std::string> schema_required;
    for (const json& key : node.value("required", json::array())) schema_required.insert(key);
    EXPECT_EQ(schema_required, required);
    // A group of which exactly one key is given is a oneOf of the schema.
    std::set<std::string> in_one_of, grouped;
    for (const json& option : node.value("oneOf", json::array())) {
      for (const json& key : option.value("required", json::array())) in_one_of.insert(key);
    }
    for (const FieldDescription& field : section.fields) {
      if (field.format.one_of) grouped.insert(std::string(field.format.key));
    }
    for (const std::string& key : grouped) EXPECT_TRUE(in_one_of.count(key)) << key;
  }
}

TEST(SceneFormat, EverySectionIsReachedFromTheScene) {
  const std::vector<SectionDescription> sections = describe_scene_format();
  std::set<std::string> named{""};
  for (const SectionDescription& section : sections) {
    for (const FieldDescription& field : section.fields) {
      if (field.format.type == ValueType::object || field.format.type == ValueType::list) {
        EXPECT_NE(find_section(sections, field.format.section), nullptr) << field.format.key;
        named.insert(std::string(field.format.section));
      }
    }
  }
  for (const SectionDescription& section : sections) {
    EXPECT_TRUE(named.count(std::string(section.name))) << section.name;
  }
  // The lists of the scene are what the studio's outliner shows.
  std::vector<std::string> lists;
  for (const FieldDescription& field : find_section(sections, "")->fields) {
    if (field.format.type == ValueType::list) lists.emplace_back(field.format.key);
  }
  EXPECT_EQ(lists, (std::vector<std::string>{"bodies", "obstacles", "force_fields", "springs",
                                             "liquids", "tracks", "constraints", "figures"}));
}

TEST(SceneFormat, NewItemsAreValid) {
  const std::vector<SectionDescription> sections = describe_scene_format();
  for (const FieldDescription& field : find_section(sections, "")->fields) {
    const SectionDescription* section = find_section(sections, field.format.section);
    if (!section || section->new_item.is_null()) continue;
    json j = json::parse(R"({"bodies": [{"material": {"mass": 1}}]})");
    if (field.format.type == ValueType::list) {
      j[std::string(field.format.key)].push_back(section->new_item);
    } else {
      j[std::string(field.format.key)] = section->new_item;
    }
    EXPECT_NO_THROW(parse_scene(j.dump(), kFile)) << field.format.key;
  }
}

// The tables' defaults are what the parser gives a key left out.
TEST(SceneFormat, DefaultsAreWhatTheParserGives) {
  const json given = json::parse(
      R"({"camera": {}, "bodies": [{"material": {"mass": 1}}], "force_fields": [{}],
          "springs": [{"node": 0}], "tracks": [{"target": "gravity[0]", "keys": [[0, 0]]}],
          "obstacles": [{}, {"kind": "box"}, {"kind": "mesh", "file": "a.obj"}],
          "constraints": [{"kind": "hinge", "a": {"body": 0, "point": [0, 0, 0]},
                           "b": {"world": [0, 0, 0]}}],
          "figures": [{"segments": [{"sites": [{}]}]}],
          "liquids": [{"fluid": [{"box": {"min": [0, 0, 0], "max": [1, 1, 0.5]}}],
                       "inflows": [{"box": {"min": [0, 0, 0.5], "max": [0.2, 1, 0.7]}}],
                       "surface_waves": [{}]}]})");
  const json written = json::parse(scene_to_json(parse_scene(given.dump(), kFile)));
  const std::vector<SectionDescription> sections = describe_scene_format();
  const std::vector<std::pair<std::string, json::json_pointer>> items = {
      {"", json::json_pointer("")},
      {"solver", json::json_pointer("/solver")},
      {"camera", json::json_pointer("/camera")},
      {"body", json::json_pointer("/bodies/0")},
      {"shape", json::json_pointer("/bodies/0/shape")},
      {"tessellation", json::json_pointer("/bodies/0/tessellation")},
      {"material", json::json_pointer("/bodies/0/material")},
      {"force_field", json::json_pointer("/force_fields/0")},
      {"spring", json::json_pointer("/springs/0")},
      {"track", json::json_pointer("/tracks/0")},
      {"obstacle", json::json_pointer("/obstacles/0")},
      {"obstacle", json::json_pointer("/obstacles/1")},
      {"obstacle", json::json_pointer("/obstacles/2")},
      {"constraint", json::json_pointer("/constraints/0")},
      {"figure", json::json_pointer("/figures/0")},
      {"segment", json::json_pointer("/figures/0/segments/0")},
      {"joint", json::json_pointer("/figures/0/segments/0/joint")},
      {"segment_shape", json::json_pointer("/figures/0/segments/0/shape")},
      {"site", json::json_pointer("/figures/0/segments/0/sites/0")},
      {"liquid", json::json_pointer("/liquids/0")},
      {"fluid_region", json::json_pointer("/liquids/0/fluid/0")},
      {"inflow", json::json_pointer("/liquids/0/inflows/0")},
      {"surface_wave", json::json_pointer("/liquids/0/surface_waves/0")}};
  for (const auto& [name, pointer] : items) {
    const json& object = written[pointer];
    const json& input = given.contains(pointer) ? given[pointer] : json::object();
    for (const FieldDescription& field : find_section(sections, name)->fields) {
      const std::string key(field.format.key);
      if (field.default_value.is_null() || input.contains(key) || !object.contains(key)) continue;
      EXPECT_EQ(object[key], field.default_value) << pointer << "/" << key;
    }
  }
}

TEST(SceneFormat, SchemaForbidsTheKeysOfOtherKinds) {
  const json schema = load_schema();
  const json written = json::parse(scene_to_json(parse_scene(full_scene().dump(), kFile)));
  const std::vector<SectionDescription> sections = describe_scene_format();
  // The full scene has an obstacle of each kind and both kinds of constraint: every item, given a
  // key of another kind (with the value another item has there), is refused.
  for (const auto& [list, name] :
       {std::pair{"obstacles", "obstacle"}, {"constraints", "constraint"}}) {
    const SectionDescription& section = *find_section(sections, name);
    for (std::size_t i = 0; i < written[list].size(); ++i) {
      const json& item = written[list][i];
      int kind = 0;
      while (section.kind_names[static_cast<std::size_t>(kind)] != item["kind"]) ++kind;
      for (const FieldDescription& field : section.fields) {
        const std::string key(field.format.key);
        if ((field.format.kinds >> kind) & 1u) continue;
        for (const json& other : written[list]) {
          if (!other.contains(key)) continue;
          json wrong = written;
          wrong[list][i][key] = other[key];
          EXPECT_NE(validate(schema, schema, wrong, ""), "") << item.dump() << " + " << key;
          break;
        }
      }
    }
  }
  // The full scene's figure has a joint of each kind: likewise for the joints' keys.
  const SectionDescription& joint = *find_section(sections, "joint");
  const json& segments = written["figures"][0]["segments"];
  int checked = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    int kind = 0;
    while (joint.kind_names[static_cast<std::size_t>(kind)] != segments[i]["joint"]["kind"]) ++kind;
    for (const FieldDescription& field : joint.fields) {
      const std::string key(field.format.key);
      if ((field.format.kinds >> kind) & 1u) continue;
      for (const json& other : segments) {
        if (!other["joint"].contains(key)) continue;
        json wrong = written;
        wrong["figures"][0]["segments"][i]["joint"][key] = other["joint"][key];
        EXPECT_NE(validate(schema, schema, wrong, ""), "") << segments[i].dump() << " + " << key;
        ++checked;
        break;
      }
    }
  }
  // axis and axis2 on spherical, fixed, free; axis2 on the two 1-DOF; stiffness and rest on fixed
  // and free; lower and upper on spherical, fixed, free; limit_restitution on fixed and free;
  // swing_limit and twist_limit on the five kinds but spherical.
  EXPECT_EQ(checked, 30);
}

TEST(SceneFormat, SchemaAcceptsWhatTheParserWritesAndRejectsWhatItRejects) {
  const json schema = load_schema();
  // Everything scene_to_json writes (every key of every section) must be in the schema.
  const json written = json::parse(scene_to_json(parse_scene(full_scene().dump(), kFile)));
  EXPECT_EQ(validate(schema, schema, written, ""), "");
  EXPECT_EQ(validate(schema, schema, full_scene(), ""), "");
  // The validator can fail: each of these is also rejected by parse_scene.
  json bad = written;
  bad["bodies"][0]["material"]["foo"] = 1;
  EXPECT_EQ(validate(schema, schema, bad, ""), "bodies[0].material.foo: forbidden");
  bad = written;
  bad["lights"] = json::object();
  EXPECT_EQ(validate(schema, schema, bad, ""), "lights: forbidden");
  bad = written;
  bad["obstacles"][0]["friction"] = 1.5;
  EXPECT_EQ(validate(schema, schema, bad, ""), "obstacles[0].friction: > max");
  bad = written;
  bad["bodies"][0]["material"]["mass"] = 1;  // both masses
  EXPECT_EQ(validate(schema, schema, bad, ""), "bodies[0].material: anyOf/oneOf not satisfied");
  bad = written;
  bad["constraints"][1]["b"]["body"] = 0;  // world and body together
  EXPECT_EQ(validate(schema, schema, bad, ""), "constraints[1].b: anyOf/oneOf not satisfied");
  bad = written;
  bad["tracks"][0]["target"] = "bodies[0].position[0]";
  EXPECT_EQ(validate(schema, schema, bad, ""), "tracks[0].target: does not match pattern");
}

TEST(SceneFormat, DescribesTheKeyAtAPointer) {
  const std::vector<SectionDescription> sections = describe_scene_format();
  const std::optional<FieldDescription> w1 = describe_scene_key(sections, "/bodies/0/material/w1");
  ASSERT_TRUE(w1.has_value());
  EXPECT_EQ(w1->format.key, "w1");
  EXPECT_EQ(range_text(w1->format.range), ">= 0");
  EXPECT_EQ(w1->default_value, 15);
  const std::optional<FieldDescription> g = describe_scene_key(sections, "/gravity/2");
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->format.unit, "m/s^2");
  EXPECT_EQ(describe_scene_key(sections, "/constraints/3/b/world")->format.key, "world");
  EXPECT_EQ(describe_scene_key(sections, "/tracks/0/keys/4/1")->format.key, "keys");
  EXPECT_EQ(range_text(describe_scene_key(sections, "/camera/fov")->format.range), "(0, 180)");
  EXPECT_FALSE(describe_scene_key(sections, "/bodies/0").has_value());
  EXPECT_FALSE(describe_scene_key(sections, "/bodies/0/shape/q_s/a1").has_value());
  EXPECT_FALSE(describe_scene_key(sections, "/bodies/x/name").has_value());
  EXPECT_FALSE(describe_scene_key(sections, "/lights").has_value());
}

TEST(SceneReadme, DocumentsEveryKeyTargetAndLimit) {
  const std::string readme = read_text(std::string(PBM_SOURCE_DIR) + "/scenes/README.md");
  for (const SectionDescription& section : describe_scene_format()) {
    for (const FieldDescription& field : section.fields) {
      EXPECT_NE(readme.find("| `" + std::string(field.format.key) + "` |"), std::string::npos)
          << section.name << "." << field.format.key;
    }
  }
  for (const TrackTargetFormat& target : kTrackTargets) {
    std::string shown;
    for (const char c : target.text) {
      if (c != '{' && c != '}') shown += c;
    }
    EXPECT_NE(readme.find("`" + shown + "`"), std::string::npos) << shown;
  }
  for (const std::string limit : {"32 MiB", "32 levels", "1,000,000 JSON values", "4096 bytes",
                                  "100,000 nodes", "4096 rings"}) {
    EXPECT_NE(readme.find(limit), std::string::npos) << limit;
  }
}

TEST(SceneReadme, FullExampleLoadsAndConformsToTheSchema) {
  const std::string readme = read_text(std::string(PBM_SOURCE_DIR) + "/scenes/README.md");
  const std::string open = "```json\n";
  const std::size_t begin = readme.find(open);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = readme.find("```", begin + open.size());
  ASSERT_NE(end, std::string::npos);
  const std::string example = readme.substr(begin + open.size(), end - begin - open.size());
  Scene s;
  ASSERT_NO_THROW(s = parse_scene(example, "README.md"));
  EXPECT_EQ(s.bodies.at(0).name, "jello");
  EXPECT_EQ(s.tracks.at(0).target, "bodies[0].q_s0[6]");
  const json schema = load_schema();
  EXPECT_EQ(validate(schema, schema, json::parse(example), ""), "");
}

}  // namespace
}  // namespace pbm::scene_test
