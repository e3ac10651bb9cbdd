#include "language/record.hpp"

#include <memory>

namespace sculpt::language {

const Value* Record::field(const std::string& name) const {
  for (const auto& [key, value] : fields_) {
    if (key == name) return &value;
  }
  return nullptr;
}

std::string Record::repr() const {
  std::string out = "{";
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    if (i > 0) out += ", ";
    out += fields_[i].first + ": " + to_repr(fields_[i].second);
  }
  return out + "}";
}

Value record_value(Record::Fields fields) {
  return Value(std::shared_ptr<const Object>(std::make_shared<Record>(std::move(fields))));
}

}  // namespace sculpt::language
