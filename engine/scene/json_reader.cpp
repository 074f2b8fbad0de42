#include "scene/json_reader.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace pbm {

namespace {

// nlohmann prefixes what() with "[json.exception.parse_error.101] "; the file name and position
// already say where, so keep only the human part.
std::string strip_exception_id(const std::string& what) {
  if (!what.empty() && what.front() == '[') {
    const std::size_t close = what.find("] ");
    if (close != std::string::npos) return what.substr(close + 2);
  }
  return what;
}

// Builds the document from nlohmann's SAX events, checking the limits and repeated keys at each
// event, before the document keeps the value. (nlohmann's parser with a callback searches the
// parent for discarded values at the end of every object or array, which is quadratic in an
// array of objects; its parser itself is iterative, so nesting cannot overflow the stack.)
class DocumentBuilder {
 public:
  DocumentBuilder(const std::string& file, const JsonLimits& limits)
      : file_(file), limits_(limits) {}

  nlohmann::json take() { return std::move(root_); }

  bool null() { return add(nullptr); }
  bool boolean(bool value) { return add(value); }
  bool number_integer(std::int64_t value) { return add(value); }
  bool number_unsigned(std::uint64_t value) { return add(value); }
  bool number_float(double value, const std::string&) { return add(value); }
  bool string(std::string& value) {
    if (value.size() > limits_.max_string_bytes) {
      throw Error(file_, next_path(),
                  "is a string of " + std::to_string(value.size()) + " bytes; at most " +
                      std::to_string(limits_.max_string_bytes) + " are allowed");
    }
    return add(std::move(value));
  }
  bool binary(nlohmann::json::binary_t&) { return add(nullptr); }  // not produced by JSON text

  bool start_object(std::size_t) { return open(nlohmann::json::object()); }
  bool start_array(std::size_t) { return open(nlohmann::json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& key) {
    Open& object = open_.back();
    if (key.size() > limits_.max_string_bytes) {
      throw Error(file_, object.path,
                  "has a key of " + std::to_string(key.size()) + " bytes; at most " +
                      std::to_string(limits_.max_string_bytes) + " are allowed");
    }
    // nlohmann would keep only the last value of a repeated key.
    if (object.value->contains(key)) {
      throw Error(file_, child_path(object.path, key), "duplicate key '" + key + "'");
    }
    object.key = key;
    return true;
  }

  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception& e) {
    if (const auto* error = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
      throw Error(file_, "",
                  "invalid JSON: " + strip_exception_id(error->what()) + " (byte " +
                      std::to_string(error->byte) + ")");
    }
    // e.g. out_of_range 406: a number literal too large for a double.
    throw Error(file_, "", "invalid JSON: " + strip_exception_id(e.what()));
  }

 private:
  // An object or array being filled; its address is stable while it is open, because its
  // parent gets no other member meanwhile.
  struct Open {
    nlohmann::json* value = nullptr;
    std::string path;
    std::size_t next_index = 0;  // arrays: index of the next element
    std::string key;             // objects: the key whose value comes next
  };

  // The path of the value about to be added (built only for containers and messages: most
  // values are numbers in arrays).
  std::string next_path() const {
    if (open_.empty()) return "";
    const Open& parent = open_.back();
    return parent.value->is_array() ? element_path(parent.path, parent.next_index)
                                    : child_path(parent.path, parent.key);
  }

  void count_value() {
    if (++values_ > limits_.max_values) {
      throw Error(file_, next_path(),
                  "the file has more than " + std::to_string(limits_.max_values) +
                      " JSON values; a scene file may have at most that many");
    }
  }

  // Stores `value` where the next value goes; returns where it went.
  nlohmann::json* place(nlohmann::json value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Open& parent = open_.back();
    if (parent.value->is_array()) {
      ++parent.next_index;
      parent.value->push_back(std::move(value));
      return &parent.value->back();
    }
    nlohmann::json& member = (*parent.value)[parent.key];
    member = std::move(value);
    return &member;
  }

  bool add(nlohmann::json value) {
    count_value();
    place(std::move(value));
    return true;
  }

  bool open(nlohmann::json container) {
    std::string path = next_path();
    if (static_cast<int>(open_.size()) >= limits_.max_depth) {
      throw Error(file_, path,
                  "nested deeper than " + std::to_string(limits_.max_depth) +
                      " objects and arrays; a scene file nests at most that deep");
    }
    count_value();
    nlohmann::json* placed = place(std::move(container));
    open_.push_back(Open{.value = placed, .path = std::move(path), .next_index = 0, .key = {}});
    return true;
  }

  bool close() {
    open_.pop_back();
    return true;
  }

  const std::string& file_;
  const JsonLimits& limits_;
  nlohmann::json root_;
  std::vector<Open> open_;
  std::size_t values_ = 0;
};

}  // namespace

std::string too_large_message(std::uintmax_t bytes, std::size_t max_bytes) {
  return "is " + std::to_string(bytes) + " bytes; a scene file may have at most " +
         std::to_string(max_bytes) + " bytes (" + std::to_string(max_bytes >> 20) + " MiB)";
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file,
                               const JsonLimits& limits) {
  if (text.size() > limits.max_bytes) {
    throw Error(file, "", too_large_message(text.size(), limits.max_bytes));
  }
  DocumentBuilder builder(file, limits);
  nlohmann::json::sax_parse(text, &builder);
  return builder.take();
}

JsonNode root_node(const nlohmann::json& document, const std::string& file) {
  return JsonNode{&document, std::string(), &file};
}

void fail(const JsonNode& node, const std::string& message) {
  throw Error(node.file ? *node.file : std::string(), node.path, message);
}

std::string child_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::size_t require_array(const JsonNode& node) {
  if (!node.value->is_array()) fail(node, "must be an array");
  return node.value->size();
}

std::optional<JsonNode> find_child(const JsonNode& object, std::string_view key) {
  const auto it = object.value->find(key);
  if (it == object.value->end()) return std::nullopt;
  return JsonNode{&*it, child_path(object.path, key), object.file};
}

JsonNode require_child(const JsonNode& object, std::string_view key) {
  std::optional<JsonNode> child = find_child(object, key);
  if (!child)
    fail(JsonNode{object.value, child_path(object.path, key), object.file}, "is required");
  return *child;
}

JsonNode element(const JsonNode& array, std::size_t index) {
  return JsonNode{&(*array.value)[index], element_path(array.path, index), array.file};
}

Real read_real(const JsonNode& node) {
  if (!node.value->is_number()) fail(node, "must be a number");
  const Real value = node.value->get<Real>();
  if (!std::isfinite(value)) fail(node, "must be finite");
  return value;
}

int read_int(const JsonNode& node) {
  const nlohmann::json& v = *node.value;
  if (v.is_number_integer()) {
    // Covers both signed and unsigned storage; compare in the widest type before narrowing.
    if (v.is_number_unsigned()) {
      const auto u = v.get<std::uint64_t>();
      if (u <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
        return static_cast<int>(u);
      }
    } else {
      const auto s = v.get<std::int64_t>();
      if (s >= std::numeric_limits<int>::min() && s <= std::numeric_limits<int>::max()) {
        return static_cast<int>(s);
      }
    }
    fail(node, "is out of range for an integer");
  }
  // 16.0 is an integer written with a decimal point; 16.5 is not.
  if (v.is_number_float()) {
    const Real r = v.get<Real>();
    if (std::isfinite(r) && r == std::floor(r) && r >= std::numeric_limits<int>::min() &&
        r <= std::numeric_limits<int>::max()) {
      return static_cast<int>(r);
    }
  }
  fail(node, "must be an integer");
}

bool read_bool(const JsonNode& node) {
  if (!node.value->is_boolean()) fail(node, "must be true or false");
  return node.value->get<bool>();
}

std::string read_string(const JsonNode& node) {
  if (!node.value->is_string()) fail(node, "must be a string");
  return node.value->get<std::string>();
}

VecX read_reals(const JsonNode& node, int n) {
  const std::string expected = "must be an array of " + std::to_string(n) + " numbers";
  if (!node.value->is_array()) fail(node, expected);
  if (node.value->size() != static_cast<std::size_t>(n)) {
    fail(node, expected + " (got " + std::to_string(node.value->size()) + ")");
  }
  VecX values(n);
  for (int i = 0; i < n; ++i) values[i] = read_real(element(node, static_cast<std::size_t>(i)));
  return values;
}

Vec2 read_vec2(const JsonNode& node) {
  return read_reals(node, 2);
}
Vec3 read_vec3(const JsonNode& node) {
  return read_reals(node, 3);
}

Real require_non_negative(const JsonNode& node, Real value) {
  if (!(value >= 0)) fail(node, "must be >= 0");
  return value;
}

Real require_in_range(const JsonNode& node, Real value, Real lo, Real hi) {
  if (!(value >= lo && value <= hi)) {
    fail(node, "must be in [" + format_real(lo) + ", " + format_real(hi) + "]");
  }
  return value;
}

std::string format_real(Real value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace pbm
