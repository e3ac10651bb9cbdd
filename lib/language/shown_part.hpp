#pragma once
/// \file shown_part.hpp
/// What show(x, name=..., color=...) collects for the live view (builtins_view.cpp; the view
/// itself is lib/view, docs/viewing.md).

#include <array>
#include <optional>
#include <string>

#include "language/value.hpp"

namespace sculpt::language {

/// A value put in the view by show().
struct ShownPart {
  std::string name;
  std::optional<std::array<double, 3>> color;  ///< red, green, blue in [0, 1]; none: the view picks one
  Value value;  ///< what render draws (language/picture_items.hpp): a solid, a mesh, a surface, a curve...
};

}  // namespace sculpt::language
