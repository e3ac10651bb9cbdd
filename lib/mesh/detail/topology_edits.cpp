#include "mesh/detail/topology_edits.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <vector>

#include "mesh/detail/crossing_search.hpp"
#include "mesh/detail/vertex_moves.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector3d;

/// What contracting a cluster into one of its vertices does to the triangles round it: those
/// with two or more corners in the cluster disappear, the others are rewritten.
struct Contraction {
  std::vector<int> removed, changed;
  std::vector<Tri> afters;  ///< per changed triangle, its corners afterwards
};

Contraction contraction(const CleanMesh& mesh, const std::set<int>& in, int target) {
  std::set<int> region;
  for (int v : in) region.insert(mesh.incident[size_t(v)].begin(), mesh.incident[size_t(v)].end());
  Contraction c;
  for (int t : region) {
    int count = 0;
    for (int w : mesh.tris[size_t(t)]) count += in.count(w) != 0 ? 1 : 0;
    if (count >= 2) {
      c.removed.push_back(t);
      continue;
    }
    Tri after = mesh.tris[size_t(t)];
    for (int& w : after)
      if (in.count(w) != 0) w = target;
    c.changed.push_back(t);
    c.afters.push_back(after);
  }
  return c;
}

/// The rewritten triangles form one fan round `target`: each edge target->w once and w->target
/// once, and the rim a single cycle.
bool rewrite_is_one_fan(const std::vector<Tri>& afters, int target) {
  std::map<int, int> next;  // rim: w1 -> w2 for each rewritten triangle (target, w1, w2)
  for (const Tri& a : afters) {
    int k = 0;
    while (a[k] != target) ++k;
    const int w1 = a[(k + 1) % 3], w2 = a[(k + 2) % 3];
    if (!next.insert({w1, w2}).second) return false;
  }
  int steps = 0;
  for (int w = next.begin()->first; steps == 0 || w != next.begin()->first; ++steps) {
    const auto it = next.find(w);
    if (it == next.end() || steps > static_cast<int>(next.size())) return false;
    w = it->second;
  }
  return steps == static_cast<int>(next.size());
}

/// Contracts the vertices of `cluster` (joined by edges shorter than delta) into its member
/// `target`: triangles with two or more corners in the cluster disappear, the others are
/// rewritten. Done only if the mesh stays a closed 2-manifold (the rewritten triangles form one
/// fan around target), no triangle degenerates, no triangle larger than delta turns over, no
/// two triangles come to meet, and nothing moves farther than max_feature. A cluster that is a
/// whole shell (nothing outside it) disappears.
bool collapse(CleanMesh& mesh, const std::vector<int>& cluster, int target, double delta) {
  const std::set<int> in(cluster.begin(), cluster.end());
  const Contraction c = contraction(mesh, in, target);
  double reach = 0;
  for (int v : cluster)
    for (const Vector3d& q : mesh.members[size_t(v)]) reach = std::max(reach, (q - mesh.p[size_t(target)]).norm());
  if (reach > mesh.limits.max_feature) return false;
  if (c.changed.empty()) {  // a closed shell smaller than delta
    for (int t : c.removed)
      for (int w : mesh.tris[size_t(t)])
        if (in.count(w) == 0) return false;
    for (int t : c.removed) mesh.kill_triangle(t);
    return true;
  }
  if (!rewrite_is_one_fan(c.afters, target)) return false;
  for (size_t i = 0; i < c.changed.size(); ++i) {
    // A triangle that was a sliver may become degenerate (a later flip removes it); others
    // must keep a positive area and their orientation.
    const Tri& a = c.afters[i];
    const Tri& before = mesh.tris[size_t(c.changed[i])];
    if (mesh.sliver(before, delta)) continue;
    if (collinear(mesh.p[size_t(a[0])], mesh.p[size_t(a[1])], mesh.p[size_t(a[2])])) return false;
    if (mesh.normal(before).dot(mesh.normal(a)) <= 0) return false;
  }
  std::vector<int> replaced = c.changed;
  replaced.insert(replaced.end(), c.removed.begin(), c.removed.end());
  if (adds_meetings(mesh, c.afters, replaced)) return false;
  for (int t : c.removed) mesh.kill_triangle(t);
  for (size_t i = 0; i < c.changed.size(); ++i) mesh.rewrite_triangle(c.changed[i], c.afters[i]);
  for (int v : cluster)
    if (v != target) mesh.merge_vertex(v, target);
  return true;
}

/// Collapses the cluster into the member that works, nearest the cluster's centre first; failing
/// that, its edges one at a time.
bool collapse_cluster(CleanMesh& mesh, const std::vector<int>& cluster, double delta, OutputRoundingReport& report) {
  Vector3d centre = Vector3d::Zero();
  for (int v : cluster) centre += mesh.p[size_t(v)];
  centre /= static_cast<double>(cluster.size());
  std::vector<int> order = cluster;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return (mesh.p[size_t(a)] - centre).norm() < (mesh.p[size_t(b)] - centre).norm(); });
  for (int target : order)
    if (collapse(mesh, cluster, target, delta)) {
      report.collapsed_edges += static_cast<int>(cluster.size()) - 1;
      return true;
    }
  bool any = false;
  for (size_t i = 0; i < cluster.size(); ++i)
    for (size_t j = 0; j < cluster.size(); ++j) {
      const int u = cluster[i], v = cluster[j];
      if (u == v || !mesh.vertex_alive(u) || !mesh.vertex_alive(v) ||
          (mesh.p[size_t(u)] - mesh.p[size_t(v)]).norm() >= delta)
        continue;
      if (mesh.neighbours(u).count(v) == 0) continue;
      if (collapse(mesh, {u, v}, v, delta)) {
        ++report.collapsed_edges;
        any = true;
      }
    }
  return any;
}

/// Flips the edge starting at corner k of triangle t (a sliver whose third corner lies close
/// to that edge) if the two new triangles keep the orientation and the edge is new.
bool flip(CleanMesh& mesh, int t, int k) {
  const Tri tri = mesh.tris[size_t(t)];
  const int a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
  int other = -1, d = -1;
  for (int s : mesh.incident[size_t(b)]) {
    if (s == t) continue;
    const Tri& q = mesh.tris[size_t(s)];
    for (int j = 0; j < 3; ++j)
      if (q[j] == b && q[(j + 1) % 3] == a) other = s, d = q[(j + 2) % 3];
  }
  if (other < 0 || d == c) return false;
  if (mesh.neighbours(c).count(d) != 0) return false;
  const Tri first = {a, d, c}, second = {d, b, c};
  const std::vector<Vector3d>& p = mesh.p;
  if (collinear(p[size_t(a)], p[size_t(d)], p[size_t(c)]) || collinear(p[size_t(d)], p[size_t(b)], p[size_t(c)]))
    return false;
  // c lies close to edge ab, so both new triangles face as the neighbour (b, a, d) does.
  const Vector3d reference = mesh.normal(mesh.tris[size_t(other)]);
  if (mesh.normal(first).dot(reference) <= 0 || mesh.normal(second).dot(reference) <= 0) return false;
  if (adds_meetings(mesh, {first, second}, {t, other})) return false;
  mesh.kill_triangle(t);
  mesh.kill_triangle(other);
  mesh.add_triangle(first);
  mesh.add_triangle(second);
  return true;
}

/// Copies of one point that no edge joins: each but the first moved into its own sheet.
bool separate_copies(CleanMesh& mesh, double delta, OutputRoundingReport& report) {
  if (mesh.limits.keep_copies) return false;
  bool changed = false;
  // The live vertices by position, then index: each run of equal positions is one point's copies
  // (sorted once instead of a map of every vertex, which took seconds on millions).
  std::vector<std::pair<std::array<double, 3>, int>> at;
  at.reserve(mesh.p.size());
  for (size_t v = 0; v < mesh.p.size(); ++v)
    if (mesh.vertex_alive(static_cast<int>(v))) at.push_back({{mesh.p[v].x(), mesh.p[v].y(), mesh.p[v].z()}, int(v)});
  std::sort(at.begin(), at.end());
  CancelPoll poll;
  std::vector<int> copies;
  for (size_t run = 0, next = 0; run < at.size(); run = next) {
    poll.tick();  // Ctrl-C (base/cancel.hpp)
    for (next = run + 1; next < at.size() && at[next].first == at[run].first;) ++next;
    if (next - run < 2) continue;
    copies.clear();
    for (size_t k = run; k < next; ++k) copies.push_back(at[k].second);
    for (size_t i = 1; i < copies.size(); ++i) {
      const std::set<int> n = mesh.neighbours(copies[i]);
      if (std::any_of(copies.begin(), copies.end(), [&](int c) { return n.count(c) != 0; }))
        continue;  // a zero-length edge
      // Ctrl-C (base/cancel.hpp): separating runs exact meeting tests, milliseconds each.
      check_cancel();
      if (separate(mesh, copies[i], delta)) {
        ++report.separated_vertices;
        changed = true;
      }
    }
  }
  return changed;
}

/// Clusters of vertices joined by edges shorter than delta, each contracted (collapse_cluster).
bool collapse_short_edges(CleanMesh& mesh, double delta, OutputRoundingReport& report) {
  std::vector<int> parent(mesh.p.size());
  for (size_t v = 0; v < parent.size(); ++v) parent[v] = static_cast<int>(v);
  auto find = [&](int v) {
    while (parent[size_t(v)] != v) v = parent[size_t(v)] = parent[size_t(parent[size_t(v)])];
    return v;
  };
  bool short_edges = false;
  CancelPoll poll;
  for (size_t t = 0; t < mesh.tris.size(); ++t) {
    poll.tick();  // Ctrl-C (base/cancel.hpp)
    if (!mesh.alive[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.tris[t][k], b = mesh.tris[t][(k + 1) % 3];
      if ((mesh.p[size_t(a)] - mesh.p[size_t(b)]).norm() < delta) {
        parent[size_t(find(a))] = find(b);
        short_edges = true;
      }
    }
  }
  if (!short_edges) return false;
  // The clusters of two or more vertices, by root, each in vertex order: (root, vertex) pairs
  // sorted (a std::map of every vertex took seconds on millions of vertices).
  // Only vertices alive now are members (a cluster one of whose members a collapse before it
  // removes is skipped below).
  std::vector<std::pair<int, int>> member;
  for (size_t v = 0; v < parent.size(); ++v)
    if (const int r = find(static_cast<int>(v)); r != static_cast<int>(v) && mesh.vertex_alive(static_cast<int>(v)))
      member.emplace_back(r, static_cast<int>(v));
  for (size_t i = 0, joined = member.size(); i < joined; ++i)
    if (mesh.vertex_alive(member[i].first)) member.emplace_back(member[i].first, member[i].first);
  std::sort(member.begin(), member.end());
  member.erase(std::unique(member.begin(), member.end()), member.end());
  bool changed = false;
  std::vector<int> cluster;
  for (size_t i = 0, next = 0; i < member.size(); i = next) {
    check_cancel();  // Ctrl-C: a collapse runs exact meeting tests, milliseconds each
    cluster.clear();
    for (next = i; next < member.size() && member[next].first == member[i].first; ++next)
      cluster.push_back(member[next].second);
    if (cluster.size() < 2) continue;
    bool alive = true;
    for (int v : cluster) alive = alive && mesh.vertex_alive(v);
    if (alive && collapse_cluster(mesh, cluster, delta, report)) changed = true;
  }
  return changed;
}

/// Slivers without a short edge (a corner close to the opposite edge): that edge flipped.
bool flip_slivers(CleanMesh& mesh, double delta, OutputRoundingReport& report) {
  bool changed = false;
  CancelPoll poll;
  for (size_t t = 0, count = mesh.tris.size(); t < count; ++t) {
    poll.tick();  // Ctrl-C (base/cancel.hpp)
    if (!mesh.alive[t]) continue;
    const Tri& tri = mesh.tris[t];
    int longest = 0;
    double longest_length = -1;
    for (int k = 0; k < 3; ++k) {
      const double l = (mesh.p[size_t(tri[(k + 1) % 3])] - mesh.p[size_t(tri[k])]).norm();
      if (l > longest_length) longest_length = l, longest = k;
    }
    const Vector3d n = mesh.normal(tri);
    if (longest_length <= 0 || n.norm() / longest_length >= delta) continue;
    if (flip(mesh, static_cast<int>(t), longest)) {
      ++report.flipped_edges;
      changed = true;
    }
  }
  return changed;
}

}  // namespace

bool sweep(CleanMesh& mesh, double delta, OutputRoundingReport& report) {
  check_cancel();  // Ctrl-C (base/cancel.hpp)
  bool changed = separate_copies(mesh, delta, report);
  changed = collapse_short_edges(mesh, delta, report) || changed;
  changed = flip_slivers(mesh, delta, report) || changed;
  return changed;
}

}  // namespace sculpt::mesh::detail
