#pragma once
/// \file moved_neighbourhood.hpp
/// The faces that a self-intersection search with exact-vertex marks must prepare
/// (SelfIntersectionOptions::exact_vertices): it examines only pairs with a face that has an
/// unmarked corner (a moved face), and two triangles that meet have boxes that meet, so a face
/// whose box meets no moved face's box is in no pair it examines. After a set operation on real
/// meshes, most of the output is marked: the armadillo job's difference moves 10,176 of 81,326
/// triangles, bunny00's 7,852 of 113,390.
///
/// The moved faces' boxes mark the cells of a uniform grid (1-2 times their mean size) that they
/// meet, each box at the finest of levels of cells 4^k times as large where it meets at most 64
/// (Teschner et al. 2003's hierarchical spatial hashing); a face is kept when its box meets a
/// marked cell of some level. Cells are told apart by a hash, and a face whose box meets more
/// than 64 cells of a marked level is kept: both only keep more faces than needed, never fewer.

#include <span>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt::mesh::detail {

/// Per face, nonzero where the face may be in a pair of the marked search: a moved face, a face whose
/// box meets a moved face's box, or a face with fewer than three corners or an index out of range
/// (the search reports those). Empty where every face is kept: when half of them or more are
/// moved, or a box is not finite. `exact`: one mark per vertex.
std::vector<char> faces_near_moved(const PolygonMesh& mesh, std::span<const char> exact);

}  // namespace sculpt::mesh::detail
