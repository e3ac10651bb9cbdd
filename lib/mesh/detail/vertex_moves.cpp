#include "mesh/detail/vertex_moves.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "base/cancel.hpp"
#include "mesh/detail/crossing_search.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector3d;

/// Crossings are worked on by moving corners (each try a local search) only while they are local:
/// at most this many pairs, or one pair per this many triangles. Wider crossings (a snap that
/// folded much of the mesh) are left to what comes after (a transform's shifted snaps and plane
/// route), not searched at length.
constexpr size_t kMaxNudgedPairs = 64;
constexpr size_t kTrianglesPerNudgedPair = 16;

/// With v where it is now, v's triangles (in incident order) keep positive areas and the
/// orientations `normals` they had (a zero normal: any).
bool keeps_shape(const CleanMesh& mesh, int v, const std::vector<Vector3d>& normals) {
  const std::vector<int>& around = mesh.incident[size_t(v)];
  for (size_t i = 0; i < around.size(); ++i) {
    const Tri& q = mesh.tris[size_t(around[i])];
    if (collinear(mesh.p[size_t(q[0])], mesh.p[size_t(q[1])], mesh.p[size_t(q[2])]) ||
        !(normals[i].squaredNorm() == 0 || normals[i].dot(mesh.normal(q)) > 0))
      return false;
  }
  return true;
}

/// Moves v along +-`direction` by the smallest step (delta / 8, doubling up to `delta`)
/// after which its triangles meet fewer others, keep their orientation and do not degenerate.
bool nudge(CleanMesh& mesh, int v, const Vector3d& direction, double delta) {
  const std::vector<int>& incident = mesh.incident[size_t(v)];
  std::vector<Tri> around;
  for (int t : incident) around.push_back(mesh.tris[size_t(t)]);
  const int before = meetings(mesh, around, incident);
  if (before == 0) return false;
  std::vector<Vector3d> normals;
  for (int t : incident) normals.push_back(mesh.normal(mesh.tris[size_t(t)]));
  const Vector3d old = mesh.p[size_t(v)];
  for (double step = std::max(mesh.resolution, delta / 8); step <= delta; step *= 2)
    for (const double sign : {1.0, -1.0}) {
      const Vector3d target = mesh.round(Vector3d(old + sign * step * direction));
      if (target == old || mesh.spread(v, v, target) > mesh.limits.max_feature) continue;
      mesh.p[size_t(v)] = target;  // tried, then put back
      const bool ok = keeps_shape(mesh, v, normals) && meetings(mesh, around, incident, before) < before;
      mesh.p[size_t(v)] = old;
      if (ok) {
        mesh.move_vertex(v, target);
        return true;
      }
    }
  return false;
}

/// A move of a vertex and how many pairs its triangles then meet in.
struct Step {
  int meetings = 0;
  std::optional<Vector3d> target;
};

/// Tries moves of v along the unit vector `direction` (`moved`: v's triangles), from the
/// resolution doubling up to `delta`, stopping at the first whose triangles meet nothing; keeps
/// in `best` the one whose triangles meet fewest pairs: fewer than best's, or as many when best
/// has no move yet (a copy of a point is moved off it even when that meets as much).
void separate_along(CleanMesh& mesh, int v, const Vector3d& direction, double delta, const std::vector<Tri>& moved,
                    Step& best) {
  const std::vector<int>& incident = mesh.incident[size_t(v)];
  const Vector3d old = mesh.p[size_t(v)];
  for (double step = mesh.resolution; step <= delta; step *= 2) {
    const Vector3d target = mesh.round(Vector3d(old + step * direction));
    if (target == old) continue;
    if (mesh.spread(v, v, target) > mesh.limits.max_feature) break;
    std::vector<Vector3d> before;
    for (int t : incident) before.push_back(mesh.normal(mesh.tris[size_t(t)]));
    mesh.p[size_t(v)] = target;  // tried, then put back
    const int count = keeps_shape(mesh, v, before) ? meetings(mesh, moved, incident, best.meetings + 1) : -1;
    mesh.p[size_t(v)] = old;
    if (count >= 0 && (count < best.meetings || (count == best.meetings && !best.target))) best = {count, target};
    if (best.target && best.meetings == 0) return;
  }
}

}  // namespace

bool nudge_crossings(CleanMesh& mesh, double delta, OutputRoundingReport& report) {
  const std::vector<std::pair<int, int>> pairs = crossings(mesh);
  if (pairs.size() > std::max(kMaxNudgedPairs, mesh.live_triangles() / kTrianglesPerNudgedPair)) return false;
  bool changed = false;
  for (const auto& [t, u] : pairs) {
    check_cancel();  // Ctrl-C (base/cancel.hpp): each nudge runs exact meeting tests, milliseconds
    for (const auto& [mine, other] : {std::pair{t, u}, std::pair{u, t}}) {
      if (!mesh.alive[size_t(mine)] || !mesh.alive[size_t(other)]) continue;
      const Vector3d n = mesh.normal(mesh.tris[size_t(other)]);
      if (!(n.squaredNorm() > 0)) continue;
      bool moved = false;
      for (int v : mesh.tris[size_t(mine)])
        if (!moved && nudge(mesh, v, n.normalized(), delta)) moved = true;
      if (moved) {
        ++report.nudged_vertices;
        changed = true;
        break;
      }
    }
  }
  return changed;
}

bool separate(CleanMesh& mesh, int v, double delta) {
  const std::vector<int>& incident = mesh.incident[size_t(v)];
  std::vector<Tri> moved;
  for (int t : incident) moved.push_back(mesh.tris[size_t(t)]);
  Step best{meetings(mesh, moved, incident), std::nullopt};  // to beat
  Vector3d n = Vector3d::Zero();
  for (int t : incident) {
    const Vector3d m = mesh.normal(mesh.tris[size_t(t)]);
    if (m.squaredNorm() > 0) n += m.normalized();
  }
  if (n.squaredNorm() > 0) separate_along(mesh, v, -n.normalized(), delta, moved, best);
  // The tip of a thin spike (slivers of solids that touch at a point, meeting at an apex) has a
  // mean normal out of its sides; toward the middle of its neighbours it goes into the spike.
  if (const std::set<int> around = mesh.neighbours(v); (!best.target || best.meetings > 0) && !around.empty()) {
    Vector3d middle = Vector3d::Zero();
    for (int w : around) middle += mesh.p[size_t(w)];
    const Vector3d inward = middle / double(around.size()) - mesh.p[size_t(v)];
    if (inward.squaredNorm() > 0) separate_along(mesh, v, inward.normalized(), delta, moved, best);
  }
  if (!best.target) return false;
  mesh.move_vertex(v, *best.target);
  return true;
}

}  // namespace sculpt::mesh::detail
