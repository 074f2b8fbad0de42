// The scene format described once: every section of a scene file (the scene itself, its solver,
// camera, bodies and their shape, tessellation and material, obstacles, force fields, springs,
// constraints and their ends, tracks) is a table of its keys, each with its type, unit, range,
// default and meaning. The tables live beside the code that reads and writes each section
// (scene_*_json.cpp), so the parser's allowed keys, the writer, the studio's outliner and
// inspector, and the test that holds scenes/scene.schema.json to them all read the same rows.
// This header is the tables' vocabulary and their read-only view for everyone outside the reader.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/types.h"

namespace pbm {

// What a key's value is in the file.
enum class ValueType {
  number,           // a JSON number, finite
  integer,          // a number with an integral value (16 or 16.0)
  boolean,          // true or false
  string,           // text
  choice,           // one of a closed set of names (FieldFormat::choices)
  vector,           // exactly FieldFormat::size numbers; FieldFormat::range holds for each
  quaternion,       // 4 numbers (w, x, y, z), nonzero, normalized on load
  direction,        // 3 numbers, nonzero, normalized on load
  object,           // an object described by the section FieldFormat::section
  list,             // an array of objects, each described by FieldFormat::section
  shape_vector,     // one number per shape parameter: an array of n_s or an object by name
  body_reference,   // a body by index or by name
  body_references,  // an array of body references
  node_index,       // a node of the body the item refers to: [0, 2 + rings * segments)
  material_point,   // (u, v) [rad], u in [-pi/2, pi/2], v in [-pi, pi]
  track_target,     // the scene value a track drives (scene/track_targets.h)
  keys,             // [time, value] pairs, strictly increasing in time
  numbers,          // an array of at most FieldFormat::limit numbers, its length free (a q0)
  counts,           // exactly FieldFormat::size integers, each in FieldFormat::range, <= limit
};

inline constexpr Real kUnbounded = std::numeric_limits<Real>::infinity();

// The valid values of a number (of each entry of a vector): lo < x or lo <= x, x < hi or x <= hi.
struct Range {
  Real lo = -kUnbounded;
  Real hi = kUnbounded;
  bool lo_open = false;
  bool hi_open = false;
};
inline constexpr Range kAny{};
inline constexpr Range kPositive{.lo = 0, .lo_open = true};
inline constexpr Range kNonNegative{.lo = 0};
inline constexpr Range kUnitInterval{.lo = 0, .hi = 1};

// Every kind of a section that has kinds (FieldFormat::kinds).
inline constexpr std::uint32_t kAllKinds = ~std::uint32_t{0};

// One key of a section: what the file may say there. Only words and numbers: how it is read and
// written sits beside it in the section's table (scene/scene_fields.h).
struct FieldFormat {
  std::string_view key{};
  ValueType type = ValueType::number;
  std::string_view unit{};  // SI unit of the value ("m", "1/s", "N m/rad"), "" when it has none
  Range range{};            // valid values (a vector's entries; a list's number of items)
  // What reading may cost: integers and list lengths above it are refused ("must be <= 4096").
  // A limit of the format, not of the model: scenes/README.md, "Limits".
  Real limit = kUnbounded;
  int size = 0;            // vector: number of entries
  bool required = false;   // (for the kinds it belongs to)
  bool non_empty = false;  // string: must not be ""
  // Keys sharing a nonzero group: exactly one of them must be given ("mass" or "nodal_mass").
  int one_of = 0;
  std::uint32_t kinds = kAllKinds;  // sections with kinds: bit k set when kind k has this key
  std::string_view section{};       // object, list: the name of the section describing the value
  std::span<const std::string_view> choices{};  // choice: the names, in the order of the enum
  // The default in words when it is not a fixed value ("body<i>", "the kind's defaults",
  // "forever"); "" when the default is what a default-constructed definition writes, or when the
  // key is required.
  std::string_view default_note{};
  std::string_view description{};
};

// A key of a section with its default as the writer writes it for a default-constructed
// definition (null when required, when the default is a note, and for objects and lists).
struct FieldDescription {
  FieldFormat format{};
  nlohmann::json default_value{};
};

// One section of the format: an object of the file and the keys it may hold.
struct SectionDescription {
  std::string_view name{};  // as in scenes/scene.schema.json's $defs ("" for the scene itself)
  std::string_view noun{};  // one item, for messages and the studio ("body", "obstacle")
  std::vector<FieldDescription> fields{};
  std::span<const std::string_view> kind_names{};  // sections with kinds, else empty
  // A valid new item of a list section for the studio's "add" (null when an item needs choices
  // only the user can make, such as which body a spring pulls).
  nlohmann::json new_item{};
};

// Every section, the scene itself first. Built from the tables on each call (no static state).
std::vector<SectionDescription> describe_scene_format();

// The section called `name` in `sections` (describe_scene_format()), or nullptr.
const SectionDescription* find_section(const std::vector<SectionDescription>& sections,
                                       std::string_view name);

// The key of the scene file at `json_pointer` (RFC 6901 into scene_to_json's output, e.g.
// "/bodies/0/material/w1", "/gravity/2" for an entry of a vector) among `sections`
// (describe_scene_format()), or nullopt when the pointer names no key of the format (shape
// parameters by name are described by deform/shape_parameters.h).
std::optional<FieldDescription> describe_scene_key(const std::vector<SectionDescription>& sections,
                                                   std::string_view json_pointer);

// "must be > 0", "must be in [0, 1]": what reading says of a value outside `range`.
std::string range_requirement(const Range& range);
// "> 0", "[0, 1]", "" for kAny: the range as the studio shows it.
std::string range_text(const Range& range);

// ---- limits: what a file can cost the reader (scenes/README.md, "Limits") ---------------------
// Each is far above what a real scene needs, and low enough that a hostile file of a few KB is
// refused before it costs seconds or gigabytes.

// Bytes of a scene file: parsing runs at about 100 MB/s, so this is a fraction of a second.
inline constexpr std::size_t kMaxSceneFileBytes = std::size_t{32} << 20;
// Objects and arrays inside each other; a scene nests 5 deep.
inline constexpr int kMaxNestingDepth = 32;
// JSON values in the file (each one costs the parsed document 16 to 100 bytes).
inline constexpr std::size_t kMaxJsonValues = 1'000'000;
// Bytes of one string or key (a name, a mesh file's path).
inline constexpr std::size_t kMaxStringBytes = 4096;

}  // namespace pbm
