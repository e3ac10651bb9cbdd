#pragma once
/// \file certified_patches.hpp
/// Patches of a triangle mesh certified to be embedded: connected sets of triangles that project
/// one to one along a coordinate axis (one fan round each vertex, one boundary loop that projects
/// to a simple polygon; the degree of the map), so that the self-intersection search passes over
/// the pairs of triangles within one patch (docs/mesh_io.md). Every decision is an exact sign or
/// comparison.

#include <vector>

#include <Eigen/Core>

#include "mesh/detail/certified_stars.hpp"

namespace sculpt::mesh::detail {

/// Per triangle: the id of the certified patch it belongs to, else -1 - (its index): two
/// triangles of one certified patch meet only in what they share. cls: per triangle 2 axis +
/// (sign > 0), the sign of its projection along its axis as the filter decides it, or -1. A patch
/// is a connected set of triangles of one class joined across edges they share with opposite
/// directions. It is certified when
///  - round each vertex its triangles form one fan, closed or open (distinct ends; a vertex
///    whose star certified_stars certified for this projection has one closed fan);
///  - the open fans' outer edges form one loop, which projects to a simple polygon (closed
///    segments, exact tests).
/// Then the projection is one to one on the patch (the degree of the map): a point of the
/// plane off the projected edges is covered once by each triangle over it, all oriented alike,
/// and as many times as the loop winds round it, at most once. So no two triangles' projections
/// overlap, and none touch but along shared edges and corners (a corner touching another
/// triangle would have its fan overlap a neighbour of that triangle or, on the loop, make the
/// loop touch itself), and the triangles meet only in their common vertices and edges.
/// Unless three quarters of the vertices have certified stars, no patch is looked for (they
/// would be small). `stars`: certified_stars of the same triangles; `points`: the ids' positions.
std::vector<int> certified_patches(const std::vector<signed char>& cls, const CertifiedStars& stars,
                                   const std::vector<Eigen::Vector3d>& points);

}  // namespace sculpt::mesh::detail
