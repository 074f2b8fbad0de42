// Reading a JSON document while keeping the path of every value, so that each bad-input error
// names the file and the field ("bodies[2].material.w1: must be >= 0"; docs/architecture.md,
// "Errors and exit codes").
//
// A JsonNode is a non-owning view: the parsed document and the file name must outlive it. Every
// read_* function either returns a value of the requested type or throws pbm::Error(file, path,
// message); none of them converts silently (a string is never read as a number, 16.5 is never
// read as an integer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/types.h"

namespace pbm {

struct JsonNode {
  const nlohmann::json* value = nullptr;
  std::string path;                   // "" for the document root, else e.g. "bodies[0].material"
  const std::string* file = nullptr;  // for messages
};

// What parsing a document may cost; a document beyond any of them is refused while parsing,
// naming the path where it went over, before it costs more time or memory.
struct JsonLimits {
  std::size_t max_bytes = 0;         // of the text
  int max_depth = 0;                 // objects and arrays inside each other
  std::size_t max_values = 0;        // every value, containers included
  std::size_t max_string_bytes = 0;  // of one string or key
};

// Parses `text` as strict JSON (no comments). Malformed text throws pbm::Error(file, "", ...)
// whose message holds the line, column and byte offset; a key repeated inside one object throws
// with the repeated key's path, because nlohmann would otherwise keep only the last value.
// Every value is counted, and its nesting, its strings' lengths checked, as it is parsed.
nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const JsonLimits& limits);

// "is 40000000 bytes; a scene file may have at most 33554432 bytes (32 MiB)".
std::string too_large_message(std::uintmax_t bytes, std::size_t max_bytes);

// The root node of a parsed document.
JsonNode root_node(const nlohmann::json& document, const std::string& file);

[[noreturn]] void fail(const JsonNode& node, const std::string& message);

// "a.b" from ("a", "b"), "b" from ("", "b"); "a[3]" from ("a", 3).
std::string child_path(const std::string& path, std::string_view key);
std::string element_path(const std::string& path, std::size_t index);

// Fails unless `node` is an array; returns its length.
std::size_t require_array(const JsonNode& node);

// The member `key` of an object node, or nullopt when absent.
std::optional<JsonNode> find_child(const JsonNode& object, std::string_view key);
// The member `key`; fails at "<path>.<key>" with "is required" when absent.
JsonNode require_child(const JsonNode& object, std::string_view key);
JsonNode element(const JsonNode& array, std::size_t index);

Real read_real(const JsonNode& node);  // "must be a number"; also rejects non-finite values
int read_int(const JsonNode& node);    // "must be an integer"
bool read_bool(const JsonNode& node);  // "must be true or false"
std::string read_string(const JsonNode& node);
// Exactly n numbers: "must be an array of n numbers".
VecX read_reals(const JsonNode& node, int n);
Vec2 read_vec2(const JsonNode& node);
Vec3 read_vec3(const JsonNode& node);

// Range checks on a value already read from `node`; the message names the bound.
Real require_non_negative(const JsonNode& node, Real value);                // "must be >= 0"
Real require_in_range(const JsonNode& node, Real value, Real lo, Real hi);  // "must be in [lo, hi]"

// Shortest decimal text that reads back as the same double ("0.25", "1e-06").
std::string format_real(Real value);

// A closed set of names for an enum is a constexpr array of (name, value) pairs, shared by the
// reader and the writer so that the two cannot disagree (scene/scene_enum_names.h).
template <typename Names>
using EnumOf = std::remove_cvref_t<decltype(std::declval<const Names&>()[0].second)>;

// "must be one of \"a\", \"b\"" unless the string is one of the names.
template <typename Names>
EnumOf<Names> read_enum(const JsonNode& node, const Names& names) {
  const std::string text = read_string(node);
  std::string choices;
  for (const auto& [name, value] : names) {
    if (name == text) return value;
    choices += (choices.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  }
  fail(node, "must be one of " + choices + " (got \"" + text + "\")");
}

template <typename Names>
std::string enum_name(EnumOf<Names> value, const Names& names) {
  for (const auto& [name, candidate] : names) {
    if (candidate == value) return std::string(name);
  }
  return {};
}

}  // namespace pbm
