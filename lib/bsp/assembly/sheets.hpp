#pragma once
/// \file assembly_sheets.hpp
/// Internal to mesh assembly: where the solid touches itself along an edge or at a vertex, each
/// sheet gets its own copy of the vertices there, so every sheet is a 2-manifold (as Manifold
/// does; docs/kernel.md); then the output mesh.

#include "bsp/assembly/faces.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::bsp::detail {

struct Sheets {
  FaceList faces;             ///< vertex ids renumbered: one vertex per sheet
  std::vector<int> original;  ///< new vertex -> the assembly vertex it stands for
};

/// Pairs each half-edge with its opposite; around an edge shared by more than two faces, the
/// pairs are the faces bounding the same inside wedge (angular order about the edge). Corners
/// connected through paired edges share a vertex; other corners get a copy.
Sheets split_non_manifold(FaceList faces, const AssemblyVertices& vertices, const kernel::PlaneTable& planes);

/// The mesh in world units of `grid` (only vertices used by faces are written; coordinates by
/// kernel::rounded_vertex), optionally with each face triangulated by mesh/triangulate.hpp's
/// exact ear clipping. `exact`, if given, receives one flag per output vertex: 1 when its
/// coordinates are exactly the vertex (nothing was rounded; see exactly_represented), else 0.
PolygonMesh output_mesh(const Sheets& sheets, const AssemblyVertices& vertices, const kernel::PlaneTable& planes,
                        bool triangulate, const kernel::Grid& grid = {}, std::vector<char>* exact = nullptr);

/// The double coordinates `at` (grid units) are exactly the vertex p ∩ q ∩ r: decided exactly
/// but only for grid points (integer coordinates below 2^53, which lie on all three planes:
/// independent planes meet in that one point); any other point is answered false, so a `true`
/// is always right and a `false` may be wrong (a vertex at a non-integer dyadic point). The
/// floating-point filter of kernel::filtered_orient rejects most inexact vertices first.
/// \pre independent(p, q, r).
bool exactly_represented(const kernel::Plane& p, const kernel::Plane& q, const kernel::Plane& r,
                         const Eigen::Vector3d& at);

}  // namespace sculpt::bsp::detail
