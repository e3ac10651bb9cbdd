// Built-ins of the curves area (registered from builtins.cpp).
#include "language/builtins.hpp"

namespace sculpt::language {

void register_curves(BuiltinTable& /*table*/) {}

}  // namespace sculpt::language
