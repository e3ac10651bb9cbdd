#pragma once
/// \file scene.hpp
/// What the live view shows: named, coloured parts (solids and meshes) with their measures, made
/// from what a script showed (show(x, name=, color=)) or, without show, from its last solid.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "language/shown_part.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::view {

/// One part of the view.
struct ViewPart {
  std::string name{};
  std::array<double, 3> color{};  ///< red, green, blue in [0, 1]
  bool solid = false;             ///< a solid (closed; has a volume) rather than an open mesh
  PolygonMesh mesh{};             ///< the boundary: exact polygon faces, not triangulated
  std::optional<double> volume;   ///< solids only, from the exact boundary
  double area = 0;
  Eigen::AlignedBox3d box;  ///< empty for an empty part
  /// The script value shown (a solid or a mesh): the depth mode reads a solid's tree from it.
  language::Value value{};
};

struct Scene {
  std::vector<ViewPart> parts;
};

/// The scene of a run: the parts in `shown` in order; when it is empty, `last_solid` (a solid
/// value, if any) as the part "last solid". Parts without a colour get one from a fixed palette
/// (by position). Values that are neither solids nor meshes are skipped (show() refuses them).
Scene scene_of(const std::vector<language::ShownPart>& shown, const std::optional<language::Value>& last_solid);

/// The palette colour of the part at `index`.
std::array<double, 3> palette_color(std::size_t index);

}  // namespace sculpt::view
