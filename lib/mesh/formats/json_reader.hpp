#pragma once
/// \file json_reader.hpp
/// A small JSON reader (RFC 8259) for the glTF codec (internal). Debian's Boost 1.74 has no
/// Boost.JSON, and Boost.PropertyTree's JSON parser recurses on the nesting of the text; this one
/// keeps an explicit stack and stores the values in one flat array (children by index), so neither
/// parsing nor destroying a document recurses, however deep the file nests.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace sculpt::mesh::detail {

enum class JsonKind { Null, Bool, Number, String, Array, Object };

/// One value of a JsonDocument. Arrays and objects list their children by index into the
/// document; an object's keys are parallel to its children.
struct JsonValue {
  JsonKind kind = JsonKind::Null;
  bool boolean = false;
  double number = 0;
  std::string text;                   ///< a string's value (UTF-8)
  std::vector<std::size_t> children;  ///< array elements or object members, in file order
  std::vector<std::string> keys;      ///< object member names, parallel to children
};

/// A parsed JSON text: values in one array, the root first.
class JsonDocument {
 public:
  /// Parses `text` (one JSON value with optional surrounding white space; a UTF-8 byte order mark
  /// is skipped). \throw IoError(name, "JSON byte N: ...") at the first problem.
  JsonDocument(std::string_view text, const std::string& name);

  [[nodiscard]] const JsonValue& root() const { return values_.front(); }
  [[nodiscard]] const JsonValue& at(std::size_t index) const { return values_[index]; }
  /// The member `key` of `object` (the first, if repeated), or nullptr when there is none or
  /// `object` is not an object.
  [[nodiscard]] const JsonValue* member(const JsonValue& object, std::string_view key) const;

 private:
  std::vector<JsonValue> values_;
};

}  // namespace sculpt::mesh::detail
