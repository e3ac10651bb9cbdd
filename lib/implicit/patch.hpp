#pragma once
/// \file patch.hpp
/// Adaptive polygonization of a triangular patch of an implicit surface (Ihm & Naylor 1990,
/// sec. 5.2, Fig. 1 and Fig. 9): the part of f = 0 bounded by three clipping planes, with the
/// corners P0, P1, P2 where the planes meet on the surface.
///
/// Method (sec. 5.2): each boundary curve, f = 0 on plane h_i from P_i to P_i+1, is traced into a
/// digitized curve and linearized with 2^d segments (curves::linearize, the paper's LA of order
/// 2^d); the centre vertex Q_i of that LA splits the curve. The triangle is refined into four by
/// Q0, Q1, Q2; each new edge Q_i Q_j is traced on the plane through Q_i, Q_j and the average of
/// the normals of its two triangles, and linearized with 2^(d-1) segments; and so on, level by
/// level, to depth d: 4^d triangles. A curve is traced once and its two sub-curves are shared by
/// the triangles on both sides, so neighbouring triangles share their edge vertices exactly.
///
///   PatchResult r = patch(f, {.corners = {P0, P1, P2}, .depth = 3});
///   // r.mesh: 64 triangles; r.boundary[i]: the vertices on the curve from P_i to P_i+1

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "curves/linearize.hpp"
#include "implicit/expression.hpp"
#include "mesh/polygon_mesh.hpp"

namespace sculpt::implicit {

/// The plane normal . p = offset (normal need not be a unit vector).
struct PatchPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
};

struct PatchOptions {
  std::array<Eigen::Vector3d, 3> corners{};  ///< P0, P1, P2, on the surface f = 0
  int depth = 3;                             ///< d in 0..8: 4^d triangles
  /// planes[i] clips the boundary from P_i to P_(i+1 mod 3) and must hold both. Default: the
  /// plane through the two corners that contains the mean of the unit normals grad f / |grad f|
  /// at them (for corners on the coordinate axes of a surface symmetric in the coordinate
  /// planes, such as the sphere or Fig. 9's quartic, these are the coordinate planes).
  std::optional<std::array<PatchPlane, 3>> planes = std::nullopt;
  /// Chord height of the traced curves (absolute); 0: 1e-3 times each curve's end-to-end distance.
  double tolerance = 0.0;
  /// A curve linearized with m segments is traced with at least this many points per segment
  /// (its step is at most the end-to-end distance / (points_per_segment m)).
  int points_per_segment = 4;
  /// How the LA of order 2^k is computed. Default: the exact minimum-error LA. The paper's ITER
  /// heuristic (Alg. 4.4) also works, but its local minima place some centres far from where
  /// the optimum does at d >= 4 (uneven triangles; docs/implicit.md).
  curves::Method method = curves::Method::Optimal;
  /// A corner off the surface by |f| / |grad f| up to this times the corners' box diagonal is
  /// moved onto it by Newton (on its two planes when planes are given); further off is an error.
  double corner_tolerance = 1e-6;
  long max_steps = 2'000'000;  ///< marching steps over all traced curves
};

struct PatchResult {
  /// 4^depth triangles; vertices on f = 0 (|f| / |grad f| <= 1e-12 times the corners' box
  /// diagonal); faces counter-clockwise seen from the side grad f points to (out of f <= 0).
  PolygonMesh mesh;
  /// Vertex indices along boundary i, from corner i to corner i+1 (both included); corner i is
  /// vertex i. Every one of these vertices lies on planes[i] (exactly, for a coordinate plane).
  std::array<std::vector<int>, 3> boundary;
  std::array<PatchPlane, 3> planes;  ///< the clipping planes used (unit normals)
  bool flipped = false;  ///< faces run P0, P2, P1 (the corners' order disagreed with grad f)
  int traced_curves = 0;  ///< curves traced (boundaries, new edges, re-traced short pieces)
  long steps = 0;         ///< marching steps used
};

/// The adaptive polygonization of the patch of f = 0 with the given corners (sec. 5.2).
/// A boundary curve, shared with a neighbouring patch of the same f, depth and options (the same
/// two corners and plane), gets the same vertices bit for bit: it is traced from its
/// lexicographically smaller corner.
/// \throw InvalidInput for depth outside 0..8, non-finite or coincident corners, a corner off the
///        surface by more than corner_tolerance (the message names it and its residual), a
///        plane with a zero or non-finite normal or not through its two corners, a negative or
///        non-finite tolerance, points_per_segment < 2, max_steps <= 0.
/// \throw GeometryError when a curve does not connect its two end points (it leaves the box of
///        the corners grown by its diagonal, closes on itself, meets a singular point of f = 0
///        on its plane, or the step budget runs out), or no default plane can be chosen.
/// \throw NonFiniteValue if f or its gradient is not finite at a point the tracer visits.
[[nodiscard]] PatchResult patch(const Expression& f, const PatchOptions& options);

}  // namespace sculpt::implicit
