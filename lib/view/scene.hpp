#pragma once
/// \file scene.hpp
/// What the live view shows: named, coloured parts (solids, meshes, B-spline surfaces as
/// triangles, curves as polylines) with their measures, made from what a script showed
/// (show(x, name=, color=)) or, without show, from its last solid.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "language/shown_part.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::view {

/// The chord error of a B-spline surface's triangles in the view, as a share of the diagonal of
/// its control points' box.
inline constexpr double kSurfaceChordShare = 1e-3;
/// Segments per knot span of a spline curve in the view, and at most this many points in all.
inline constexpr int kSplineSegmentsPerSpan = 64;
inline constexpr std::size_t kMaxCurvePoints = 1u << 18;

/// One part of the view.
struct ViewPart {
  std::string name{};
  std::array<double, 3> color{};  ///< red, green, blue in [0, 1]
  bool solid = false;             ///< a solid (closed; has a volume) rather than an open mesh
  /// The boundary (exact polygon faces, not triangulated), an open mesh, or a surface's triangles
  /// (chord error kSurfaceChordShare of its size); empty for a curve.
  PolygonMesh mesh{};
  /// A curve's points (splines sampled kSplineSegmentsPerSpan times per span, a closed curve
  /// ending where it starts); empty for a part with a mesh.
  std::vector<Eigen::Vector3d> curve{};
  std::optional<double> volume;  ///< solids only, from the exact boundary
  double area = 0;
  double length = 0;        ///< a curve's: its polyline's
  Eigen::AlignedBox3d box;  ///< empty for an empty part
  /// The script value shown (a solid or a mesh): the depth mode reads a solid's tree from it.
  language::Value value{};
};

struct Scene {
  std::vector<ViewPart> parts;
};

/// The scene of a run: the parts in `shown` in order; when it is empty, `last_solid` (a solid
/// value, if any) as the part "last solid". Parts without a colour get one from a fixed palette
/// (by position). Values render cannot draw are skipped (show() refuses them).
Scene scene_of(const std::vector<language::ShownPart>& shown, const std::optional<language::Value>& last_solid);

/// The palette colour of the part at `index`.
std::array<double, 3> palette_color(std::size_t index);

}  // namespace sculpt::view
