#pragma once
/// \file junction_removal.hpp
/// Internal to mesh assembly: T-junction removal. A vertex lying strictly inside another face's
/// edge is inserted into that edge, so every half-edge gets an opposite one (Naylor et al. 1990
/// leave the fragments' T-junctions to the user; a watertight mesh cannot have them).

#include "bsp/assembly/faces.hpp"

namespace sculpt::bsp::detail {

struct JunctionOptions {
  bool group_by_lines = true;  ///< false: every open edge goes to the spatial search (tests)
};

struct JunctionResult {
  FaceList faces;
  int open = 0;       ///< half-edges without an opposite before insertion
  int by_lines = 0;   ///< of which resolved by their line groups
  int by_search = 0;  ///< of which went to the spatial search
};

/// `faces` with T-junctions removed. Every half-edge without an opposite is a candidate edge,
/// and the endpoints of such half-edges are the candidate vertices (a vertex inside another
/// face's edge has an unmatched half-edge on the other side). Candidates are first grouped by
/// line: half-edges on the same two planes are on one line without arithmetic, half-edges that
/// share an endpoint are joined when exactly collinear; each group's vertices are sorted along
/// the line exactly and inserted into the group's edges they lie strictly inside. An edge whose
/// pieces still lack an opposite falls back to a spatial search over all candidate vertices
/// (on-the-line and between decided exactly).
JunctionResult remove_t_junctions(FaceList faces, const VertexGeometry& geometry, const PlaneIds& ids,
                                  const JunctionOptions& options = {});

}  // namespace sculpt::bsp::detail
