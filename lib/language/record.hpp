#pragma once
/// \file record.hpp
/// Records: values with named fields that built-ins return when a result has several parts
/// (`stats` returns one per solid). Read with a string subscript, `r["height"]`; `keys(r)` lists
/// the names in order. Records are values: built once, never changed.

#include <string>
#include <utility>
#include <vector>

#include "language/value.hpp"

namespace sculpt::language {

class Record final : public Object {
 public:
  using Fields = std::vector<std::pair<std::string, Value>>;
  explicit Record(Fields fields) : fields_(std::move(fields)) {}

  [[nodiscard]] const Fields& fields() const { return fields_; }
  /// The field's value, or null if the record has no such field.
  [[nodiscard]] const Value* field(const std::string& name) const;
  [[nodiscard]] std::string type_name() const override { return "record"; }
  /// `{nodes: 12, height: 5}`: fields in order, values as the REPL shows them.
  [[nodiscard]] std::string repr() const override;

 private:
  Fields fields_;
};

/// A record value built from its fields (in the order given).
Value record_value(Record::Fields fields);

}  // namespace sculpt::language
