#include "mesh/output_rounding.hpp"
#include "base/cancel.hpp"
#include "base/dispose.hpp"
#include "base/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "mesh/detail/clean_mesh.hpp"
#include "mesh/detail/crossing_search.hpp"
#include "mesh/detail/point_copies.hpp"
#include "mesh/detail/topology_edits.hpp"
#include "mesh/detail/vertex_moves.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"
#include "mesh/shell_orientation.hpp"

namespace sculpt {
namespace {

using Eigen::Vector3d;
using mesh::detail::Rounder;

/// Budget of the self-intersection search (candidate pairs): enough for any mesh whose faces are
/// not long fans (thousands of corners in one face); beyond it the check gives up
/// (OutputCheck::Unchecked).
constexpr size_t kCandidatesPerCorner = 16;
constexpr size_t kMinCandidates = 500'000;
/// Faces with more corners are not triangulated for the search (ear clipping is quadratic).
constexpr size_t kMaxJudgedCorners = 2048;
constexpr const char* kUnchecked = "self-intersections not checked: the search exceeded its budget";

/// A mesh's verdict: clean, a problem (the first found), or too costly to judge.
enum class OutputCheck { Clean, Problem, Unchecked };

struct OutputVerdict {
  OutputCheck check = OutputCheck::Clean;
  std::string problem;  ///< empty when clean

  static OutputVerdict problem_found(std::string message) { return {OutputCheck::Problem, std::move(message)}; }
  static OutputVerdict unchecked() { return {OutputCheck::Unchecked, kUnchecked}; }
};

size_t corner_count(const PolygonMesh& mesh) {
  size_t n = 0;
  for (const auto& f : mesh.faces) n += f.size();
  return n;
}

/// A shell that local operations turned inside out (it faces against its nesting), or "".
std::string inverted_shell(const PolygonMesh& mesh) {
  const std::vector<ShellOrientation> shells = shell_orientations(mesh);
  for (size_t s = 0; s < shells.size(); ++s)
    if (!shells[s].consistent())
      return "shell " + std::to_string(s) + " faces against its nesting (signed volume " +
             std::to_string(shells[s].signed_volume) + ")";
  return {};
}

/// What a caller of judge already knows of the mesh.
struct Known {
  /// Every vertex rounds to itself (doubles; or a mesh already in the precision, as a transform's
  /// boundary snapped to the grid): the rounded mesh is the mesh, not copied.
  bool rounding_moves_nothing = false;
  /// The caller found no defect at all in the mesh with the same topology check, and rounding
  /// moves no vertex, so it is not repeated.
  bool topology_clean = false;
  /// The mesh is the cleaner's mesh, all triangles, with coordinates already in the precision,
  /// and the cleaner's own exact search (mesh::detail::crossings, every pair of live,
  /// non-degenerate triangles, corners told apart by index) found no two that meet beyond what
  /// they share; the search here (corners at one point counted as one, so it allows more) would
  /// find none either, and is not repeated.
  bool crossings_searched = false;
};

/// output_problem's verdict. `options.exact_vertices` (if one per vertex) marks vertices whose
/// pairs of all-marked faces need no self-intersection test; a vertex the rounding moves loses
/// its mark.
OutputVerdict judge(const PolygonMesh& mesh, const OutputRoundingOptions& options, Known known = {}) {
  const Rounder round(options);
  PolygonMesh copy;
  const bool moves = options.precision != OutputPrecision::Double && !known.rounding_moves_nothing;
  if (moves) {
    copy = mesh;
    for (Vector3d& v : copy.vertices) v = round(v);
  }
  const PolygonMesh& rounded = moves ? copy : mesh;
  std::vector<char> used(rounded.vertices.size(), 0);
  for (const auto& f : rounded.faces)
    for (int v : f)
      if (v >= 0 && static_cast<size_t>(v) < used.size()) used[size_t(v)] = 1;
  if (!options.keep_copies) {
    // Two used vertices at one point: of all such pairs, the one whose later vertex comes first
    // (with the first vertex at that point), as a scan in index order finds it.
    const std::vector<int> copy_of = mesh::detail::first_copies(rounded.vertices, used);
    int first = -1, second = -1;
    for (size_t v = 0; v < copy_of.size() && second < 0; ++v)
      if (copy_of[v] != int(v)) first = copy_of[v], second = int(v);
    if (second >= 0)
      return OutputVerdict::problem_found("vertices " + std::to_string(first) + " and " + std::to_string(second) +
                                          " are at the same point");
  }
  if (!known.topology_clean) {
    const ValidationReport report =
        check_closed_manifold(rounded, {.check_self_intersections = false, .check_face_shapes = false,
                                        .check_shell_orientation = false, .max_defects_per_kind = 1});
    if (!report.ok()) return OutputVerdict::problem_found(report.defects.front().message);
  }
  if (known.crossings_searched) return {};
  for (const auto& f : rounded.faces)
    if (f.size() > kMaxJudgedCorners) return OutputVerdict::unchecked();
  std::vector<char> exact;  // the marks of vertices that the rounding leaves where they are
  if (options.exact_vertices.size() == mesh.vertices.size() && !mesh.vertices.empty()) {
    exact.assign(options.exact_vertices.begin(), options.exact_vertices.end());
    if (&rounded != &mesh)
      for (size_t v = 0; v < exact.size(); ++v)
        if (rounded.vertices[v] != mesh.vertices[v]) exact[v] = 0;
  }
  const SelfIntersectionSearch search = search_self_intersections(
      rounded, {.max_pairs = 1, .max_candidates = kCandidatesPerCorner * corner_count(rounded) + kMinCandidates,
                .exact_vertices = exact, .distinct_vertices = !options.keep_copies});
  if (!search.pairs.empty()) {
    const FacePair& p = search.pairs.front();
    return OutputVerdict::problem_found("faces " + std::to_string(p.face_a) + " and " + std::to_string(p.face_b) +
                                        " intersect");
  }
  if (!search.complete) return OutputVerdict::unchecked();
  return {};
}

/// The sweeps of round_for_output on its cleaner, at growing feature sizes from `smallest` to
/// `max_feature`, until the mesh is clean or max_feature is reached; the result mesh.
PolygonMesh sweep_until_clean(mesh::detail::CleanMesh& cleaner, const OutputRoundingOptions& options, double smallest,
                              double max_feature, OutputRoundingReport& r) {
  PolygonMesh result = cleaner.mesh();
  if (options.triangles && output_problem(result, options).empty()) {
    r.changed = false;
    return result;
  }
  const double growth = options.precision == OutputPrecision::Grid ? 2 : 16;
  // The mesh is judged again only after a sweep changed it (an unchanged mesh keeps its problem):
  // first by the cleaner's own crossings (only what changed is searched again), and only when no
  // triangles cross by the rest of the verdict (that search is not repeated), and at the end.
  bool judged = false, full = false;
  for (double delta = smallest;; delta = std::min(growth * delta, max_feature)) {
    bool changed = false;
    // Contractions and flips until nothing changes (at most 20 passes), then corner moves; again
    // while corner moves made a difference (at most 4 times).
    for (int alternation = 0; alternation < 4; ++alternation) {
      check_cancel();  // Ctrl-C (base/cancel.hpp): a sweep over a large mesh takes a while
      for (int pass = 0; pass < 20 && mesh::detail::sweep(cleaner, delta, r); ++pass) changed = true;
      if (!mesh::detail::nudge_crossings(cleaner, delta, r)) break;
      changed = true;
    }
    r.feature = delta;
    if (changed || !judged) {
      judged = true;
      full = mesh::detail::crossings(cleaner).empty();
      if (full) {
        result = cleaner.mesh();
        r.problem = judge(result, options, {.crossings_searched = true}).problem;
        if (r.problem.empty()) r.problem = inverted_shell(result);
      }
    }
    if ((full && r.problem.empty()) || delta >= max_feature) break;
  }
  if (!full) {
    result = cleaner.mesh();
    r.problem = output_problem(result, options);
    if (r.problem.empty()) r.problem = inverted_shell(result);
  }
  r.clean = r.problem.empty();
  r.max_move = cleaner.max_move();
  return result;
}

}  // namespace

std::string output_problem(const PolygonMesh& mesh, const OutputRoundingOptions& options) {
  return judge(mesh, options).problem;
}

PolygonMesh round_for_output(const PolygonMesh& mesh, const OutputRoundingOptions& given,
                             OutputRoundingReport* report) {
  return round_for_output(PolygonMesh(mesh), given, report);
}

PolygonMesh round_for_output(PolygonMesh&& mesh, const OutputRoundingOptions& given,
                             OutputRoundingReport* report) {
  // The exact-vertex marks hold for `mesh` only: its first judgement; repaired meshes are judged in full.
  OutputRoundingOptions options = given;
  options.exact_vertices = {};
  OutputRoundingReport local;
  OutputRoundingReport& r = report != nullptr ? *report : local;
  r = {};
  if (mesh.faces.empty()) return std::move(mesh);
  const Rounder round(options);
  // Where rounding moves no vertex (doubles, or a transform's boundary already snapped to the
  // grid), the topology check below is the rounded mesh's: judge neither copies the mesh nor
  // checks again, and it runs beside the check (it needs only readable indices and coordinates);
  // its verdict counts only if the check finds nothing. With exact-vertex marks (to_mesh's
  // output) too, since the marked search prepares only the faces near moved ones: side by side
  // they once raised the real-mesh jobs' peak by 4-10 MB, now by at most 1.4 MB
  // (docs/benchmarks.md, "Session 41").
  const bool moves_nothing =
      options.precision == OutputPrecision::Double ||
      std::all_of(mesh.vertices.begin(), mesh.vertices.end(), [&](const Vector3d& v) { return round(v) == v; });
  ValidationReport topology;
  const auto check_topology = [&] {
    topology = check_closed_manifold(mesh, {.check_self_intersections = false,
                                            .check_face_shapes = false,
                                            .check_shell_orientation = false,
                                            .max_defects_per_kind = 1});
  };
  std::optional<OutputVerdict> beside;
  std::exception_ptr beside_error;
  if (moves_nothing && !options.triangles && indices_and_coordinates_valid(mesh))
    beside_error = parallel_invoke_holding_second(
        check_topology, [&] { beside = judge(mesh, given, {.rounding_moves_nothing = true, .topology_clean = true}); });
  else
    check_topology();
  // Only closed, oriented 2-manifolds are rounded: anything else (an open patch) is left as it is.
  for (const Defect& d : topology.defects) {
    if (d.kind == DefectKind::DegenerateFace || d.kind == DefectKind::NonPlanarFace ||
        d.kind == DefectKind::SelfCrossingFace)
      continue;
    r.clean = false;
    r.problem = d.message;
    return std::move(mesh);
  }
  const bool topology_clean = topology.defects.empty() && moves_nothing;
  if (topology_clean && beside_error) std::rethrow_exception(beside_error);
  const OutputVerdict first =
      options.triangles ? OutputVerdict::problem_found("triangles asked for")
      : topology_clean && beside
          ? *beside
          : judge(mesh, given, {.rounding_moves_nothing = moves_nothing, .topology_clean = topology_clean});
  if (first.check == OutputCheck::Unchecked) {  // too costly to judge: written as it is, and said so
    r.clean = false;
    r.problem = first.problem;
    return std::move(mesh);
  }
  if (first.check == OutputCheck::Clean) {
    if (moves_nothing) return std::move(mesh);
    PolygonMesh rounded = std::move(mesh);
    for (Vector3d& v : rounded.vertices) v = round(v);
    return rounded;
  }
  r.changed = true;
  // Grid points: edges shorter than one step have length zero; otherwise 4 units in the last place.
  const double resolution = round.resolution(mesh.vertices);
  const double smallest = options.precision == OutputPrecision::Grid ? resolution / 2 : 4 * resolution;
  double max_feature = options.max_feature;
  if (max_feature <= 0) {
    Eigen::AlignedBox3d box;
    for (const Vector3d& v : mesh.vertices) box.extend(v);
    max_feature = std::ldexp(box.sizes().maxCoeff(), -20);
  }
  max_feature = std::max(max_feature, options.precision == OutputPrecision::Grid ? smallest : 256 * resolution);

  // The cleaner holds millions of small blocks on large meshes: stopped by Ctrl-C, it is freed
  // on another thread (base/dispose.hpp) so that the stop answers at once.
  auto cleaner = std::make_unique<mesh::detail::CleanMesh>(
      mesh, round, mesh::detail::CleanLimits{.max_feature = max_feature, .keep_copies = options.keep_copies});
  try {
    return sweep_until_clean(*cleaner, options, smallest, max_feature, r);
  } catch (const Cancelled&) {
    // The given mesh too (the caller's, moved in): millions of face vectors.
    dispose_in_background(std::make_pair(std::move(cleaner), std::move(mesh)));
    throw;
  }
}

}  // namespace sculpt
