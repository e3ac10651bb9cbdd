#pragma once
/// \file assembly_sheets.hpp
/// Internal to mesh assembly: where the solid touches itself along an edge or at a vertex, each
/// sheet gets its own copy of the vertices there, so every sheet is a 2-manifold (as Manifold
/// does; docs/kernel.md); then the output mesh.

#include "bsp/assembly/faces.hpp"
#include "kernel/grid.hpp"
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

struct OutputMeshOptions {
  bool triangulate = false;  ///< each face triangulated by mesh/triangulate.hpp's exact ear clipping
  kernel::Grid grid{};       ///< the solid's grid: output vertices in its world units
  /// For a screen: a vertex whose approximation's error bound is at most kDisplayError grid units
  /// is written at its approximation instead of correctly rounded (kernel::rounded_vertex, whose
  /// exact arithmetic is a third of a faceted sphere's assembly). Not for files: the coordinates
  /// then depend on which corner the vertex was first seen at.
  bool approximate = false;
  /// If given, receives one flag per output vertex: 1 when its coordinates are exactly the vertex
  /// (nothing was rounded; see exactly_represented), else 0. With `approximate`, only vertices
  /// whose approximation is exact (error bound 0) can be flagged.
  std::vector<char>* exact = nullptr;
};

/// The error bound, in grid units, up to which `approximate` output takes a vertex's
/// approximation: 2^-20 of a grid step (3e-11 world units at the default grid), far below what a
/// screen or a picked coordinate shows; a looser vertex (nearly dependent planes) is rounded.
inline constexpr double kDisplayError = 0x1p-20;

/// The mesh in world units of options.grid (only vertices used by faces are written; coordinates
/// by kernel::rounded_vertex, or as options.approximate says).
PolygonMesh output_mesh(const Sheets& sheets, const AssemblyVertices& vertices, const kernel::PlaneTable& planes,
                        const OutputMeshOptions& options = {});

/// The double coordinates `at` (grid units) are exactly the vertex p ∩ q ∩ r: decided exactly
/// but only for grid points (integer coordinates below 2^53, which lie on all three planes:
/// independent planes meet in that one point); any other point is answered false, so a `true`
/// is always right and a `false` may be wrong (a vertex at a non-integer dyadic point). The
/// floating-point filter of kernel::filtered_orient rejects most inexact vertices first.
/// \pre independent(p, q, r).
bool exactly_represented(const kernel::Plane& p, const kernel::Plane& q, const kernel::Plane& r,
                         const Eigen::Vector3d& at);

}  // namespace sculpt::bsp::detail
