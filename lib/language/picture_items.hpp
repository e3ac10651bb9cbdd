#pragma once
/// \file picture_items.hpp
/// What `render` and the REPL's `:show` draw: a value of any area that has a picture (solids,
/// meshes, surfaces, splines, curves, linearizations, motions, lists of points), or a list of them.

#include <string>
#include <variant>
#include <vector>

#include "language/value.hpp"
#include "render/picture.hpp"

namespace sculpt::language {

/// Samples per pixel side of the pictures `render` and `:show` make unless told (antialiasing:
/// edges and lines without stair steps, at four times the drawing work).
inline constexpr int kPictureAntialias = 2;

/// True for a list of points ([[x, y, z], ...]), which is one item, as opposed to a list of items.
bool is_point_list(const List* list);

/// The picture item of v, or why it has none ("must be a solid, mesh, ...").
std::variant<render::PictureItem, std::string> picture_item(const Value& v);

/// The items of x (one value, or a list of them), or the first error, naming the item
/// ("item 2 must be ...", or `name` for x itself: "x must be ...").
std::variant<std::vector<render::PictureItem>, std::string> picture_items(const Value& x, const std::string& name);

}  // namespace sculpt::language
