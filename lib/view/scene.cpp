#include "view/scene.hpp"

#include "language/solid_values.hpp"
#include "mesh/mesh_measures.hpp"

namespace sculpt::view {
namespace {

/// A part of `value` (a solid or a mesh), or nullopt for anything else.
std::optional<ViewPart> part_of(const language::Value& value) {
  ViewPart part;
  part.value = value;
  if (const auto* s = value.object<language::SolidValue>()) {
    part.solid = true;
    part.mesh = s->boundary();
    part.volume = s->volume();
    part.area = s->area();
  } else if (const auto* m = value.object<language::MeshValue>()) {
    part.mesh = m->mesh;
    part.area = mesh_surface_area(part.mesh);
  } else {
    return std::nullopt;
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
