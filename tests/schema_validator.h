// The schema validator of the tests that hold scenes/scene.schema.json to the format's tables and
// to the parser (test_scene_format.cpp).
#pragma once

#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "scene_json_support.h"

namespace pbm::scene_test {

// A small validator for the subset of JSON Schema 2020-12 that scene.schema.json uses, enough to
// check that the schema accepts what the parser accepts and rejects unknown keys. Returns "" if
// `value` conforms, else the first problem with its path.
inline std::string validate(const json& schema, const json& root, const json& value,
                            const std::string& path) {
  if (schema.is_boolean()) return schema.get<bool>() ? "" : path + ": forbidden";
  if (schema.contains("$ref")) {
    const std::string ref = schema["$ref"];
    const std::string prefix = "#/$defs/";
    if (ref.rfind(prefix, 0) != 0) return path + ": unsupported $ref " + ref;
    const std::string problem =
        validate(root["$defs"][ref.substr(prefix.size())], root, value, path);
    if (!problem.empty()) return problem;
  }
  if (schema.contains("type")) {
    const std::string type = schema["type"];
    const bool ok =
        (type == "object" && value.is_object()) || (type == "array" && value.is_array()) ||
        (type == "string" && value.is_string()) || (type == "boolean" && value.is_boolean()) ||
        (type == "number" && value.is_number()) || (type == "integer" && value.is_number_integer());
    if (!ok) return path + ": not " + type;
  }
  if (schema.contains("enum")) {
    bool found = false;
    for (const json& option : schema["enum"]) found = found || option == value;
    if (!found) return path + ": not in enum";
  }
  if (schema.contains("const") && schema["const"] != value) return path + ": not const";
  if (value.is_number()) {
    const double x = value.get<double>();
    if (schema.contains("minimum") && x < schema["minimum"].get<double>()) return path + ": < min";
    if (schema.contains("maximum") && x > schema["maximum"].get<double>()) return path + ": > max";
    if (schema.contains("exclusiveMinimum") && x <= schema["exclusiveMinimum"].get<double>()) {
      return path + ": <= exclusive min";
    }
  }
  if (value.is_string()) {
    const std::string s = value;
    if (schema.contains("minLength") && s.size() < schema["minLength"].get<std::size_t>()) {
      return path + ": too short";
    }
    if (schema.contains("pattern") &&
        !std::regex_search(s, std::regex(schema["pattern"].get<std::string>()))) {
      return path + ": does not match pattern";
    }
  }
  if (value.is_array()) {
    if (schema.contains("minItems") && value.size() < schema["minItems"].get<std::size_t>()) {
      return path + ": too few items";
    }
    if (schema.contains("maxItems") && value.size() > schema["maxItems"].get<std::size_t>()) {
      return path + ": too many items";
    }
    if (schema.contains("items")) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        const std::string problem =
            validate(schema["items"], root, value[i], path + "[" + std::to_string(i) + "]");
        if (!problem.empty()) return problem;
      }
    }
  }
  if (value.is_object()) {
    if (schema.contains("required")) {
      for (const json& key : schema["required"]) {
        if (!value.contains(key.get<std::string>())) return path + ": missing " + key.dump();
      }
    }
    for (const auto& [key, member] : value.items()) {
      const std::string member_path = path.empty() ? key : path + "." + key;
      if (schema.contains("properties") && schema["properties"].contains(key)) {
        const std::string problem = validate(schema["properties"][key], root, member, member_path);
        if (!problem.empty()) return problem;
      } else if (schema.contains("additionalProperties")) {
        const std::string problem =
            validate(schema["additionalProperties"], root, member, member_path);
        if (!problem.empty()) return problem;
      }
    }
  }
  if (schema.contains("anyOf") || schema.contains("oneOf")) {
    const bool one = schema.contains("oneOf");
    int matches = 0;
    for (const json& option : schema[one ? "oneOf" : "anyOf"]) {
      matches += validate(option, root, value, path).empty() ? 1 : 0;
    }
    if (matches == 0 || (one && matches != 1)) return path + ": anyOf/oneOf not satisfied";
  }
  if (schema.contains("allOf")) {
    for (const json& part : schema["allOf"]) {
      const std::string problem = validate(part, root, value, path);
      if (!problem.empty()) return problem;
    }
  }
  if (schema.contains("not") && validate(schema["not"], root, value, path).empty()) {
    return path + ": matches 'not'";
  }
  if (schema.contains("if")) {
    const bool condition = validate(schema["if"], root, value, path).empty();
    const char* branch = condition ? "then" : "else";
    if (schema.contains(branch)) {
      const std::string problem = validate(schema[branch], root, value, path);
      if (!problem.empty()) return problem;
    }
  }
  return "";
}

inline json load_schema() {
  return json::parse(read_text(std::string(PBM_SOURCE_DIR) + "/scenes/scene.schema.json"));
}

}  // namespace pbm::scene_test
