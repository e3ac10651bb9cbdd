#pragma once
/// \file vertex_moves.hpp
/// The output rounding's vertex moves (mesh/output_rounding.hpp): a copy of a point moved into
/// its own sheet (separate), and corners of triangles that rounding made cross moved off the other
/// triangle's plane (nudge_crossings), each by the smallest step that helps, doubling from the
/// output's resolution, never farther than the limit on moves nor turning a triangle over.

#include "mesh/detail/clean_mesh.hpp"
#include "mesh/output_rounding.hpp"

namespace sculpt::mesh::detail {

/// Sheets closer than the resolution over a wide area (no short edge, no sliver) that rounding
/// made cross: a corner of each crossing pair is moved off the other triangle's plane, either
/// way (at most `delta`). True if anything moved. A full scan: called once contractions and flips
/// are done or stuck, not after each of their passes. Counted in report.nudged_vertices.
bool nudge_crossings(CleanMesh& mesh, double delta, OutputRoundingReport& report);

/// Moves v by at most `delta` against the mean normal of its triangles (into its own sheet), else
/// toward the middle of its neighbours, rounded to the precision, if no triangle turns over or
/// degenerates: by the smallest step after which its triangles meet nothing, else by the step
/// after which they meet fewest, if that is no more than before. True if v moved.
bool separate(CleanMesh& mesh, int v, double delta);

}  // namespace sculpt::mesh::detail
