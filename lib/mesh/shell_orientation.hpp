#pragma once
/// \file shell_orientation.hpp
/// Whether each shell (connected component) of a closed, consistently oriented mesh faces the
/// way its nesting asks for: a shell inside an even number of other shells bounds material and
/// must face outwards (positive signed volume); one inside an odd number bounds a cavity and
/// must face inwards. Then the winding number of the whole mesh is 0 or 1 everywhere, which is
/// what a solid's boundary needs. Nesting is decided exactly (ray parity with exact orient3d).

#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

struct ShellOrientation {
  std::vector<int> faces;     ///< the shell's faces (indices into the mesh)
  double signed_volume = 0;   ///< > 0: the shell faces outwards
  int enclosing_shells = 0;   ///< how many other shells contain this one
  /// True when the orientation agrees with the nesting (see the file comment).
  [[nodiscard]] bool consistent() const { return (enclosing_shells % 2 == 0) == (signed_volume > 0); }
};

/// The shells of `mesh` (faces connected through shared vertices), each with its signed volume
/// and nesting depth. \pre the mesh is closed, consistently oriented and free of
/// self-intersections (otherwise the nesting is not well defined; the result is then
/// unspecified, but the call still returns).
/// \throw InvalidInput for a face index out of range.
std::vector<ShellOrientation> shell_orientations(const PolygonMesh& mesh);

}  // namespace sculpt
