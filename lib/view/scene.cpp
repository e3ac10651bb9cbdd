#include "view/scene.hpp"

#include <algorithm>

#include "base/parallel.hpp"
#include "language/picture_items.hpp"
#include "language/solid_values.hpp"
#include "mesh/mesh_measures.hpp"
#include "splines/tessellate_surface.hpp"

namespace sculpt::view {
namespace {

/// A B-spline surface's triangles, the chord error a small share of its control points' box.
PolygonMesh surface_mesh(const splines::BSplineSurface& surface) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : surface.controls()) box.extend(p);
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  const splines::SurfaceTriangles t =
      splines::tessellate(surface, {.tolerance = diagonal > 0 ? kSurfaceChordShare * diagonal : 1e-3});
  PolygonMesh mesh;
  mesh.vertices = t.points;
  mesh.faces.reserve(t.triangles.size());
  for (const auto& tri : t.triangles) mesh.faces.push_back({tri[0], tri[1], tri[2]});
  return mesh;
}

/// A spline curve's points: kSplineSegmentsPerSpan per knot span (fewer when there are many
/// spans, so that at most kMaxCurvePoints are made).
std::vector<Eigen::Vector3d> spline_points(const splines::BSpline& spline) {
  const std::vector<double> breaks = spline.breaks();
  if (breaks.size() < 2) return {};
  const std::size_t spans = breaks.size() - 1;
  const int per_span = static_cast<int>(
      std::clamp<std::size_t>(kMaxCurvePoints / spans, 1, static_cast<std::size_t>(kSplineSegmentsPerSpan)));
  std::vector<Eigen::Vector3d> points{spline.point(breaks.front())};
  for (std::size_t k = 0; k < spans; ++k)
    for (int i = 1; i <= per_span; ++i)
      points.push_back(
          spline.point(i == per_span ? breaks[k + 1] : breaks[k] + (breaks[k + 1] - breaks[k]) * i / per_span));
  return points;
}

/// A part of `value` (what render draws), or nullopt for anything else.
std::optional<ViewPart> part_of(const language::Value& value) {
  ViewPart part;
  part.value = value;
  if (const auto* s = value.object<language::SolidValue>()) {
    part.solid = true;
    // The exact boundary, once: for a screen the output rounding that makes files clean is not
    // needed, and the measures come from the same faces (a million faces: seconds saved).
    part.mesh = s->display_boundary();
    // The measures side by side (each a pass over a million faces takes tens of ms).
    parallel_invoke([&] { part.volume = s->exact_boundary ? s->volume() : mesh_volume(part.mesh); },
                    [&] {
                      part.area = s->exact_boundary ? s->area() : mesh_surface_area(part.mesh);
                      part.box = mesh_bounding_box(part.mesh);
                    });
    return part;
  } else if (const auto* m = value.object<language::MeshValue>()) {
    part.mesh = m->mesh;
    part.area = mesh_surface_area(part.mesh);
  } else {
    auto item = language::picture_item(value);
    const auto* picture = std::get_if<render::PictureItem>(&item);
    if (!picture) return std::nullopt;
    if (const auto* surface = std::get_if<splines::BSplineSurface>(picture)) {
      part.mesh = surface_mesh(*surface);
      part.area = mesh_surface_area(part.mesh);
    } else if (const auto* mesh = std::get_if<render::PictureMesh>(picture)) {
      part.mesh = mesh->mesh;
      part.area = mesh_surface_area(part.mesh);
    } else if (const auto* spline = std::get_if<splines::BSpline>(picture)) {
      part.curve = spline_points(*spline);  // a closed spline's last break is its first point again
    } else if (const auto* polyline = std::get_if<render::PictureCurve>(picture)) {
      part.curve = polyline->points;
      if (polyline->closed && part.curve.size() > 2) part.curve.push_back(part.curve.front());
    }
    for (std::size_t k = 0; k < part.curve.size(); ++k) {
      part.box.extend(part.curve[k]);
      if (k) part.length += (part.curve[k] - part.curve[k - 1]).norm();
    }
  }
  if (!part.mesh.vertices.empty()) part.box = mesh_bounding_box(part.mesh);
  return part;
}

}  // namespace

std::array<double, 3> palette_color(std::size_t index) {
  static constexpr std::array<double, 3> kPalette[] = {{0.35, 0.55, 0.85}, {0.9, 0.5, 0.2},   {0.35, 0.7, 0.4},
                                                       {0.8, 0.3, 0.35},   {0.6, 0.45, 0.75}, {0.75, 0.65, 0.3},
                                                       {0.3, 0.7, 0.75},   {0.55, 0.55, 0.55}};
  return kPalette[index % std::size(kPalette)];
}

Scene scene_of(const std::vector<language::ShownPart>& shown, const std::optional<language::Value>& last_solid) {
  Scene scene;
  for (const language::ShownPart& s : shown) {
    std::optional<ViewPart> part = part_of(s.value);
    if (!part) continue;
    part->name = s.name;
    part->color = s.color ? *s.color : palette_color(scene.parts.size());
    scene.parts.push_back(std::move(*part));
  }
  if (shown.empty() && last_solid) {
    if (std::optional<ViewPart> part = part_of(*last_solid)) {
      part->name = "last solid";
      part->color = palette_color(0);
      scene.parts.push_back(std::move(*part));
    }
  }
  return scene;
}

}  // namespace sculpt::view
