#pragma once
/// \file from_mesh.hpp
/// B-rep to BSP (Thibault & Naylor 1987): the tree is built top-down from the face polygons
/// (explicit stack). Each node's plane, a face plane or an axis-aligned auxiliary plane, is the
/// candidate of least estimated expected depth of a point query (Naylor, "Constructing good
/// partitioning trees", 1993; Ihm & Naylor 1990 sec. 6): cell volumes are estimated from points
/// sampled in the mesh's box (fixed seed: deterministic), polygon counts from a sample of the
/// cell's polygons (docs/bsp.md, "B-rep to BSP"). Only the choice is estimated; the tree is exact.

#include "bsp/solid.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// How the planes are chosen (defaults tuned on the goblet, the bunny and the Menger sponge:
/// docs/benchmarks.md, "Trees from meshes"). Every setting gives the same solid, only the tree differs.
struct FromMeshOptions {
  int candidates = 6;           ///< face planes scored per node (drawn at random, fixed seed)
  int sample = 48;              ///< polygons of the cell each candidate is scored against
  double split_weight = 3.0;    ///< charge for splitting all sampled polygons, in expected nodes
  int volume_samples = 4096;    ///< points uniform in the mesh's box estimating cell volumes
  int point_sample = 128;       ///< points of the cell each candidate is scored against
  bool auxiliary_planes = true; ///< also try axis-aligned planes that carry no face
  double auxiliary_cost = 0.5;  ///< charge for such a plane (it adds a node), in expected nodes
  /// Also try the scored face planes moved just past all of the cell's faces (Naylor's separating
  /// planes). Off: slightly shallower and smaller trees for the goblet and a sphere, not for the
  /// bunny, at 15-23 % more build time (docs/benchmarks.md, "Trees from meshes").
  bool separating_planes = false;
  /// Leave out faces whose snapped vertices are collinear (zero area after snapping) instead of
  /// throwing InvalidInput: the rest still encloses the same volume. General transforms use it
  /// (bsp/transform.hpp), where a face narrower than the grid step is no error of the user's.
  bool skip_degenerate_faces = false;
  /// The caller has checked the mesh after snapping: its vertices are grid points of `grid` and it
  /// is clean there (round_for_output's `clean` at OutputPrecision::Grid: closed, oriented, no
  /// two faces crossing). Its faces then are exactly the solid's boundary, so the solid carries
  /// them and later operations and to_mesh need not extract the boundary from the tree again.
  /// The tree itself is then built on first use (bsp/local/deferred_build.hpp): an import that is
  /// only transformed, combined by the set operations' cell path and written out never builds it.
  bool snapped_mesh_is_clean = false;
  /// The grid the vertices are snapped to, which the solid carries (docs/kernel.md, "World range").
  kernel::Grid grid{};
};

/// Solid bounded by a closed mesh (world units of options.grid, snapped to it; outward orientation).
/// A face whose snapped vertices are exactly coplanar keeps one plane; otherwise each triangle of
/// its triangulation gets its own plane through its three grid points (so the boundary still
/// closes exactly; the face count of a later to_mesh can then grow). \pre the caller validated the mesh (lib/mesh/mesh_validation.hpp): closed,
/// manifold, oriented, not self-intersecting. \throw RangeError for coordinates out of range,
/// InvalidInput for faces with fewer than three non-collinear vertices (unless
/// options.skip_degenerate_faces).
Solid from_mesh(const PolygonMesh& mesh, const FromMeshOptions& options = {});

}  // namespace sculpt
