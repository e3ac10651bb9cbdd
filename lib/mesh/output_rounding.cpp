#include "mesh/output_rounding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "base/errors.hpp"
#include "mesh/detail/box_grid.hpp"
#include "mesh/detail/point_copies.hpp"
#include "mesh/detail/triangle_pairs.hpp"
#include "mesh/formats/mesh_formats.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/predicates.hpp"
#include "mesh/self_intersection.hpp"
#include "mesh/shell_orientation.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {
namespace {

using Eigen::Vector3d;
using Tri = std::array<int, 3>;
using mesh::detail::PreparedTriangle;

/// Rounds coordinates to the numbers of the output.
struct Rounder {
  OutputPrecision precision = OutputPrecision::Double;
  double step = 0;
  explicit Rounder(const OutputRoundingOptions& o) : precision(o.precision), step(o.grid_step) {
    if (precision == OutputPrecision::Grid && !(step > 0)) throw InvalidInput("round_for_output: grid_step must be positive");
  }
  double operator()(double x) const {
    switch (precision) {
      case OutputPrecision::Float32: {
        // volatile: GCC 12's loop vectorizer at -O3 drops a float round trip inside a loop
        // (seen in output_problem's rounding loop), leaving the double unrounded.
        const volatile float f = static_cast<float>(x);
        return static_cast<double>(f);
      }
      case OutputPrecision::Grid: return std::nearbyint(x / step) * step;
      case OutputPrecision::ThreeMf: {
        // lib3mf truncates, so what it keeps of a kept value can be a micrometre less: follow it
        // down to a value it keeps unchanged (a few steps at most in practice).
        double v = mesh::detail::lib3mf_kept(x);
        for (int i = 0; i < 32; ++i) {
          const double w = mesh::detail::lib3mf_kept(v);
          if (w == v) break;
          v = w;
        }
        return v;
      }
      case OutputPrecision::Double: break;
    }
    return x;
  }
  Vector3d operator()(const Vector3d& v) const {
    Vector3d out;
    for (int k = 0; k < 3; ++k) out[k] = (*this)(v[k]);
    return out;
  }
  /// The smallest distance rounding can tell apart near the largest coordinate of `points`.
  double resolution(const std::vector<Vector3d>& points) const {
    if (precision == OutputPrecision::Grid) return step;
    double m = std::numeric_limits<double>::min();
    for (const Vector3d& p : points) m = std::max(m, p.cwiseAbs().maxCoeff());
    const int digits = precision == OutputPrecision::Double ? 53 : 24;
    const double ulp = std::ldexp(1.0, std::ilogb(m) + 1 - digits);
    return precision == OutputPrecision::ThreeMf ? std::max(ulp, 1e-6) : ulp;
  }
};

/// Exact: a, b, c on one line (all three coordinate projections have zero orientation).
bool collinear(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (orient2d({a[u], a[v]}, {b[u], b[v]}, {c[u], c[v]}) != 0) return false;
  }
  return true;
}

/// Crossings are worked on by moving corners (each try a local search) only while they are local:
/// at most this many pairs, or one pair per this many triangles. Wider crossings (a snap that
/// folded much of the mesh) are left to what comes after (a transform's shifted snaps and plane
/// route), not searched at length.
constexpr size_t kMaxNudgedPairs = 64;
constexpr size_t kTrianglesPerNudgedPair = 16;

/// The triangle mesh being cleaned: positions always representable in the target precision,
/// per vertex the input points it stands for (to bound how far anything moves).
class Cleaner {
 public:
  Cleaner(const PolygonMesh& mesh, const Rounder& round, double max_feature, bool keep_copies)
      : round_(round), resolution_(round.resolution(mesh.vertices)), max_feature_(max_feature), keep_copies_(keep_copies) {
    p_.reserve(mesh.vertices.size());
    members_.resize(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      p_.push_back(round_(mesh.vertices[i]));
      members_[i].push_back(mesh.vertices[i]);
    }
    incident_.resize(p_.size());
    // Cells of the spatial hash: about the mean edge length of the faces' corners.
    double total = 0;
    size_t edges = 0;
    for (const auto& f : mesh.faces)
      for (size_t k = 0; k < f.size(); ++k, ++edges) total += (mesh.vertices[f[k]] - mesh.vertices[f[(k + 1) % f.size()]]).norm();
    cell_ = edges > 0 && total > 0 ? 2 * total / static_cast<double>(edges) : 1.0;
    // Every face as n - 2 triangles: ear clipping of the rounded corners where it covers the face;
    // else of the given corners (rounding can make two corners one point, and a polygon with a
    // hole bridged to its rim then no longer simple; the given face is, and what rounding folds of
    // its triangles the sweeps below repair); else a fan (a face of zero area keeps its edges; its
    // zero-area triangles are removed below).
    for (const auto& f : mesh.faces) {
      std::vector<IndexTriangle> tris = triangulate_polygon(p_, f);
      if (tris.size() + 2 != f.size()) tris = triangulate_polygon(mesh.vertices, f);
      if (tris.size() + 2 != f.size()) {
        tris.clear();
        for (size_t k = 1; k + 1 < f.size(); ++k) tris.push_back({f[0], f[k], f[k + 1]});
      }
      for (const IndexTriangle& t : tris) add_triangle(t);
    }
    settled_ = true;
  }

  /// Whether any triangles cross (crossings(): only what changed is searched again).
  bool cross() { return !crossings().empty(); }

  /// One round of local operations at feature size `delta`; true if anything changed.
  bool sweep(double delta, OutputRoundingReport& report) {
    bool changed = false;
    // Copies of one point that no edge joins: move each but the first into its own sheet.
    std::map<std::array<double, 3>, std::vector<int>> at;
    for (size_t v = 0; v < p_.size(); ++v)
      if (vertex_alive(static_cast<int>(v))) at[{p_[v].x(), p_[v].y(), p_[v].z()}].push_back(static_cast<int>(v));
    for (auto& [point, copies] : at) {
      if (keep_copies_) break;
      for (size_t i = 1; i < copies.size(); ++i) {
        const std::set<int> n = neighbours(copies[i]);
        if (std::any_of(copies.begin(), copies.end(), [&](int c) { return n.count(c) != 0; })) continue;  // a zero-length edge
        if (separate(copies[i], delta)) {
          ++report.separated_vertices;
          changed = true;
        }
      }
    }
    // Clusters of vertices joined by edges shorter than delta.
    std::vector<int> parent(p_.size());
    for (size_t v = 0; v < parent.size(); ++v) parent[v] = static_cast<int>(v);
    auto find = [&](int v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    bool short_edges = false;
    for (size_t t = 0; t < tris_.size(); ++t) {
      if (!alive_[t]) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = tris_[t][k], b = tris_[t][(k + 1) % 3];
        if ((p_[a] - p_[b]).norm() < delta) {
          parent[find(a)] = find(b);
          short_edges = true;
        }
      }
    }
    if (short_edges) {
      std::map<int, std::vector<int>> clusters;
      for (size_t v = 0; v < parent.size(); ++v)
        if (vertex_alive(static_cast<int>(v))) clusters[find(static_cast<int>(v))].push_back(static_cast<int>(v));
      for (const auto& [root, cluster] : clusters) {
        if (cluster.size() < 2) continue;
        bool alive = true;
        for (int v : cluster) alive = alive && vertex_alive(v);
        if (alive && collapse_cluster(cluster, delta, report)) changed = true;
      }
    }
    // Slivers without a short edge (a corner close to the opposite edge): flip that edge.
    for (size_t t = 0, count = tris_.size(); t < count; ++t) {
      if (!alive_[t]) continue;
      const Tri& tri = tris_[t];
      int longest = 0;
      double longest_length = -1;
      for (int k = 0; k < 3; ++k) {
        const double l = (p_[tri[(k + 1) % 3]] - p_[tri[k]]).norm();
        if (l > longest_length) longest_length = l, longest = k;
      }
      const Vector3d n = normal(tri);
      if (longest_length <= 0 || n.norm() / longest_length >= delta) continue;
      if (flip(static_cast<int>(t), longest)) {
        ++report.flipped_edges;
        changed = true;
      }
    }
    return changed;
  }

  /// Sheets closer than the resolution over a wide area (no short edge, no sliver) that rounding
  /// made cross: a corner of each crossing pair is moved off the other triangle's plane, either
  /// way (nudge). True if anything moved. A full scan: called once contractions and flips are
  /// done or stuck, not after each of their passes.
  bool nudge_crossings(double delta, OutputRoundingReport& report) {
    const std::vector<std::pair<int, int>> pairs = crossings();
    if (pairs.size() > std::max(kMaxNudgedPairs, live_triangles() / kTrianglesPerNudgedPair)) return false;
    bool changed = false;
    for (const auto& [t, u] : pairs)
      for (const auto& [mine, other] : {std::pair{t, u}, std::pair{u, t}}) {
        if (!alive_[mine] || !alive_[other]) continue;
        const Vector3d n = normal(tris_[other]);
        if (!(n.squaredNorm() > 0)) continue;
        bool moved = false;
        for (int v : tris_[mine])
          if (!moved && nudge(v, n.normalized(), delta)) moved = true;
        if (moved) {
          ++report.nudged_vertices;
          changed = true;
          break;
        }
      }
    return changed;
  }

  size_t live_triangles() const { return static_cast<size_t>(std::count(alive_.begin(), alive_.end(), true)); }

  /// The live triangles; the vertices they use in the order of the input (indexed formats keep it).
  PolygonMesh mesh() const {
    PolygonMesh out;
    std::vector<int> index(p_.size(), -1);
    for (size_t t = 0; t < tris_.size(); ++t)
      if (alive_[t])
        for (int v : tris_[t]) index[v] = 0;
    for (size_t v = 0; v < p_.size(); ++v)
      if (index[v] == 0) {
        index[v] = static_cast<int>(out.vertices.size());
        out.vertices.push_back(p_[v]);
      }
    for (size_t t = 0; t < tris_.size(); ++t)
      if (alive_[t]) out.faces.push_back({index[tris_[t][0]], index[tris_[t][1]], index[tris_[t][2]]});
    return out;
  }

  /// Farthest an input vertex is from the vertex standing for it.
  double max_move() const {
    double m = 0;
    for (size_t v = 0; v < p_.size(); ++v)
      if (vertex_alive(static_cast<int>(v)))
        for (const Vector3d& q : members_[v]) m = std::max(m, (q - p_[v]).norm());
    return m;
  }

 private:
  void add_triangle(const Tri& t) {
    const int id = static_cast<int>(tris_.size());
    tris_.push_back(t);
    alive_.push_back(true);
    level_.push_back(-1);
    boxes_.emplace_back();
    prepared_.emplace_back();
    update_box(id);
    for (int v : t) incident_[v].push_back(id);
  }

  void kill_triangle(int t) {
    alive_[t] = false;
    index(t, -1);
    for (int v : tris_[t]) std::erase(incident_[v], t);
  }

  bool vertex_alive(int v) const { return !incident_[v].empty(); }

  Vector3d normal(const Tri& t) const { return (p_[t[1]] - p_[t[0]]).cross(p_[t[2]] - p_[t[0]]); }

  std::set<int> neighbours(int v) const {
    std::set<int> n;
    for (int t : incident_[v])
      for (int w : tris_[t])
        if (w != v) n.insert(w);
    return n;
  }

  /// Pairs (triangle in `group`, live triangle outside `replaced`) that meet beyond what they
  /// share, plus pairs within `group`; `group` holds corner ids with the current positions.
  int meetings(const std::vector<Tri>& group, const std::vector<int>& replaced,
               int enough = std::numeric_limits<int>::max()) const {
    int count = 0;
    for (size_t i = 0; i < group.size(); ++i) {
      const Tri& a = group[i];
      const std::array<Vector3d, 3> pa = {p_[a[0]], p_[a[1]], p_[a[2]]};
      if (collinear(pa[0], pa[1], pa[2])) continue;
      Eigen::AlignedBox3d box;
      for (const Vector3d& q : pa) box.extend(q);
      for (int t : near(box)) {
        if (!alive_[t] || !box.intersects(boxes_[t])) continue;
        if (std::find(replaced.begin(), replaced.end(), t) != replaced.end()) continue;
        const Tri& b = tris_[t];
        const std::array<Vector3d, 3> pb = {p_[b[0]], p_[b[1]], p_[b[2]]};
        if (collinear(pb[0], pb[1], pb[2])) continue;  // degenerate: removed later or reported
        if (triangles_meet(a, pa, b, pb) && ++count >= enough) return count;
      }
      for (size_t j = 0; j < i; ++j) {
        const Tri& b = group[j];
        const std::array<Vector3d, 3> pb = {p_[b[0]], p_[b[1]], p_[b[2]]};
        if (!collinear(pb[0], pb[1], pb[2]) && triangles_meet(a, pa, b, pb) && ++count >= enough) return count;
      }
    }
    return count;
  }

  /// Replacing the triangles `replaced` by `added` (corners at the positions in `added_at`, which
  /// differ from the current ones only for `moved`) would add meetings of triangles: more pairs
  /// meet afterwards than before. Meetings that rounding made before are not held against an
  /// operation that keeps or removes them.
  bool conflicts(const std::vector<Tri>& added, const std::vector<int>& replaced,
                 int moved = -1, const Vector3d& moved_to = Vector3d::Zero()) {
    const int after_moving = [&] {
      if (moved < 0) return meetings(added, replaced);
      const Vector3d keep = p_[moved];
      p_[moved] = moved_to;
      const int n = meetings(added, replaced);
      p_[moved] = keep;
      return n;
    }();
    if (after_moving == 0) return false;
    std::vector<Tri> before;
    for (int t : replaced) before.push_back(tris_[t]);
    return after_moving > meetings(before, replaced);
  }

  // The spatial hash has levels of cells cell_ * 4^k; a triangle is kept at the finest level whose
  // cells its box spans at most 4 of per axis (so long triangles do not fill every query).
  static constexpr int kLevels = 16;

  /// Cell range of a box at level k, or false if the coordinates are out of range.
  bool cell_range(const Eigen::AlignedBox3d& box, int k, Eigen::Array3i& lo, Eigen::Array3i& hi) const {
    const double size = std::ldexp(cell_, 2 * k);
    const Eigen::Array3d a = (box.min().array() / size).floor(), b = (box.max().array() / size).floor();
    if (!a.allFinite() || !b.allFinite() || a.abs().maxCoeff() > 1e9 || b.abs().maxCoeff() > 1e9) return false;
    lo = a.cast<int>();
    hi = b.cast<int>();
    return true;
  }

  /// The level a box is kept at, or -1 (kept in big_).
  int level_of(const Eigen::AlignedBox3d& box) const {
    Eigen::Array3i lo, hi;
    for (int k = 0; k < kLevels; ++k)
      if (cell_range(box, k, lo, hi) && (hi - lo).maxCoeff() <= 3) return k;
    return -1;
  }

  static std::int64_t cell_key(int k, int x, int y, int z) {
    return (static_cast<std::int64_t>(x) * 73856093) ^ (static_cast<std::int64_t>(y) * 19349663) ^
           (static_cast<std::int64_t>(z) * 83492791) ^ (static_cast<std::int64_t>(k) * 2654435761);
  }

  /// Adds (sign > 0) or removes triangle t under its current box.
  void index(int t, int sign) {
    const int k = sign > 0 ? level_of(boxes_[t]) : level_[t];
    if (sign > 0) level_[t] = k;
    if (k < 0) {
      if (sign > 0) big_.push_back(t);
      else std::erase(big_, t);
      return;
    }
    per_level_[k] += sign;
    Eigen::Array3i lo, hi;
    cell_range(boxes_[t], k, lo, hi);
    for (int x = lo.x(); x <= hi.x(); ++x)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int z = lo.z(); z <= hi.z(); ++z) {
          auto& list = cells_[cell_key(k, x, y, z)];
          if (sign > 0) list.push_back(t);
          else std::erase(list, t);
        }
  }

  /// Triangles whose boxes may meet `box` (each once).
  std::vector<int> near(const Eigen::AlignedBox3d& box) const {
    // Each triangle once (it may sit in several cells): marked with this query's stamp.
    if (seen_.size() < tris_.size()) seen_.resize(tris_.size(), 0);
    if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0), stamp_ = 1;
    std::vector<int> out = big_;
    for (int k = 0; k < kLevels; ++k) {
      if (per_level_[k] == 0) continue;
      Eigen::Array3i lo, hi;
      if (!cell_range(box, k, lo, hi) || (hi - lo + 1).cast<double>().prod() > 4096) {
        for (size_t t = 0; t < tris_.size(); ++t)  // a query far larger than this level's cells
          if (alive_[t] && level_[t] == k) out.push_back(static_cast<int>(t));
        continue;
      }
      for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
          for (int z = lo.z(); z <= hi.z(); ++z) {
            const auto it = cells_.find(cell_key(k, x, y, z));
            if (it == cells_.end()) continue;
            for (int t : it->second)
              if (seen_[t] != stamp_) {
                seen_[t] = stamp_;
                out.push_back(t);
              }
          }
    }
    return out;
  }

  void update_box(int t) {
    if (dirty_.size() < tris_.size()) dirty_.resize(tris_.size(), 0);
    dirty_[t] = settled_ ? 1 : 0;
    if (!boxes_[t].isEmpty()) index(t, -1);
    Eigen::AlignedBox3d box;
    for (int v : tris_[t]) box.extend(p_[v]);
    boxes_[t] = box;
    index(t, +1);
    prepared_[t] = mesh::detail::prepare_triangle(tris_[t], {p_[tris_[t][0]], p_[tris_[t][1]], p_[tris_[t][2]]});
  }

  /// Farthest input point of u's and v's members from `target`.
  double spread(int u, int v, const Vector3d& target) const {
    double m = 0;
    for (int w : {u, v})
      for (const Vector3d& q : members_[w]) m = std::max(m, (q - target).norm());
    return m;
  }

  /// A triangle with the corners of t (any order) is alive, other than the ones in `except`.
  bool triangle_exists(const Tri& t, const std::vector<int>& except) const {
    Tri sorted = t;
    std::sort(sorted.begin(), sorted.end());
    for (int id : incident_[t[0]]) {
      if (std::find(except.begin(), except.end(), id) != except.end()) continue;
      Tri other = tris_[id];
      std::sort(other.begin(), other.end());
      if (other == sorted) return true;
    }
    return false;
  }

  /// A triangle whose shape says nothing about its orientation: its height is below `delta`.
  bool sliver(const Tri& t, double delta) const {
    double longest = 0;
    for (int k = 0; k < 3; ++k) longest = std::max(longest, (p_[t[(k + 1) % 3]] - p_[t[k]]).norm());
    return normal(t).norm() < delta * longest;
  }

  /// Contracts the vertices of `cluster` (joined by edges shorter than delta) into its member
  /// `target`: triangles with two or more corners in the cluster disappear, the others are
  /// rewritten. Done only if the mesh stays a closed 2-manifold (the rewritten triangles form one
  /// fan around target), no triangle degenerates, no triangle larger than delta turns over, no
  /// two triangles come to meet, and nothing moves farther than max_feature. A cluster that is a
  /// whole shell (nothing outside it) disappears.
  bool collapse(const std::vector<int>& cluster, int target, double delta) {
    std::set<int> in(cluster.begin(), cluster.end());
    std::set<int> region;
    for (int v : cluster) region.insert(incident_[v].begin(), incident_[v].end());
    std::vector<int> removed, changed;
    std::vector<Tri> afters;
    for (int t : region) {
      int count = 0;
      for (int w : tris_[t]) count += in.count(w) != 0 ? 1 : 0;
      if (count >= 2) {
        removed.push_back(t);
        continue;
      }
      Tri after = tris_[t];
      for (int& w : after)
        if (in.count(w) != 0) w = target;
      changed.push_back(t);
      afters.push_back(after);
    }
    double reach = 0;
    for (int v : cluster)
      for (const Vector3d& q : members_[v]) reach = std::max(reach, (q - p_[target]).norm());
    if (reach > max_feature_) return false;
    if (changed.empty()) {  // a closed shell smaller than delta
      bool closed = true;
      for (int t : removed)
        for (int w : tris_[t]) closed = closed && in.count(w) != 0;
      if (!closed) return false;
      for (int t : removed) kill_triangle(t);
      return true;
    }
    // One fan: each edge target->w once and w->target once, and the rim a single cycle.
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
    if (steps != static_cast<int>(next.size())) return false;
    for (size_t i = 0; i < changed.size(); ++i) {
      // A triangle that was a sliver may become degenerate (a later flip removes it); others
      // must keep a positive area and their orientation.
      const Tri& a = afters[i];
      const Tri& before = tris_[changed[i]];
      if (sliver(before, delta)) continue;
      if (collinear(p_[a[0]], p_[a[1]], p_[a[2]])) return false;
      if (normal(before).dot(normal(a)) <= 0) return false;
    }
    std::vector<int> replaced = changed;
    replaced.insert(replaced.end(), removed.begin(), removed.end());
    if (conflicts(afters, replaced)) return false;
    for (int t : removed) kill_triangle(t);
    for (size_t i = 0; i < changed.size(); ++i) {
      const int t = changed[i];
      for (int w : tris_[t]) std::erase(incident_[w], t);
      tris_[t] = afters[i];
      for (int w : tris_[t]) incident_[w].push_back(t);
      update_box(t);
    }
    for (int v : cluster) {
      if (v == target) continue;
      incident_[v].clear();
      members_[target].insert(members_[target].end(), members_[v].begin(), members_[v].end());
      members_[v].clear();
    }
    return true;
  }

  /// Collapses the cluster into the member that works, nearest the cluster's centre first; failing
  /// that, its edges one at a time.
  bool collapse_cluster(const std::vector<int>& cluster, double delta, OutputRoundingReport& report) {
    Vector3d centre = Vector3d::Zero();
    for (int v : cluster) centre += p_[v];
    centre /= static_cast<double>(cluster.size());
    std::vector<int> order = cluster;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return (p_[a] - centre).norm() < (p_[b] - centre).norm(); });
    for (int target : order)
      if (collapse(cluster, target, delta)) {
        report.collapsed_edges += static_cast<int>(cluster.size()) - 1;
        return true;
      }
    bool any = false;
    for (size_t i = 0; i < cluster.size(); ++i)
      for (size_t j = 0; j < cluster.size(); ++j) {
        const int u = cluster[i], v = cluster[j];
        if (u == v || !vertex_alive(u) || !vertex_alive(v) || (p_[u] - p_[v]).norm() >= delta) continue;
        if (neighbours(u).count(v) == 0) continue;
        if (collapse({u, v}, v, delta)) {
          ++report.collapsed_edges;
          any = true;
        }
      }
    return any;
  }

  /// Flips the edge starting at corner k of triangle t (a sliver whose third corner lies close
  /// to that edge) if the two new triangles keep the orientation and the edge is new.
  bool flip(int t, int k) {
    const Tri tri = tris_[t];
    const int a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    int other = -1, d = -1;
    for (int s : incident_[b]) {
      if (s == t) continue;
      const Tri& q = tris_[s];
      for (int j = 0; j < 3; ++j)
        if (q[j] == b && q[(j + 1) % 3] == a) other = s, d = q[(j + 2) % 3];
    }
    if (other < 0 || d == c) return false;
    const std::set<int> nc = neighbours(c);
    if (nc.count(d) != 0) return false;
    const Tri first = {a, d, c}, second = {d, b, c};
    if (collinear(p_[a], p_[d], p_[c]) || collinear(p_[d], p_[b], p_[c])) return false;
    // c lies close to edge ab, so both new triangles face as the neighbour (b, a, d) does.
    const Vector3d reference = normal(tris_[other]);
    const Vector3d n1 = normal(first), n2 = normal(second);
    if (n1.dot(reference) <= 0 || n2.dot(reference) <= 0) return false;
    if (conflicts({first, second}, {t, other})) return false;
    kill_triangle(t);
    kill_triangle(other);
    add_triangle(first);
    add_triangle(second);
    return true;
  }

  /// Pairs of live, non-degenerate triangles that meet beyond what they share: the pairs that met
  /// at construction and are both unchanged since (they keep their verdict), and the pairs with a
  /// triangle added or moved since, searched anew.
  std::vector<std::pair<int, int>> crossings() {
    if (!first_crossings_) {  // all pairs of the triangles as built (the changed ones left out)
      first_crossings_.emplace();
      for (const auto& [t, u] : full_crossings())
        if (dirty_[t] == 0 && dirty_[u] == 0) first_crossings_->push_back({t, u});
    }
    std::vector<std::pair<int, int>> out;
    for (const auto& [t, u] : *first_crossings_)
      if (alive_[t] && alive_[u] && dirty_[t] == 0 && dirty_[u] == 0) out.push_back({t, u});
    for (size_t t = 0; t < tris_.size(); ++t)  // each pair once: a dirty partner only from the lower index
      if (alive_[t] && dirty_[t] != 0)
        meeting_partners(static_cast<int>(t), [&](int u) { return dirty_[u] != 0 && u < static_cast<int>(t); }, out);
    std::sort(out.begin(), out.end());  // worked on in this order
    return out;
  }

  /// Appends to `out` the pairs (t, u), smaller index first, of live, non-degenerate triangles u
  /// near t, not `skip`ped, that meet t beyond what they share (t itself non-degenerate).
  /// The triangles as prepared (prepared_, kept with the boxes: positions settle only through
  /// update_box; axis < 0 marks collinear corners).
  template <class Skip>
  void meeting_partners(int t, Skip skip, std::vector<std::pair<int, int>>& out) const {
    const PreparedTriangle& a = prepared_[t];
    if (a.axis < 0) return;
    for (int u : near(boxes_[t])) {
      if (u == t || skip(u) || !alive_[u] || !boxes_[t].intersects(boxes_[u])) continue;
      const PreparedTriangle& b = prepared_[u];
      if (b.axis >= 0 && mesh::detail::triangles_meet(a, b)) out.push_back(std::minmax(t, u));
    }
  }

  /// Pairs of live, non-degenerate triangles that meet beyond what they share, all searched.
  /// Candidates come from one pass over a uniform grid (mesh/detail/box_grid.hpp, the broad phase
  /// of search_self_intersections too), not from a query per triangle: every pair of overlapping
  /// boxes once, so the same pairs as meeting_partners over all triangles.
  std::vector<std::pair<int, int>> full_crossings() const {
    std::vector<std::pair<int, int>> out;
    std::vector<int> live;
    for (size_t t = 0; t < tris_.size(); ++t)
      if (alive_[t] && prepared_[t].axis >= 0) live.push_back(static_cast<int>(t));
    if (live.size() < 2) return out;
    std::vector<Eigen::AlignedBox3d> boxes;
    boxes.reserve(live.size());
    Eigen::AlignedBox3d all;
    for (int t : live) boxes.push_back(boxes_[t]), all.extend(boxes_[t]);
    if (!all.min().allFinite() || !all.max().allFinite() || !all.sizes().allFinite()) {
      for (int t : live) meeting_partners(t, [&](int u) { return u <= t; }, out);  // no grid: a query per triangle
    } else {
      const mesh::detail::BoxGrid grid(boxes);
      std::vector<Eigen::AlignedBox3d> local;  // a cell's boxes, gathered
      for (size_t k = 0; k < grid.cells(); ++k) {
        const std::span<const int> here = grid.cell(k);
        const std::span<const unsigned char> first = grid.first_cell_masks(k);
        local.clear();
        for (int i : here) local.push_back(boxes[size_t(i)]);
        for (size_t i = 0; i < here.size(); ++i)
          for (size_t j = i + 1; j < here.size(); ++j) {
            // Owned by this cell (BoxGrid::first_cell_masks) and overlapping.
            if ((first[i] | first[j]) != 7 || !local[i].intersects(local[j])) continue;
            const int t = live[size_t(here[i])], u = live[size_t(here[j])];
            if (mesh::detail::triangles_meet(prepared_[t], prepared_[u])) out.push_back(std::minmax(t, u));
          }
      }
    }
    std::sort(out.begin(), out.end());  // worked on in this order
    return out;
  }

  /// Moves v along +-`direction` by the smallest step (delta / 8, doubling up to `delta`)
  /// after which its triangles meet fewer others, keep their orientation and do not degenerate.
  bool nudge(int v, const Vector3d& direction, double delta) {
    std::vector<Tri> around;
    for (int t : incident_[v]) around.push_back(tris_[t]);
    const int before = meetings(around, incident_[v]);
    if (before == 0) return false;
    std::vector<Vector3d> normals;
    for (int t : incident_[v]) normals.push_back(normal(tris_[t]));
    const Vector3d old = p_[v];
    for (double step = std::max(resolution_, delta / 8); step <= delta; step *= 2)
      for (const double sign : {1.0, -1.0}) {
        const Vector3d target = round_(Vector3d(old + sign * step * direction));
        if (target == old || spread(v, v, target) > max_feature_) continue;
        p_[v] = target;
        bool ok = true;
        for (size_t i = 0; i < incident_[v].size() && ok; ++i) {
          const Tri& q = tris_[incident_[v][i]];
          ok = !collinear(p_[q[0]], p_[q[1]], p_[q[2]]) && (normals[i].squaredNorm() == 0 || normals[i].dot(normal(q)) > 0);
        }
        ok = ok && meetings(around, incident_[v], before) < before;
        p_[v] = old;
        if (ok) {
          p_[v] = target;
          for (int t : incident_[v]) update_box(t);
          return true;
        }
      }
    return false;
  }

  /// Moves v by at most `delta` against the mean normal of its triangles (into its own sheet), else
  /// toward the middle of its neighbours, rounded to the precision, if no triangle turns over or
  /// degenerates: by the smallest step after which its triangles meet nothing, else by the step
  /// after which they meet fewest, if that is no more than before.
  bool separate(int v, double delta) {
    std::vector<Tri> moved;
    for (int t : incident_[v]) moved.push_back(tris_[t]);
    Step best{meetings(moved, incident_[v]), std::nullopt};  // to beat
    Vector3d n = Vector3d::Zero();
    for (int t : incident_[v]) {
      const Vector3d m = normal(tris_[t]);
      if (m.squaredNorm() > 0) n += m.normalized();
    }
    if (n.squaredNorm() > 0) separate_along(v, -n.normalized(), delta, moved, best);
    // The tip of a thin spike (slivers of solids that touch at a point, meeting at an apex) has a
    // mean normal out of its sides; toward the middle of its neighbours it goes into the spike.
    if (const std::set<int> around = neighbours(v); (!best.target || best.meetings > 0) && !around.empty()) {
      Vector3d middle = Vector3d::Zero();
      for (int w : around) middle += p_[w];
      const Vector3d inward = middle / double(around.size()) - p_[v];
      if (inward.squaredNorm() > 0) separate_along(v, inward.normalized(), delta, moved, best);
    }
    if (!best.target) return false;
    p_[v] = *best.target;
    for (int t : incident_[v]) update_box(t);
    return true;
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
  void separate_along(int v, const Vector3d& direction, double delta, const std::vector<Tri>& moved, Step& best) {
    const Vector3d old = p_[v];
    for (double step = resolution_; step <= delta; step *= 2) {
      const Vector3d target = round_(Vector3d(old + step * direction));
      if (target == old) continue;
      if (spread(v, v, target) > max_feature_) break;
      std::vector<Vector3d> before;
      for (int t : incident_[v]) before.push_back(normal(tris_[t]));
      p_[v] = target;
      bool ok = true;
      for (size_t i = 0; i < incident_[v].size() && ok; ++i) {
        const Tri& q = tris_[incident_[v][i]];
        ok = !collinear(p_[q[0]], p_[q[1]], p_[q[2]]) && (before[i].squaredNorm() == 0 || before[i].dot(normal(q)) > 0);
      }
      const int count = ok ? meetings(moved, incident_[v], best.meetings + 1) : -1;
      p_[v] = old;
      if (count >= 0 && (count < best.meetings || (count == best.meetings && !best.target))) best = {count, target};
      if (best.target && best.meetings == 0) return;
    }
  }

  Rounder round_;
  double resolution_;
  double max_feature_;
  bool keep_copies_;
  std::vector<Vector3d> p_;
  std::vector<std::vector<Vector3d>> members_;
  std::vector<Tri> tris_;
  std::vector<bool> alive_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  std::vector<PreparedTriangle> prepared_;  ///< per triangle, at the positions of its box
  double cell_ = 1;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
  std::array<int, kLevels> per_level_{};  ///< triangles kept at each level
  std::vector<int> level_;                ///< level of each triangle (-1: big_)
  std::vector<int> big_;
  bool settled_ = false;                 ///< construction done: changes from here on make triangles dirty
  std::vector<char> dirty_;              ///< triangle added or moved since construction
  std::optional<std::vector<std::pair<int, int>>> first_crossings_;  ///< crossings() at construction
  mutable std::vector<unsigned> seen_;  ///< near(): the stamp of the last query that returned a triangle
  mutable unsigned stamp_ = 0;
  std::vector<std::vector<int>> incident_;
};

/// Budget of the self-intersection search (candidate pairs): enough for any mesh whose faces are
/// not long fans (thousands of corners in one face); beyond it the check gives up (kUnchecked).
constexpr size_t kCandidatesPerCorner = 16;
constexpr size_t kMinCandidates = 500'000;
/// Faces with more corners are not triangulated for the search (ear clipping is quadratic).
constexpr size_t kMaxJudgedCorners = 2048;
constexpr const char* kUnchecked = "self-intersections not checked: the search exceeded its budget";

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

}  // namespace

namespace {

/// output_problem; `topology_clean`: the caller found no defect at all in `mesh` with the same
/// topology check, and the precision is doubles (rounding changes nothing), so it is not repeated.
/// `options.exact_vertices` (if one per vertex) marks vertices whose pairs of all-marked faces
/// need no self-intersection test; a vertex the rounding moves loses its mark.
/// `crossings_searched`: `mesh` is the cleaner's mesh, all triangles, with coordinates already in
/// the precision, and the cleaner's own exact search (Cleaner::crossings, every pair of live,
/// non-degenerate triangles, corners told apart by index) found no two that meet beyond what they
/// share; the search here (corners at one point counted as one, so it allows more) would find
/// none either, and is not repeated.
std::string judge(const PolygonMesh& mesh, const OutputRoundingOptions& options, bool topology_clean,
                  bool crossings_searched = false) {
  const Rounder round(options);
  PolygonMesh copy;
  if (options.precision != OutputPrecision::Double) {  // doubles: rounding is the identity
    copy = mesh;
    for (Vector3d& v : copy.vertices) v = round(v);
  }
  const PolygonMesh& rounded = options.precision == OutputPrecision::Double ? mesh : copy;
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
      return "vertices " + std::to_string(first) + " and " + std::to_string(second) + " are at the same point";
  }
  if (!topology_clean) {
    const ValidationReport report =
        check_closed_manifold(rounded, {.check_self_intersections = false, .check_face_shapes = false,
                                        .check_shell_orientation = false, .max_defects_per_kind = 1});
    if (!report.ok()) return report.defects.front().message;
  }
  if (crossings_searched) return {};
  for (const auto& f : rounded.faces)
    if (f.size() > kMaxJudgedCorners) return std::string(kUnchecked);
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
    return "faces " + std::to_string(p.face_a) + " and " + std::to_string(p.face_b) + " intersect";
  }
  if (!search.complete) return std::string(kUnchecked);
  return {};
}

}  // namespace

std::string output_problem(const PolygonMesh& mesh, const OutputRoundingOptions& options) {
  return judge(mesh, options, false);
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
  // Only closed, oriented 2-manifolds are rounded: anything else (an open patch) is left as it is.
  const ValidationReport topology =
      check_closed_manifold(mesh, {.check_self_intersections = false, .check_face_shapes = false,
                                   .check_shell_orientation = false, .max_defects_per_kind = 1});
  for (const Defect& d : topology.defects) {
    if (d.kind == DefectKind::DegenerateFace || d.kind == DefectKind::NonPlanarFace ||
        d.kind == DefectKind::SelfCrossingFace)
      continue;
    r.clean = false;
    r.problem = d.message;
    return std::move(mesh);
  }
  const Rounder round(options);
  const bool topology_clean = topology.defects.empty() && options.precision == OutputPrecision::Double;
  const std::string first = options.triangles ? std::string("triangles asked for") : judge(mesh, given, topology_clean);
  if (first == kUnchecked) {  // too costly to judge: written as it is, and said so
    r.clean = false;
    r.problem = first;
    return std::move(mesh);
  }
  if (first.empty()) {
    if (options.precision == OutputPrecision::Double) return std::move(mesh);
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

  Cleaner cleaner(mesh, round, max_feature, options.keep_copies);
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
      for (int pass = 0; pass < 20 && cleaner.sweep(delta, r); ++pass) changed = true;
      if (!cleaner.nudge_crossings(delta, r)) break;
      changed = true;
    }
    r.feature = delta;
    if (changed || !judged) {
      judged = true;
      full = !cleaner.cross();
      if (full) {
        result = cleaner.mesh();
        r.problem = judge(result, options, false, /*crossings_searched=*/true);
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

}  // namespace sculpt
