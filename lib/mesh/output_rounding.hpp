#pragma once
/// \file output_rounding.hpp
/// Rounding a closed mesh to the numbers a file holds (doubles, or float32 for binary STL) so that
/// other tools can use it as it is: every edge once in each direction, no two vertices at one
/// point, no face of zero area, no self-intersection, all decided exactly on the rounded
/// coordinates. The exact boundary of a solid can hold features far below the grid step (slivers
/// where two operands' planes nearly meet, a vertex duplicated where the solid touches itself);
/// rounding each vertex alone can then fold or cross faces. Such features are collapsed
/// (a snap-rounding step in the manner of Fortune's vertex rounding, local operations only):
/// short edges are contracted, needle-free slivers are flipped away, copies of one point (sheets
/// touching at an edge or a vertex) are moved apart into their own sheet, and corners of
/// triangles that cross (sheets closer than the rounding) are moved off the other's plane; a
/// result with a shell turned inside out is not taken for clean. Nothing moves
/// farther than `max_feature`: every input vertex ends within that distance of the output vertex
/// that stands for it.

#include <span>
#include <string>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

/// The numbers the coordinates are judged in (and rounded to in the result): doubles, float32,
/// multiples of `OutputRoundingOptions::grid_step` (a power of two: a solid's grid), or what 3MF
/// keeps through lib3mf 1.8 (float32 printed with six decimals, truncated, and read back as
/// float32: the values it writes and reads back unchanged; about a micrometre apart near 1 mm).
enum class OutputPrecision { Double, Float32, Grid, ThreeMf };

struct OutputRoundingOptions {
  OutputPrecision precision = OutputPrecision::Double;
  /// Largest distance any vertex may move (world units); features smaller than this may be
  /// collapsed. 0: 2^-20 of the bounding box's largest extent. For doubles and float32 at least
  /// 256 units in the last place of the largest coordinate is always allowed (float32: about
  /// 3e-5 for coordinates near 1).
  double max_feature = 0;
  /// The reader will triangulate (STL): judge and return triangles even when the polygons are clean.
  bool triangles = false;
  double grid_step = 0;  ///< for OutputPrecision::Grid
  /// Copies of one point (a solid touching itself at an edge or a vertex, each sheet with its own
  /// copy) are allowed and kept, as `from_mesh` reads them; otherwise they are moved apart.
  bool keep_copies = false;
  /// Optional, one flag per vertex of the mesh given (empty: none): nonzero marks a vertex whose
  /// coordinates are exactly its position on a boundary that is clean with every vertex at its
  /// exact position (the precondition of SelfIntersectionOptions::exact_vertices, which the
  /// caller promises). The first check then examines for self-intersections only pairs of faces
  /// of which one has a corner that is not marked or that the rounding to `precision` moves.
  /// bsp's to_mesh fills it from the assembly (docs/kernel.md, "Clean output"). Used only for the
  /// mesh given, never for a repaired one.
  std::span<const char> exact_vertices = {};
};

/// What round_for_output did.
struct OutputRoundingReport {
  bool changed = false;      ///< false: the mesh was clean as it was and is returned unchanged
  bool clean = true;         ///< the result passed every check
  int collapsed_edges = 0;   ///< short edges contracted
  int flipped_edges = 0;     ///< edges flipped to remove slivers
  int separated_vertices = 0;  ///< copies of one point moved into their own sheet
  int nudged_vertices = 0;   ///< corners moved off a crossing triangle's plane (close sheets)
  double feature = 0;        ///< the largest feature size that had to be collapsed
  double max_move = 0;       ///< farthest an input vertex ended from its output vertex
  std::string problem;       ///< the first remaining problem when !clean
};

/// `mesh` (closed, consistently oriented; polygons allowed), clean in `options.precision`.
/// Returned unchanged (polygons kept) when it already is clean after rounding; otherwise as
/// triangles with every coordinate representable in `options.precision`. When even
/// `max_feature` does not suffice, the best mesh found is returned and `report->clean` is false.
/// Returned unchanged with `report->clean` false, too: an open or non-manifold mesh, and one too
/// costly to judge (a face of more than 2048 corners, or a self-intersection search beyond its
/// budget of 16 candidate pairs per corner).
PolygonMesh round_for_output(const PolygonMesh& mesh, const OutputRoundingOptions& options = {},
                             OutputRoundingReport* report = nullptr);
/// The same, taking the mesh: returned without a copy where it is returned unchanged.
PolygonMesh round_for_output(PolygonMesh&& mesh, const OutputRoundingOptions& options = {},
                             OutputRoundingReport* report = nullptr);

/// The first reason `mesh` is not clean for other tools in `options.precision` (after rounding each
/// coordinate; max_feature is not used), or an empty string: an edge not used once in each direction, two vertices at one
/// point, a face of zero area, two faces that intersect.
std::string output_problem(const PolygonMesh& mesh, const OutputRoundingOptions& options = {});

}  // namespace sculpt
