#include "bsp/boundary.hpp"

#include <optional>

#include "base/parallel.hpp"
#include "bsp/assembly/mesh_assembly.hpp"
#include "bsp/tree/boundary_fragments.hpp"
#include "bsp/tree/solid_access.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/output_rounding.hpp"

namespace sculpt {

PolygonMesh to_mesh(const Solid& solid, const MeshOptions& options) {
  // A carried boundary (set operation results) is used as is, without building a deferred tree
  // (solid.hpp): a solid with boundary fragments is not a leaf. Otherwise it is extracted.
  // An import whose tree waits keeps the triangles it was made from: they are its exact boundary.
  if (!options.clean)
    if (const TriangleMesh* source = bsp::detail::SolidAccess::deferred_source_mesh(solid))
      return to_polygon_mesh(*source);
  const Solid::BoundaryView view = solid.boundary_view();
  const bool carried = view.fragments != nullptr && !view.fragments->empty();
  if (!carried && is_leaf(solid.root())) return {};
  std::optional<bsp::detail::Fragments> extracted;
  if (!carried) extracted = bsp::detail::boundary_fragments(solid);
  const bsp::detail::FragmentsView f = carried ? bsp::detail::FragmentsView(*view.planes, *view.fragments)
                                               : bsp::detail::FragmentsView(*extracted);
  if (!options.clean)
    return bsp::detail::assemble_mesh(
        f, {.triangulate = options.triangulate, .grid = solid.grid(), .approximate = options.approximate});
  // Vertices written exactly (a grid point, say) are marked for the clean check: the assembled
  // faces are the exact boundary of the solid, which is clean (docs/kernel.md, "Clean output"),
  // so only pairs of faces with a rounded corner need a test.
  std::vector<char> exact_vertices;
  PolygonMesh exact = bsp::detail::assemble_mesh(
      f, {.triangulate = options.triangulate, .grid = solid.grid(), .exact_vertices = &exact_vertices});
  return round_for_output(std::move(exact),
                          {.precision = OutputPrecision::Double, .max_feature = solid.grid().step(),
                           .exact_vertices = exact_vertices},
                          options.report);
}

namespace {

// The solid's boundary fragments as polygons in world units, not assembled into a mesh (no
// vertex merging, no T-junction or coplanar-face work: the measures need only a tiling of the
// boundary, which the fragments are; solid.hpp). Corners are the exact vertices rounded as the
// output rounds them (kernel::rounded_vertex), in reverse order on fragments that face their
// plane's negative side. An import whose tree waits measures the triangles it was made from.
PolygonSoup boundary_soup(const Solid& solid) {
  PolygonSoup soup;
  const Solid::BoundaryView view = solid.boundary_view();
  const bool carried = view.fragments != nullptr && !view.fragments->empty();
  if (!carried && is_leaf(solid.root())) return soup;
  std::optional<bsp::detail::Fragments> extracted;
  if (!carried) extracted = bsp::detail::boundary_fragments(solid);
  const FragmentList& fragments = carried ? *view.fragments : extracted->fragments;
  const kernel::PlaneTable& planes = carried ? *view.planes : extracted->planes;
  soup.offsets.reserve(fragments.size() + 1);
  for (const FragmentRef f : fragments) soup.offsets.push_back(soup.offsets.back() + f.polygon.corners.size());
  soup.points.resize(soup.offsets.back());
  const kernel::Grid& grid = solid.grid();
  // Each fragment writes its own points (rounding is most of the work): the same soup for any
  // thread count.
  constexpr std::size_t kChunk = 2048;
  parallel_chunks(fragments.size(), kChunk, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const FragmentRef f = fragments[i];
      const auto& corners = f.polygon.corners;
      Eigen::Vector3d* out = soup.points.data() + soup.offsets[i];
      for (std::size_t k = 0; k < corners.size(); ++k) {
        const kernel::Corner& c = corners[f.flip ? corners.size() - 1 - k : k];
        out[k] = grid.to_world(kernel::rounded_vertex(planes[f.polygon.support], planes[c.p], planes[c.q], c.at()));
      }
    }
  });
  return soup;
}

}  // namespace

// Measures from the boundary fragments (one implementation, compensated sums, for meshes and
// solids: mesh/mesh_measures.hpp), without assembling the output mesh.
double volume(const Solid& solid) {
  if (const TriangleMesh* source = bsp::detail::SolidAccess::deferred_source_mesh(solid)) return mesh_volume(*source);
  return soup_volume(boundary_soup(solid));
}
double surface_area(const Solid& solid) {
  if (const TriangleMesh* source = bsp::detail::SolidAccess::deferred_source_mesh(solid))
    return mesh_surface_area(*source);
  return soup_surface_area(boundary_soup(solid));
}
Eigen::AlignedBox3d bounding_box(const Solid& solid) { return mesh_bounding_box(to_mesh(solid, {.clean = false})); }

}  // namespace sculpt
