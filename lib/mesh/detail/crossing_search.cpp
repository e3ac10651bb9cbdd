#include "mesh/detail/crossing_search.hpp"

#include <algorithm>
#include <array>
#include <span>
#include "base/cancel.hpp"

#include "mesh/detail/box_grid.hpp"
#include "mesh/self_intersection.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector3d;

/// Appends to `out` the pairs (t, u), smaller index first, of live, non-degenerate triangles u
/// near t, not `skip`ped, that meet t beyond what they share (t itself non-degenerate).
/// The triangles as prepared (kept with the boxes: positions settle only through update_box;
/// axis < 0 marks collinear corners).
template <class Skip>
void meeting_partners(const CleanMesh& mesh, int t, Skip skip, std::vector<std::pair<int, int>>& out) {
  const PreparedTriangle& a = mesh.prepared[size_t(t)];
  if (a.axis < 0) return;
  for (int u : mesh.index.near(mesh.boxes[size_t(t)])) {
    if (u == t || skip(u) || !mesh.alive[size_t(u)] || !mesh.boxes[size_t(t)].intersects(mesh.boxes[size_t(u)]))
      continue;
    const PreparedTriangle& b = mesh.prepared[size_t(u)];
    if (b.axis >= 0 && triangles_meet(a, b)) out.push_back(std::minmax(t, u));
  }
}

/// Pairs of live, non-degenerate triangles that meet beyond what they share, all searched.
/// Candidates come from one pass over a uniform grid (box_grid.hpp, the broad phase of
/// search_self_intersections too), not from a query per triangle: every pair of overlapping
/// boxes once, so the same pairs as meeting_partners over all triangles.
std::vector<std::pair<int, int>> full_crossings(const CleanMesh& mesh) {
  std::vector<std::pair<int, int>> out;
  std::vector<int> live;
  for (size_t t = 0; t < mesh.tris.size(); ++t)
    if (mesh.alive[t] && mesh.prepared[t].axis >= 0) live.push_back(static_cast<int>(t));
  if (live.size() < 2) return out;
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(live.size());
  Eigen::AlignedBox3d all;
  for (int t : live) boxes.push_back(mesh.boxes[size_t(t)]), all.extend(mesh.boxes[size_t(t)]);
  if (!all.min().allFinite() || !all.max().allFinite() || !all.sizes().allFinite()) {
    for (int t : live)
      meeting_partners(
          mesh, t, [&](int u) { return u <= t; }, out);  // no grid: a query per triangle
  } else {
    const BoxGrid grid(boxes);
    std::vector<Eigen::AlignedBox3d> local;  // a cell's boxes, gathered
    CancelPoll poll;
    for (size_t k = 0; k < grid.cells(); ++k) {
      poll.tick();  // Ctrl-C (base/cancel.hpp)
      const std::span<const int> here = grid.cell(k);
      const std::span<const unsigned char> first = grid.first_cell_masks(k);
      local.clear();
      for (int i : here) local.push_back(boxes[size_t(i)]);
      for (size_t i = 0; i < here.size(); ++i)
        for (size_t j = i + 1; j < here.size(); ++j) {
          // Owned by this cell (BoxGrid::first_cell_masks) and overlapping.
          if ((first[i] | first[j]) != 7 || !local[i].intersects(local[j])) continue;
          const int t = live[size_t(here[i])], u = live[size_t(here[j])];
          if (triangles_meet(mesh.prepared[size_t(t)], mesh.prepared[size_t(u)])) out.push_back(std::minmax(t, u));
        }
    }
  }
  std::sort(out.begin(), out.end());  // worked on in this order
  return out;
}

}  // namespace

std::vector<std::pair<int, int>> crossings(CleanMesh& mesh) {
  if (!mesh.first_crossings) {  // all pairs of the triangles as built (the changed ones left out)
    mesh.first_crossings.emplace();
    for (const auto& [t, u] : full_crossings(mesh))
      if (mesh.dirty[size_t(t)] == 0 && mesh.dirty[size_t(u)] == 0) mesh.first_crossings->push_back({t, u});
  }
  std::vector<std::pair<int, int>> out;
  for (const auto& [t, u] : *mesh.first_crossings)
    if (mesh.alive[size_t(t)] && mesh.alive[size_t(u)] && mesh.dirty[size_t(t)] == 0 && mesh.dirty[size_t(u)] == 0)
      out.push_back({t, u});
  for (size_t t = 0; t < mesh.tris.size(); ++t)  // each pair once: a dirty partner only from the lower index
    if (mesh.alive[t] && mesh.dirty[t] != 0)
      meeting_partners(
          mesh, static_cast<int>(t), [&](int u) { return mesh.dirty[size_t(u)] != 0 && u < static_cast<int>(t); }, out);
  std::sort(out.begin(), out.end());  // worked on in this order
  return out;
}

int meetings(const CleanMesh& mesh, const std::vector<Tri>& group, const std::vector<int>& replaced, int enough) {
  const std::vector<Vector3d>& p = mesh.p;
  int count = 0;
  for (size_t i = 0; i < group.size(); ++i) {
    const Tri& a = group[i];
    const std::array<Vector3d, 3> pa = {p[a[0]], p[a[1]], p[a[2]]};
    if (collinear(pa[0], pa[1], pa[2])) continue;
    Eigen::AlignedBox3d box;
    for (const Vector3d& q : pa) box.extend(q);
    for (int t : mesh.index.near(box)) {
      if (!mesh.alive[size_t(t)] || !box.intersects(mesh.boxes[size_t(t)])) continue;
      if (std::find(replaced.begin(), replaced.end(), t) != replaced.end()) continue;
      const Tri& b = mesh.tris[size_t(t)];
      const std::array<Vector3d, 3> pb = {p[b[0]], p[b[1]], p[b[2]]};
      if (collinear(pb[0], pb[1], pb[2])) continue;  // degenerate: removed later or reported
      if (sculpt::triangles_meet(a, pa, b, pb) && ++count >= enough) return count;
    }
    for (size_t j = 0; j < i; ++j) {
      const Tri& b = group[j];
      const std::array<Vector3d, 3> pb = {p[b[0]], p[b[1]], p[b[2]]};
      if (!collinear(pb[0], pb[1], pb[2]) && sculpt::triangles_meet(a, pa, b, pb) && ++count >= enough) return count;
    }
  }
  return count;
}

bool adds_meetings(const CleanMesh& mesh, const std::vector<Tri>& added, const std::vector<int>& replaced) {
  const int after = meetings(mesh, added, replaced);
  if (after == 0) return false;
  std::vector<Tri> before;
  for (int t : replaced) before.push_back(mesh.tris[size_t(t)]);
  return after > meetings(mesh, before, replaced);
}

}  // namespace sculpt::mesh::detail
