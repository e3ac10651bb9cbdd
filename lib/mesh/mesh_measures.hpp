#pragma once
/// \file mesh_measures.hpp
/// Global measures of a polygon mesh: volume (divergence theorem), surface area, bounding
/// box, Euler characteristic, connected components and genus. Faces may be any planar
/// polygons (convex or not); sums are compensated (Neumaier) so large meshes keep accuracy.

#include <Eigen/Geometry>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// Signed volume enclosed by a closed, outward-oriented mesh: sum over faces of the
/// fan tetrahedra (v0, vi, vi+1) against a reference point, / 6 (divergence theorem).
/// Positive for outward (counter-clockwise from outside) faces. Meaningless for open meshes.
double mesh_volume(const PolygonMesh& mesh);
/// The same for a triangle mesh (the same sums in the same order: equal to the PolygonMesh's).
double mesh_volume(const TriangleMesh& mesh);

/// Sum of face areas (half the norm of each face's Newell normal; exact for planar faces).
double mesh_surface_area(const PolygonMesh& mesh);
double mesh_surface_area(const TriangleMesh& mesh);

/// Polygons given by their points, each its own (no vertex shared): polygon i is points
/// [offsets[i], offsets[i + 1]). For measures of a surface that is tiled but not assembled (a
/// solid's boundary fragments: bsp/boundary.hpp).
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> offsets{0};
};
/// mesh_volume and mesh_surface_area of the mesh whose faces are the soup's polygons: the
/// divergence theorem needs only a tiling of the closed surface, not shared vertices.
double soup_volume(const PolygonSoup& soup);
double soup_surface_area(const PolygonSoup& soup);

/// Axis-aligned bounding box of the vertices referenced by faces (empty box if none).
Eigen::AlignedBox3d mesh_bounding_box(const PolygonMesh& mesh);

/// V - E + F with V = vertices referenced by faces and E = distinct undirected edges.
int euler_characteristic(const PolygonMesh& mesh);

/// Component id per face (0-based, in order of first appearance); faces sharing a vertex
/// belong to the same component.
std::vector<int> face_components(const PolygonMesh& mesh);

/// Number of connected components (faces connected through shared vertices).
int component_count(const PolygonMesh& mesh);

/// Total genus of a closed orientable mesh: sum over components of (2 - chi_i) / 2,
/// i.e. (2 C - chi) / 2.
/// \throw GeometryError if some edge does not have exactly two faces (not closed) or
/// 2 C - chi is odd.
int genus(const PolygonMesh& mesh);

}  // namespace sculpt
