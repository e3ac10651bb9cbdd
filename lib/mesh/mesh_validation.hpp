#pragma once
/// \file mesh_validation.hpp
/// Checks that a polygon mesh bounds a solid: a closed, consistently oriented 2-manifold
/// without degenerate faces or self-intersections. Each defect says which elements and
/// where (vertex coordinates), so a user can find it in their modeling tool.

#include <cstddef>
#include <string>
#include <vector>

#include "mesh/polygon_mesh.hpp"

namespace sculpt {

enum class DefectKind {
  InvalidIndex,             ///< face with < 3 corners or an index out of range
  NonFiniteCoordinate,      ///< NaN or infinite vertex coordinate
  DegenerateFace,           ///< repeated corner or all corners collinear (zero area)
  NonPlanarFace,            ///< a corner farther from the face's plane than the tolerance
  SelfCrossingFace,         ///< the boundary of one face crosses or touches itself
  OpenEdge,                 ///< edge used by one face only (boundary)
  NonManifoldEdge,          ///< edge used by more than two faces
  InconsistentOrientation,  ///< two faces run along their shared edge in the same direction
  NonManifoldVertex,        ///< faces around a vertex form more than one fan
  SelfIntersection,         ///< two faces meet away from their shared vertices and edge
  MisorientedShell,         ///< a shell faces inwards outside any other, or outwards in a cavity
};

/// Short lower-case name of a defect kind ("open edge", ...).
const char* defect_name(DefectKind kind);

struct Defect {
  DefectKind kind;
  std::vector<int> faces;     ///< faces involved
  std::vector<int> vertices;  ///< vertices involved (edge ends, the vertex, ...)
  std::string message;        ///< one line: what and where, with coordinates
};

struct ValidationReport {
  std::vector<Defect> defects;
  [[nodiscard]] bool ok() const { return defects.empty(); }
  [[nodiscard]] size_t count(DefectKind kind) const;
  /// Counts per kind, then up to `max_lines` defect messages, one per line.
  [[nodiscard]] std::string summary(size_t max_lines = 10) const;
};

struct ValidationOptions {
  bool check_self_intersections = true;
  /// Planarity and self-crossing boundaries of faces with more than three corners (quadratic in a
  /// face's corner count).
  bool check_face_shapes = true;
  /// Each shell must face the way its nesting asks (shell_orientation.hpp); checked only when
  /// the mesh passed every other check, since nesting needs a closed, unintersecting surface.
  bool check_shell_orientation = true;
  size_t max_defects_per_kind = 100;  ///< keep at most this many defects of each kind
  /// A face is non-planar when a corner lies farther than planarity_tolerance * (the face's
  /// radius around its centroid) from the plane through the centroid normal to the Newell normal.
  double planarity_tolerance = 1e-9;
  std::string source = {};  ///< where the mesh came from (a file): put in the message and GeometryError::where()
};

/// Whether every face has at least 3 corners, every index names a vertex and every coordinate is
/// finite: what check_closed_manifold's other checks, and a self-intersection search, need to read
/// the mesh at all (its first checks, without their messages).
bool indices_and_coordinates_valid(const PolygonMesh& mesh);

/// All defects that keep `mesh` from bounding a solid. Index and coordinate errors stop the
/// other checks (they could not be trusted).
ValidationReport check_closed_manifold(const PolygonMesh& mesh, ValidationOptions options = {});

/// Throws if check_closed_manifold finds anything.
/// \throw GeometryError whose message is "[source: ]mesh is not a closed manifold: " + summary(),
/// with where().file = options.source.
void validate_closed_manifold(const PolygonMesh& mesh, ValidationOptions options = {});

}  // namespace sculpt
