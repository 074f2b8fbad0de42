// The rows of the format's tables (scene/scene_format.h) with how each is read and written, and
// the generic reader and writer of a section that walk them. Only the scene reader's files
// (scene_*_json.cpp) include this.
//
// A section's table is a constexpr array of Field<Def>, one row per key in the order the writer
// writes them. Most rows are made by a factory from a member pointer, so the member, its key and
// its range are named once:
//     value<&SolverDef::dt>({.key = "dt", .unit = "s", .range = kPositive, .description = ...})
// and reading checks the type and range the row states, with the messages of scene/json_reader.h.
// Keys whose reading depends on other keys or on the rest of the scene (a node of the body a
// spring pulls, shape vectors by the body's shape kind) are rows with their own read and write.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/json_reader.h"
#include "scene/scene.h"
#include "scene/scene_format.h"

namespace pbm {

using OrderedJson = nlohmann::ordered_json;  // keeps keys in the order of the tables

// What a row may look at besides its own value.
struct ReadContext {
  const Scene& scene;     // what is read so far: the bodies before every list that refers to them
  std::size_t index = 0;  // of the item in its list (default names such as "body<i>")
};

template <typename Def>
struct Field {
  FieldFormat format{};
  // Reads the value at `node` (present) into `def`, or throws pbm::Error naming node.path.
  void (*read)(const FieldFormat&, const JsonNode& node, Def& def, const ReadContext&) = nullptr;
  // Writes the value into `object` under format.key, or nothing when the definition leaves it
  // out (an absent optional value, the mass that was not given).
  void (*write)(const FieldFormat&, const Def& def, OrderedJson& object) = nullptr;
};

template <typename Def>
struct Section {
  std::string_view name{};  // as in scene.schema.json's $defs
  std::string_view noun{};  // one item ("body"), for messages
  std::span<const Field<Def>> fields{};
  // Sections with kinds: the index of the item's kind in kind_names. The keys of other kinds are
  // refused as soon as the "kind" row is read, and not written.
  int (*kind_of)(const Def&) = nullptr;
  std::span<const std::string_view> kind_names{};
  // Defaults that depend on the item's index in its list (names such as "body<i>").
  void (*init)(Def& def, const ReadContext&) = nullptr;
  // Relations between keys, once every key is read (t_end >= t_begin, unique names).
  void (*check)(const JsonNode& node, Def& def, const ReadContext&) = nullptr;
  std::string_view new_item{};  // JSON text of a valid new item for the studio, "" for none
};

// ---- member pointers -------------------------------------------------------------------------

template <typename Pointer>
struct MemberTraits;
template <typename Class, typename Member>
struct MemberTraits<Member Class::*> {
  using ClassType = Class;
  using Type = Member;
};
template <auto Member>
using ClassOf = typename MemberTraits<decltype(Member)>::ClassType;
template <auto Member>
using TypeOf = typename MemberTraits<decltype(Member)>::Type;

template <typename T>
inline constexpr bool kIsOptional = false;
template <typename T>
inline constexpr bool kIsOptional<std::optional<T>> = true;

// The names of a NameTable (scene/scene_enum_names.h), for FieldFormat::choices.
template <const auto& Names>
inline constexpr auto kNameList = [] {
  std::array<std::string_view, std::tuple_size_v<std::remove_cvref_t<decltype(Names)>>> names{};
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = Names[i].first;
  return names;
}();

template <typename Enum>
constexpr std::uint32_t kind_bit(Enum kind) {
  return std::uint32_t{1} << static_cast<int>(kind);
}

// ---- values --------------------------------------------------------------------------------

// "100000" rather than format_real's shortest "1e+05": bounds and limits read as counts.
std::string bound_text(Real bound);
// `value` if it lies in format.range and below format.limit, else fail at `node`.
Real check_range(const FieldFormat& format, const JsonNode& node, Real value);
// A string; format.non_empty refuses "".
std::string read_text(const FieldFormat& format, const JsonNode& node);
// A body given by index (0) or by name ("jello").
int read_body_reference(const JsonNode& node, const std::vector<BodyDef>& bodies);
// A node of `body` (springs, constraint ends).
int read_node_index(const JsonNode& node, const BodyDef& body);
// Material coordinates (u, v) within the ranges of (2.7): -pi/2 <= u <= pi/2, -pi <= v <= pi.
Vec2 read_material_point(const JsonNode& node);
// Keyframes: [time, value] pairs, at least one and at most format.limit, strictly increasing in
// time (tracks, joint trajectories); and their JSON.
std::vector<Keyframe> read_keyframes(const FieldFormat& format, const JsonNode& node);
OrderedJson keyframes_json(const std::vector<Keyframe>& keys);

// A row of keyframes (std::vector<Keyframe>).
template <auto Member>
constexpr Field<ClassOf<Member>> keyframes(FieldFormat format) {
  format.type = ValueType::keys;
  return {format,
          [](const FieldFormat& f, const JsonNode& node, ClassOf<Member>& def, const ReadContext&) {
            def.*Member = read_keyframes(f, node);
          },
          [](const FieldFormat& f, const ClassOf<Member>& def, OrderedJson& object) {
            object[f.key] = keyframes_json(def.*Member);
          }};
}

// Below this length a quaternion or normal carries no direction.
inline constexpr Real kMinimumDirectionLength = 1e-12;
// Quaternions and normals are rescaled only when visibly off unit length, so that a vector
// written by scene_to_json (already unit to within rounding) reads back bit-identical.
inline constexpr Real kUnitLengthSlack = 1e-14;

// A unit vector from `value` read at `node`; zero length is an error.
template <typename Vector>
Vector normalized_direction(const JsonNode& node, const Vector& value, const std::string& what) {
  const Real length = value.norm();
  if (!(length > kMinimumDirectionLength)) fail(node, "must be a nonzero " + what);
  if (std::abs(length - 1) <= kUnitLengthSlack) return value;
  return value / length;
}

template <typename Vector>
OrderedJson to_array(const Vector& v) {
  OrderedJson array = OrderedJson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) array.push_back(v[i]);
  return array;
}

template <auto Member>
void read_value(const FieldFormat& format, const JsonNode& node, ClassOf<Member>& def,
                const ReadContext&) {
  using T = TypeOf<Member>;
  if constexpr (std::is_same_v<T, Real> || std::is_same_v<T, std::optional<Real>>) {
    def.*Member = check_range(format, node, read_real(node));
  } else if constexpr (std::is_same_v<T, int>) {
    def.*Member = static_cast<int>(check_range(format, node, read_int(node)));
  } else if constexpr (std::is_same_v<T, bool>) {
    def.*Member = read_bool(node);
  } else if constexpr (std::is_same_v<T, std::string>) {
    def.*Member = read_text(format, node);
  } else {
    const T value = read_reals(node, T::RowsAtCompileTime);
    if (format.type == ValueType::quaternion) {
      def.*Member = normalized_direction(node, value, "quaternion");
    } else if (format.type == ValueType::direction) {
      def.*Member = normalized_direction(node, value, "vector");
    } else {
      for (int k = 0; k < value.size(); ++k) check_range(format, element(node, k), value[k]);
      def.*Member = value;
    }
  }
}

template <auto Member>
void write_value(const FieldFormat& format, const ClassOf<Member>& def, OrderedJson& object) {
  using T = TypeOf<Member>;
  const T& value = def.*Member;
  if constexpr (kIsOptional<T>) {
    if (value) object[format.key] = *value;
  } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
    object[format.key] = value;
  } else {
    object[format.key] = to_array(value);
  }
}

template <typename T>
constexpr ValueType value_type_of() {
  if constexpr (std::is_same_v<T, Real> || std::is_same_v<T, std::optional<Real>>) {
    return ValueType::number;
  } else if constexpr (std::is_same_v<T, int>) {
    return ValueType::integer;
  } else if constexpr (std::is_same_v<T, bool>) {
    return ValueType::boolean;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return ValueType::string;
  } else {
    return ValueType::vector;
  }
}

// A number, integer, boolean, string or vector member: its type and size come from the member.
template <auto Member>
constexpr Field<ClassOf<Member>> value(FieldFormat format) {
  using T = TypeOf<Member>;
  format.type = value_type_of<T>();
  if constexpr (value_type_of<T>() == ValueType::vector) format.size = T::RowsAtCompileTime;
  return {format, &read_value<Member>, &write_value<Member>};
}

// A quaternion (Vec4) or a direction (Vec3), normalized on load.
template <auto Member>
constexpr Field<ClassOf<Member>> unit_vector(FieldFormat format) {
  using T = TypeOf<Member>;
  format.size = T::RowsAtCompileTime;
  format.type = format.size == 4 ? ValueType::quaternion : ValueType::direction;
  return {format, &read_value<Member>, &write_value<Member>};
}

// One of a closed set of names (scene/scene_enum_names.h).
template <auto Member, const auto& Names>
constexpr Field<ClassOf<Member>> choice(FieldFormat format) {
  format.type = ValueType::choice;
  format.choices = kNameList<Names>;
  return {format,
          [](const FieldFormat&, const JsonNode& node, ClassOf<Member>& def, const ReadContext&) {
            def.*Member = read_enum(node, Names);
          },
          [](const FieldFormat& f, const ClassOf<Member>& def, OrderedJson& object) {
            object[f.key] = enum_name(def.*Member, Names);
          }};
}

// ---- sections ----------------------------------------------------------------------------------

template <typename Def>
bool has_kind(const Section<Def>& section, const Def& def, const FieldFormat& format) {
  return !section.kind_of || (format.kinds >> section.kind_of(def)) & 1u;
}

// Fails at the first key of `node` that is not a row of `section` ("unknown key").
template <typename Def>
void require_section_keys(const Section<Def>& section, const JsonNode& node) {
  if (!node.value->is_object()) fail(node, "must be an object");
  for (const auto& [key, value] : node.value->items()) {
    bool known = false;
    for (const Field<Def>& field : section.fields) known = known || field.format.key == key;
    if (!known) {
      fail(JsonNode{&value, child_path(node.path, key), node.file}, "unknown key '" + key + "'");
    }
  }
}

// Keys of another kind would be silently ignored, which hides typos like a plane's "center".
template <typename Def>
void refuse_keys_of_other_kinds(const Section<Def>& section, const JsonNode& node, const Def& def) {
  for (const Field<Def>& field : section.fields) {
    if (has_kind(section, def, field.format)) continue;
    if (auto misplaced = find_child(node, field.format.key)) {
      fail(*misplaced, "key '" + std::string(field.format.key) + "' is not valid for a " +
                           std::string(section.kind_names[section.kind_of(def)]) + " " +
                           std::string(section.noun));
    }
  }
}

// The row called `key` of `section`, read into `def` if `node` has it; whether it had it.
template <typename Def>
bool read_key(const Section<Def>& section, std::string_view key, const JsonNode& node, Def& def,
              const ReadContext& context) {
  for (const Field<Def>& field : section.fields) {
    if (field.format.key != key) continue;
    const std::optional<JsonNode> child = find_child(node, key);
    if (child) field.read(field.format, *child, def, context);
    return child.has_value();
  }
  return false;
}

// Fails at `node` unless exactly one key of `group` is in it ("give exactly one of 'node' and
// 'material_point'").
template <typename Def>
void require_one_of(const Section<Def>& section, const JsonNode& node, int group) {
  std::vector<std::string_view> keys;
  int given = 0;
  for (const Field<Def>& field : section.fields) {
    if (field.format.one_of != group) continue;
    keys.push_back(field.format.key);
    given += find_child(node, field.format.key).has_value() ? 1 : 0;
  }
  if (given == 1) return;
  std::string list;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    list += std::string(k == 0                 ? ""
                        : k + 1 == keys.size() ? " and "
                                               : ", ") +
            "'" + std::string(keys[k]) + "'";
  }
  fail(node, "give exactly one of " + list);
}

// Reads every row of `section` present in `node` into `def`, in the table's order; a required
// row that is absent fails at its path with "is required", and a group of which exactly one key
// must be given is checked where its first row is.
template <typename Def>
void read_section(const Section<Def>& section, const JsonNode& node, Def& def,
                  const ReadContext& context) {
  require_section_keys(section, node);
  int groups_checked = 0;
  for (const Field<Def>& field : section.fields) {
    if (!has_kind(section, def, field.format)) continue;
    if (field.format.one_of > groups_checked) {
      require_one_of(section, node, field.format.one_of);
      groups_checked = field.format.one_of;
    }
    if (const std::optional<JsonNode> child = find_child(node, field.format.key)) {
      field.read(field.format, *child, def, context);
    } else if (field.format.required) {
      require_child(node, field.format.key);
    }
    if (section.kind_of && field.format.key == "kind") {
      refuse_keys_of_other_kinds(section, node, def);
    }
  }
  if (section.check) section.check(node, def, context);
}

template <typename Def>
OrderedJson write_section(const Section<Def>& section, const Def& def) {
  OrderedJson object = OrderedJson::object();
  for (const Field<Def>& field : section.fields) {
    if (has_kind(section, def, field.format)) field.write(field.format, def, object);
  }
  return object;
}

// The words of `section`, with each key's default as written for a default-constructed Def.
template <typename Def>
SectionDescription describe_section(const Section<Def>& section) {
  SectionDescription description{.name = section.name,
                                 .noun = section.noun,
                                 .fields = {},
                                 .kind_names = section.kind_names,
                                 .new_item = nullptr};
  if (!section.new_item.empty()) description.new_item = nlohmann::json::parse(section.new_item);
  const Def defaults{};
  for (const Field<Def>& field : section.fields) {
    const FieldFormat& format = field.format;
    nlohmann::json default_value;
    const bool has_fixed_default = !format.required && format.default_note.empty() &&
                                   format.type != ValueType::object &&
                                   format.type != ValueType::list;
    if (has_fixed_default) {
      OrderedJson written = OrderedJson::object();
      field.write(format, defaults, written);
      if (written.contains(format.key)) {
        default_value = nlohmann::json::parse(written[format.key].dump());
      }
    }
    description.fields.push_back({format, std::move(default_value)});
  }
  return description;
}

// A new item of `section` read from `node`: its index-dependent defaults, then its keys.
template <typename Def>
Def read_item(const Section<Def>& section, const JsonNode& node, const ReadContext& context) {
  Def def{};
  if (section.init) section.init(def, context);
  read_section(section, node, def, context);
  return def;
}

// A member holding an object of the file described by `Sub` (a CameraDef, an optional one).
// format.section is Sub's name; a row of another file than Sub's gives it (Sub's name is not a
// constant there).
template <auto Member, const auto& Sub>
constexpr Field<ClassOf<Member>> object(FieldFormat format) {
  format.type = ValueType::object;
  if (format.section.empty()) format.section = Sub.name;
  return {format,
          [](const FieldFormat&, const JsonNode& node, ClassOf<Member>& def,
             const ReadContext& context) { def.*Member = read_item(Sub, node, context); },
          [](const FieldFormat& f, const ClassOf<Member>& def, OrderedJson& out) {
            if constexpr (kIsOptional<TypeOf<Member>>) {
              if (def.*Member) out[f.key] = write_section(Sub, *(def.*Member));
            } else {
              out[f.key] = write_section(Sub, def.*Member);
            }
          }};
}

// An object of the file whose keys are members of the same definition (a body's "shape").
template <const auto& Sub, typename Def>
constexpr Field<Def> inline_object(FieldFormat format) {
  format.type = ValueType::object;
  format.section = Sub.name;
  return {format,
          [](const FieldFormat&, const JsonNode& node, Def& def, const ReadContext& context) {
            read_section(Sub, node, def, context);
          },
          [](const FieldFormat& f, const Def& def, OrderedJson& out) {
            out[f.key] = write_section(Sub, def);
          }};
}

// Fails unless `node` is an array of at least format.range.lo and at most format.limit items;
// returns its length. The limit is checked before any item is read.
std::size_t require_list_length(const FieldFormat& format, const JsonNode& node);

// A vector member of items of the section `Sub` (format.section names it, as for object()).
// Items are appended one by one, so an item's reader sees the items before it in the scene.
template <auto Member, const auto& Sub>
constexpr Field<ClassOf<Member>> list(FieldFormat format) {
  format.type = ValueType::list;
  if (format.section.empty()) format.section = Sub.name;
  return {format,
          [](const FieldFormat& f, const JsonNode& node, ClassOf<Member>& def,
             const ReadContext& context) {
            const std::size_t n = require_list_length(f, node);
            auto& items = def.*Member;
            items.reserve(n);
            for (std::size_t i = 0; i < n; ++i) {
              items.push_back(read_item(Sub, element(node, i), ReadContext{context.scene, i}));
            }
          },
          [](const FieldFormat& f, const ClassOf<Member>& def, OrderedJson& out) {
            OrderedJson items = OrderedJson::array();
            for (const auto& item : def.*Member) items.push_back(write_section(Sub, item));
            out[f.key] = std::move(items);
          }};
}

// The first item of `items` before `index` whose `member` equals `value`, or -1: names and
// track targets that must be unique.
template <typename Def, typename Value>
int earlier_with(const std::vector<Def>& items, std::size_t index, Value Def::*member,
                 const Value& value) {
  for (std::size_t j = 0; j < index && j < items.size(); ++j) {
    if (items[j].*member == value) return static_cast<int>(j);
  }
  return -1;
}

}  // namespace pbm
