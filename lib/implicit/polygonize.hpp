#pragma once
/// \file polygonize.hpp
/// The boundary of an implicit solid {f <= 0} inside a box as a closed, oriented 2-manifold
/// triangle mesh: the step from the paper's implicit curves and patches (Ihm & Naylor 1990,
/// sec. 5) to solids the BSP modeler can combine (sec. 6 builds its trees from such boundaries).
///
/// Method (docs/implicit.md, "Implicit solids"): an adaptive octree over the box, built with an
/// explicit stack. A cell whose interval bounds exclude 0 is proven empty or full and not split.
/// A cell whose corner signs differ is split while the normals at its corners say the surface
/// bends more inside it than a flat triangle of its size can follow within tol. A cell whose
/// corners agree but whose bounds cannot exclude 0 is searched (sub-cells culled by interval
/// bounds, down to feature_size / 2) for a point of the other sign; one found splits the cell.
/// The octree is 2:1 balanced over faces, edges and corners; each leaf is cut into tetrahedra
/// that conform across all leaves (the 6 Kuhn tetrahedra of a cube whose faces have no finer
/// neighbour, else a cone from the cube centre over its faces' triangles), and marching
/// tetrahedra with safeguarded root finding on the edges gives the surface. f == 0 counts as
/// inside. Where {f <= 0} meets the box, the box faces' triangles, clipped by the same edge
/// roots, close the solid: the result bounds {f <= 0} inside the box.
/// With simplify (the default) the octree is coarse first: unless the surface meets the box in
/// it, a crossed cell is split only while a flat piece of it would be off by more than 8 tol (the
/// other criteria are unchanged), the marched mesh is brought within 0.8 tol by edge splits whose
/// new vertices are put on f = 0 (detail/refine.hpp), and the collapses follow. Far fewer
/// triangles are marched (the torus at 2e-3: 14,528 instead of 127,448). Should a split fail (a
/// new triangle facing against grad f) or the collapses' mesh intersect itself, the fine octree
/// is meshed instead.
///
///   PolygonizeResult r = polygonize(f, {.box = {.lo = {-2, -2, -1}, .hi = {2, 2, 1}}, .tolerance = 2e-3});
///   // r.mesh: triangles, counter-clockwise from outside

#include <functional>

#include <Eigen/Core>

#include "implicit/expression.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::implicit {

struct PolygonizeOptions {
  Box box;                   ///< the region; the solid is {f <= 0} inside it
  double tolerance = 1e-3;   ///< wanted distance between the mesh and the surface (see guarantees)
  /// Components of {f <= 0} or of {f > 0} that contain a ball of this diameter are found even
  /// where every corner of a cell has the same sign. 0: 4 * tolerance.
  double feature_size = 0.0;
  /// Work budget: octree cells and search cells visited, and leaves made by balancing. Running
  /// out is a GeometryError, never a hang.
  long max_cells = 4'000'000;
  /// Coarse octree, edge splits towards f = 0, then collapse edges where the surface is flat (half-edge collapses that keep the mesh a manifold
  /// and every changed triangle within 0.7 tol (0.8 tol for slivers) of f = 0 by the first-order distance |f| / |grad f|;
  /// the result is checked for self-intersections exactly and dropped if it has any).
  bool simplify = true;
  /// With simplify: triangles less high than this (2 area / longest edge) are then collapsed
  /// away where the checks allow (marching tetrahedra makes slivers where the surface passes
  /// near a lattice point; snapping the vertices to a grid could turn them over).
  double min_height = 0.0;
  /// A vertex on a lattice edge is kept at least this far from the edge's ends (at most a quarter
  /// of the edge): where the surface passes within it of a lattice point, the vertex moves along
  /// the edge by up to this much. A caller that snaps the vertices to a grid gives a few grid
  /// steps, so that no vertex snaps onto a lattice point (a box corner of the closing faces, or
  /// the vertex on another edge from that point). 0: 1e-7 of the edge.
  double min_root_gap = 0.0;
  /// With simplify: the test a simplified mesh must pass to be kept, instead of the exact test for
  /// self-intersections (a simplified mesh that fails it is dropped, as one that intersects itself
  /// would be). For a caller that builds its solid from a changed copy of the mesh and must test
  /// that copy anyway (the language snaps the vertices to the exact kernel's grid): the test is then
  /// made once, on the mesh that matters. Empty: find_self_intersections (lib/mesh).
  std::function<bool(const PolygonMesh&)> accept_simplified = {};
};

struct PolygonizeResult {
  PolygonMesh mesh;             ///< triangles, counter-clockwise seen from outside
  long cells = 0;               ///< octree cells visited (interval bounds evaluated)
  long search_cells = 0;        ///< cells visited while searching same-sign cells for hidden parts
  long leaves = 0;              ///< octree leaves after balancing
  long tetrahedra = 0;          ///< tetrahedra marched
  long marched_triangles = 0;   ///< triangles marched (before the edge splits and collapses)
  long refinements = 0;         ///< edge splits towards f = 0 after marching the coarse octree
  /// The mesh comes from the coarse octree and edge splits; false: from the fine octree (without
  /// simplify, or as the fallback when the coarse way failed).
  bool coarse = false;
  long collapses = 0;           ///< edge collapses kept
  bool simplify_rejected = false;  ///< the simplified mesh intersected itself; the marched one is returned
  /// The mesh returned is a simplified one that passed options.accept_simplified (false without
  /// that option, without simplify, and when the marched mesh is returned).
  bool accepted = false;
  long thin_triangles = 0;      ///< triangles still below min_height after simplification
  int max_level = 0;            ///< deepest leaf (the root, the box, is level 0)
  /// Cells whose search reached feature_size / 2 without proving the cell free of the surface or
  /// finding a point of the other sign (the surface may touch such a cell without crossing it).
  long unresolved_cells = 0;
};

/// Meshes the boundary of {f <= 0} inside options.box.
///
/// Guaranteed, by construction: the mesh is closed, consistently oriented (outward), 2-manifold
/// (every edge in two triangles, every vertex a single fan) and without self-intersections
/// (each triangle lies in one tetrahedron of a conforming tetrahedral mesh, or on a box face);
/// every vertex is on f = 0 (to root-finding accuracy, about 1e-12 of its edge; a vertex of an
/// edge split to |f| / |grad f| <= 1e-10 of the edge) or on the box;
/// a component of either sign that contains a ball of diameter feature_size is present. With
/// simplify, closed, oriented, manifold and unintersecting still hold (the last checked exactly;
/// with accept_simplified, the simplified mesh passed that test instead, or the marched one is returned).
/// Not guaranteed, measured (tests/implicit/polygonize_test.cpp): the Hausdorff distance to
/// the surface (about tol where the surface is smooth; sharp creases of f are cut off by up
/// to a cell), and the topology inside cells whose corners differ in sign (a surface that
/// crosses one edge twice, or two sheets closer than a cell, may join or part).
/// \throw InvalidInput for an invalid box, tolerance <= 0 or below 4e-6 of the box's longest side,
///        a negative feature_size or max_cells <= 0; GeometryError when the budget runs out;
///        NonFiniteValue when f is not finite at a point it is evaluated at.
[[nodiscard]] PolygonizeResult polygonize(const Expression& f, const PolygonizeOptions& options);

}  // namespace sculpt::implicit
