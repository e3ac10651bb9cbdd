#pragma once
/// \file mesh_assembly.hpp
/// Internal: turns boundary fragments into a closed polygon mesh: exact vertex merging,
/// T-junction removal, pairing of half-edges around non-manifold edges and one vertex copy per
/// sheet at non-manifold vertices (as Manifold does; docs/kernel.md).

#include "bsp/tree/boundary_fragments.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::bsp::detail {

struct AssemblyOptions {
  bool triangulate = false;
  kernel::Grid grid{};  ///< the solid's grid: output vertices in its world units
  /// For a screen: vertices at their approximations where those are within kDisplayError
  /// (assembly/sheets.hpp's OutputMeshOptions::approximate).
  bool approximate = false;
  /// If given, receives one flag per output vertex: 1 when its coordinates are exactly the exact
  /// vertex (nothing rounded; output_mesh's exactly_represented), else 0.
  std::vector<char>* exact_vertices = nullptr;
};

PolygonMesh assemble_mesh(FragmentsView fragments, const AssemblyOptions& options);

}  // namespace sculpt::bsp::detail
