// Built-ins of the solids area (registered from builtins.cpp).
#include "language/builtins.hpp"

namespace sculpt::language {

void register_solids(BuiltinTable& /*table*/) {}

}  // namespace sculpt::language
