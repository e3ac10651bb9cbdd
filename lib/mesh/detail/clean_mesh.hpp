#pragma once
/// \file clean_mesh.hpp
/// The triangle mesh that round_for_output cleans (mesh/output_rounding.hpp), and what its steps
/// share: the rounding to the output's numbers, the triangles with their incidences, boxes
/// (indexed in a BoxHash) and prepared forms for the exact tests, and the edits that keep those in
/// step. The steps themselves: topology_edits.hpp (contractions and flips, a snap-rounding step in
/// the manner of Fortune's vertex rounding), vertex_moves.hpp, crossing_search.hpp.

#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "mesh/detail/box_hash.hpp"
#include "mesh/detail/triangle_pairs.hpp"
#include "mesh/formats/mesh_formats.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/polygon_mesh.hpp"
#include "mesh/predicates.hpp"

namespace sculpt::mesh::detail {

using Tri = std::array<int, 3>;

/// Rounds coordinates to the numbers of the output.
struct Rounder {
  OutputPrecision precision = OutputPrecision::Double;
  double step = 0;
  explicit Rounder(const OutputRoundingOptions& o) : precision(o.precision), step(o.grid_step) {
    if (precision == OutputPrecision::Grid && !(step > 0))
      throw InvalidInput("round_for_output: grid_step must be positive");
  }
  double operator()(double x) const {
    switch (precision) {
      case OutputPrecision::Float32: {
        // volatile: GCC 12's loop vectorizer at -O3 drops a float round trip inside a loop
        // (seen in output_problem's rounding loop), leaving the double unrounded.
        const volatile float f = static_cast<float>(x);
        return static_cast<double>(f);
      }
      case OutputPrecision::Grid:
        return std::nearbyint(x / step) * step;
      case OutputPrecision::ThreeMf: {
        // lib3mf truncates, so what it keeps of a kept value can be a micrometre less: follow it
        // down to a value it keeps unchanged (a few steps at most in practice).
        double v = lib3mf_kept(x);
        for (int i = 0; i < 32; ++i) {
          const double w = lib3mf_kept(v);
          if (w == v) break;
          v = w;
        }
        return v;
      }
      case OutputPrecision::Double:
        break;
    }
    return x;
  }
  Eigen::Vector3d operator()(const Eigen::Vector3d& v) const {
    Eigen::Vector3d out;
    for (int k = 0; k < 3; ++k) out[k] = (*this)(v[k]);
    return out;
  }
  /// The smallest distance rounding can tell apart near the largest coordinate of `points`.
  [[nodiscard]] double resolution(const std::vector<Eigen::Vector3d>& points) const;
};

/// Exact: a, b, c on one line (all three coordinate projections have zero orientation).
/// (Inline: the checks call it for every triangle they meet.)
inline bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (orient2d({a[u], a[v]}, {b[u], b[v]}, {c[u], c[v]}) != 0) return false;
  }
  return true;
}

/// What limits the cleaning.
struct CleanLimits {
  double max_feature = 0;    ///< farthest an input point may end from the vertex standing for it
  bool keep_copies = false;  ///< OutputRoundingOptions::keep_copies
};

/// The triangle mesh being cleaned: positions always representable in the target precision,
/// per vertex the input points it stands for (to bound how far anything moves). The fields are
/// read freely; they change only through the member functions (which keep incidences, boxes, the
/// index and the prepared triangles in step), except that a check may move a vertex in `p` and
/// put it back before anything else reads it.
struct CleanMesh {
  /// `mesh`'s faces as n - 2 triangles each, at the rounded positions.
  CleanMesh(const PolygonMesh& mesh, const Rounder& round, CleanLimits limits);

  Rounder round;
  double resolution;
  CleanLimits limits;
  std::vector<Eigen::Vector3d> p;
  std::vector<std::vector<Eigen::Vector3d>> members;  ///< per vertex, the input points it stands for
  std::vector<Tri> tris;
  std::vector<bool> alive;
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<PreparedTriangle> prepared;  ///< per triangle, at the positions of its box
  std::vector<std::vector<int>> incident;  ///< per vertex, its live triangles
  BoxHash index;                           ///< the live triangles under their boxes
  bool settled = false;                    ///< construction done: changes from here on make triangles dirty
  std::vector<char> dirty;                 ///< triangle added or moved since construction
  /// crossing_search's memo: the crossings among the triangles as built (crossings()).
  std::optional<std::vector<std::pair<int, int>>> first_crossings;

  void add_triangle(const Tri& t);
  void kill_triangle(int t);
  /// Triangle t with the corners `after` (its box and prepared form renewed).
  void rewrite_triangle(int t, const Tri& after);
  /// Renews t's box, index entry and prepared form from the current positions.
  void update_box(int t);
  /// Vertex v to `target`, its triangles' boxes renewed.
  void move_vertex(int v, const Eigen::Vector3d& target);
  /// Vertex v merged into `target`: v's input points are target's, v has no triangle left.
  void merge_vertex(int v, int target);

  [[nodiscard]] bool vertex_alive(int v) const { return !incident[size_t(v)].empty(); }
  [[nodiscard]] Eigen::Vector3d normal(const Tri& t) const { return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]); }
  [[nodiscard]] std::set<int> neighbours(int v) const;
  /// Farthest input point of u's and v's members from `target`.
  [[nodiscard]] double spread(int u, int v, const Eigen::Vector3d& target) const;
  /// A triangle whose shape says nothing about its orientation: its height is below `delta`.
  [[nodiscard]] bool sliver(const Tri& t, double delta) const;
  [[nodiscard]] size_t live_triangles() const;
  /// The live triangles; the vertices they use in the order of the input (indexed formats keep it).
  [[nodiscard]] PolygonMesh mesh() const;
  /// Farthest an input vertex is from the vertex standing for it.
  [[nodiscard]] double max_move() const;
};

}  // namespace sculpt::mesh::detail
