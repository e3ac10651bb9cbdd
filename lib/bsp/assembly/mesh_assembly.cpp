#include "bsp/assembly/mesh_assembly.hpp"

#include "base/assert.hpp"
#include "base/cancel.hpp"
#include "bsp/assembly/coplanar_faces.hpp"
#include "bsp/assembly/faces.hpp"
#include "bsp/assembly/junction_removal.hpp"
#include "bsp/assembly/sheets.hpp"
#include "bsp/assembly/vertex_merge.hpp"
#include "mesh/edge_incidence.hpp"
#include "mesh/touching_vertices.hpp"

#include <utility>

namespace sculpt::bsp::detail {

namespace {

// The fragments as a mesh on merged vertices, before touching vertices are inserted. Its own
// function so that the stages' data (merged vertices and classes, plane ids, sheets: 14 MB for
// the armadillo job's output) is freed before the touching-vertex search allocates its own.
PolygonMesh merged_faces(FragmentsView fragments, const AssemblyOptions& options, std::vector<char>& exact) {
  // Ctrl-C (base/cancel.hpp) is checked between the steps (each linear in the fragments).
  MergedFragments merged = merge_vertices(fragments);
  check_cancel();
  const PlaneIds& ids = merged.ids;
  const VertexGeometry geometry(fragments.planes, ids, merged.vertices);
  FaceList faces = remove_t_junctions(std::move(merged.faces), geometry, ids).faces;
  check_cancel();
  faces = merge_coplanar_faces(std::move(faces), merged.vertices.size(), ids);
  check_cancel();
  faces = remove_straight_vertices(std::move(faces), merged.vertices.size(), geometry);
  const Sheets sheets = split_non_manifold(std::move(faces), merged.vertices, fragments.planes);
  check_cancel();
  return output_mesh(
      sheets, merged.vertices, fragments.planes,
      {.triangulate = options.triangulate, .grid = options.grid, .approximate = options.approximate, .exact = &exact});
}

}  // namespace

// The stages, each in its own file: exact vertex merging and the fragments as faces on the
// merged vertices (vertex_merge), T-junction removal (junction_removal), coplanar merging and
// straight vertices (assembly_coplanar), one vertex copy per sheet and output
// (assembly_sheets), vertices touching another part's face or edge made corners there
// (mesh/touching_vertices); shared data in assembly_faces.
PolygonMesh assemble_mesh(FragmentsView fragments, const AssemblyOptions& options) {
  std::vector<char> own_flags;
  std::vector<char>& exact = options.exact_vertices != nullptr ? *options.exact_vertices : own_flags;
  PolygonMesh mesh = merged_faces(fragments, options, exact);
  check_cancel();
  // Where parts touch at an isolated point inside another part's face or edge, the point becomes
  // a corner there too (mesh/touching_vertices.hpp; docs/kernel.md, "Clean output").
  insert_touching_vertices(mesh, exact, options.triangulate);
  SCULPT_ASSERT(edges_paired(mesh), "assemble_mesh: the output uses an edge other than once in each direction");
  return mesh;
}

}  // namespace sculpt::bsp::detail
