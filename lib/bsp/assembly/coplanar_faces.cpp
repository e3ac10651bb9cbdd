#include "bsp/assembly/coplanar_faces.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <span>

#include "base/assert.hpp"

namespace sculpt::bsp::detail {

namespace {

/// A union of fragments with holes (a plate's face around its drilled holes) is not one simple
/// polygon, but it can be a few: this grows disks through it, one after the other, each from its
/// first free fragment in face order, adding a neighbour across a shared edge while the union
/// stays a disk (Whitney's condition for gluing a convex cell to a disk: it meets the disk's
/// boundary in one path of its own edges and nowhere else), up to kMaxCorners corners. Every
/// vertex cut into the interior of a disk leaves the output; before, all the fragments stayed,
/// with the vertices where extended face planes crossed inside the face (not grid points: the
/// output check then searched a plate's long fan triangles against each other).
class DiskGrower {
 public:
  static constexpr int kMaxCorners = 128;  // faces stay cheap to triangulate and to check

  DiskGrower(const FaceList& faces, int vertex_count)
      : faces_(faces), leave_to_(std::size_t(vertex_count), -1), leave_line_(std::size_t(vertex_count), 0) {}

  /// Disks through the fragments `members` (one connected union on one oriented plane), whose
  /// neighbours across interior edges `neighbours(f, visit)` lists. Each disk of two or more is
  /// appended to `added` and its fragments marked in `removed`; `disk` (one entry per face,
  /// -1 for free ones) is left marked for the members.
  template <typename Neighbours>
  void run(std::span<const int> members, Neighbours&& neighbours, std::vector<int>& disk, FaceList& added,
           std::vector<std::uint8_t>& removed) {
    for (const int seed : members) {
      if (disk[std::size_t(seed)] >= 0) continue;
      const int id = seed;
      grown_.assign(1, seed);
      disk[std::size_t(seed)] = id;
      corners_ = 0;
      for (int c = faces_.begin(seed); c < faces_.end(seed); ++c) {
        const int u = faces_.vertex[std::size_t(c)];
        leave_to_[std::size_t(u)] = faces_.vertex[std::size_t(faces_.next(seed, c))];
        leave_line_[std::size_t(u)] = faces_.line[std::size_t(c)];
        touched_.push_back(u);
        ++corners_;
      }
      queue_.clear();
      neighbours(seed, [&](int g) { queue_.push_back(g); });
      for (std::size_t k = 0; k < queue_.size(); ++k) {
        const int f = queue_[k];
        if (disk[std::size_t(f)] >= 0 || !glue(f)) continue;
        disk[std::size_t(f)] = id;
        grown_.push_back(f);
        neighbours(f, [&](int g) {
          if (disk[std::size_t(g)] < 0) queue_.push_back(g);
        });
      }
      if (grown_.size() >= 2) emit(seed, added, removed);
      for (const int v : touched_) leave_to_[std::size_t(v)] = -1;
      touched_.clear();
    }
  }

 private:
  // Fragment f glued to the disk if that keeps it a disk of at most kMaxCorners corners. Edge i
  // (v_i -> v_i+1) is shared when the disk's boundary runs v_i+1 -> v_i.
  bool glue(int f) {
    const int b = faces_.begin(f), n = faces_.count(f);
    auto vertex = [&](int i) { return faces_.vertex[std::size_t(b + (i % n))]; };
    shared_.assign(std::size_t(n), 0);
    int count = 0;
    for (int i = 0; i < n; ++i) count += shared_[std::size_t(i)] = leave_to_[std::size_t(vertex(i + 1))] == vertex(i);
    if (count == 0 || count == n) return false;
    // One run of shared edges: exactly one edge i shared after an unshared one; it starts the run.
    int first = -1, runs = 0;
    for (int i = 0; i < n; ++i)
      if (shared_[std::size_t(i)] && !shared_[std::size_t((i + n - 1) % n)]) first = i, ++runs;
    if (runs != 1) return false;
    const int last = first + count;  // v_first .. v_last lie on the run
    // The other vertices must not be on the disk's boundary (no pinch).
    for (int i = last + 1; i < first + n; ++i)
      if (leave_to_[std::size_t(vertex(i))] >= 0) return false;
    const int after = corners_ - (count - 1) + (n - count - 1);
    if (after > kMaxCorners) return false;
    // The run's edges leave the boundary (the disk's edge v_i+1 -> v_i leaves v_i+1), then f's
    // other edges join it.
    for (int i = first; i < last; ++i) leave_to_[std::size_t(vertex(i + 1))] = -1;
    for (int i = last; i < first + n; ++i) {
      const int u = vertex(i);
      leave_to_[std::size_t(u)] = vertex(i + 1);
      leave_line_[std::size_t(u)] = faces_.line[std::size_t(b + (i % n))];
      touched_.push_back(u);
    }
    corners_ = after;
    return true;
  }

  // The disk's boundary loop as one face, from the first vertex that joined the boundary and
  // is still on it (the seed's corners may all have become interior).
  void emit(int seed, FaceList& added, std::vector<std::uint8_t>& removed) {
    int first = -1;
    for (std::size_t k = 0; k < touched_.size() && first < 0; ++k)
      if (leave_to_[std::size_t(touched_[k])] >= 0) first = touched_[k];
    SCULPT_ASSERT(first >= 0, "merge_coplanar_faces: a disk without a boundary");
    if (first < 0) return;
    const std::size_t mark = added.vertex.size();
    added.open_face(faces_.support[std::size_t(seed)], faces_.flip[std::size_t(seed)] != 0);
    int u = first;
    do {
      added.add_corner(u, leave_line_[std::size_t(u)]);
      u = leave_to_[std::size_t(u)];
    } while (u >= 0 && u != first && int(added.vertex.size() - mark) <= corners_);
    if (u != first || int(added.vertex.size() - mark) != corners_) {  // not one loop: keep the fragments
      SCULPT_ASSERT(false, "merge_coplanar_faces: a disk's boundary is not one loop");
      added.drop_last_face();
      return;
    }
    for (const int f : grown_) removed[std::size_t(f)] = 1;
  }

  const FaceList& faces_;
  std::vector<int> leave_to_;  // per vertex: the next vertex along the disk's boundary, or -1
  std::vector<std::int32_t> leave_line_;
  std::vector<int> touched_, grown_, queue_;
  std::vector<std::uint8_t> shared_;
  int corners_ = 0;
};

}  // namespace

FaceList merge_coplanar_faces(FaceList faces, int vertex_count, const PlaneIds& ids) {
  const int nf = faces.size();
  const std::size_t corners = std::size_t(faces.corners());
  // Oriented plane of each face: equal planes share a canonical id, the outward side one bit.
  std::vector<std::uint64_t> plane(static_cast<std::size_t>(nf));
  std::vector<std::uint8_t> on_plane(2 * ids.id.size(), 0);  // faces per oriented plane: 0, 1, 2 = more
  for (int f = 0; f < nf; ++f) {
    const auto s = std::size_t(faces.support[std::size_t(f)]);
    const std::uint64_t oriented = 2 * std::uint64_t(ids.id[s]) + ((ids.negated[s] != 0) != (faces.flip[std::size_t(f)] != 0) ? 1 : 0);
    plane[std::size_t(f)] = oriented;
    std::uint8_t& n = on_plane[std::size_t(oriented)];
    n = n < 2 ? n + 1 : 2;
  }
  // A face alone on its oriented plane has no interior edge (its opposite half-edges lie on
  // other planes): only the other faces' half-edges are indexed and looked up.
  auto shared = [&](int f) { return on_plane[std::size_t(plane[std::size_t(f)])] == 2; };
  // Half-edges by start vertex (counting sort), each with its face and that face's plane, so a
  // lookup touches one contiguous run.
  struct Out {
    int to, face;
    std::uint64_t plane;
  };
  std::vector<int> start(std::size_t(vertex_count) + 1, 0);
  for (int f = 0; f < nf; ++f)
    if (shared(f))
      for (int c = faces.begin(f); c < faces.end(f); ++c) ++start[std::size_t(faces.vertex[std::size_t(c)]) + 1];
  for (std::size_t v = 0; v < std::size_t(vertex_count); ++v) start[v + 1] += start[v];
  std::vector<Out> by_start(std::size_t(start.back()));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < nf; ++f)
      if (shared(f))
        for (int c = faces.begin(f); c < faces.end(f); ++c)
          by_start[std::size_t(fill[std::size_t(faces.vertex[std::size_t(c)])]++)] = {faces.vertex[std::size_t(faces.next(f, c))], f,
                                                                                 plane[std::size_t(f)]};
  }
  // Faces of one oriented plane joined through an edge (u, w) / (w, u) form one candidate union;
  // such edges are interior to it.
  UnionFind uf(static_cast<std::size_t>(nf));
  std::vector<std::uint8_t> interior(corners, 0);
  bool any = false;
  constexpr std::size_t kAhead = 8;
  for (int f = 0; f < nf; ++f) {
    if (!shared(f)) continue;
    const std::uint64_t mine = plane[std::size_t(f)];
    for (int c = faces.begin(f); c < faces.end(f); ++c) {
      const int u = faces.vertex[std::size_t(c)], w = faces.vertex[std::size_t(faces.next(f, c))];
      // The run of a corner a few ahead (its face's next corner or a later face's: only a hint)
      // is prefetched: the runs are scattered over an index larger than the caches.
      if (std::size_t(c) + kAhead < corners) __builtin_prefetch(&by_start[std::size_t(start[std::size_t(faces.vertex[std::size_t(c) + kAhead])])]);
      for (int i = start[std::size_t(w)]; i < start[std::size_t(w) + 1]; ++i) {
        const Out& o = by_start[std::size_t(i)];
        if (o.to != u || o.plane != mine) continue;
        interior[std::size_t(c)] = 1;
        if (o.face != f) uf.unite(f, o.face), any = true;
      }
    }
  }
  if (!any) return faces;
  // Members of each union (the root is its smallest face), by counting sort.
  std::vector<int> member_start(std::size_t(nf) + 1, 0);
  for (int f = 0; f < nf; ++f) ++member_start[std::size_t(uf.find(f)) + 1];
  for (std::size_t f = 0; f < std::size_t(nf); ++f) member_start[f + 1] += member_start[f];
  std::vector<int> members(static_cast<std::size_t>(nf));
  {
    std::vector<int> fill(member_start.begin(), member_start.end() - 1);
    for (int f = 0; f < nf; ++f) members[std::size_t(fill[std::size_t(uf.find(f))]++)] = f;
  }
  // Each union's boundary edges (corners not interior) must form one loop through every one
  // of them: a simple polygon. The edge leaving each vertex is found through a per-vertex slot
  // (`leaving`, reset after each union) instead of sorting the edges.
  struct Boundary {
    int u, w;
    std::int32_t line;
  };
  std::vector<int> leaving(std::size_t(vertex_count), -1);  // vertex -> its boundary edge
  std::vector<Boundary> boundary;                           // the union's boundary edges
  boundary.reserve(64);
  std::vector<std::uint8_t> removed(std::size_t(nf), 0);
  // The fragments across f's interior edges (on its oriented plane), for the disks.
  auto neighbours = [&](int f, auto&& visit) {
    const std::uint64_t mine = plane[std::size_t(f)];
    for (int c = faces.begin(f); c < faces.end(f); ++c) {
      if (interior[std::size_t(c)] == 0) continue;
      const int u = faces.vertex[std::size_t(c)], w = faces.vertex[std::size_t(faces.next(f, c))];
      for (int i = start[std::size_t(w)]; i < start[std::size_t(w) + 1]; ++i) {
        const Out& o = by_start[std::size_t(i)];
        if (o.to == u && o.plane == mine && o.face != f) visit(o.face);
      }
    }
  };
  std::optional<DiskGrower> grower;
  std::vector<int> disk;  // per face: the disk it joined (its seed), -1 while free
  FaceList added;
  added.reserve(std::size_t(nf) / 8 + 16, corners / 8 + 64);  // (growing from empty allocates often)
  for (int r = 0; r < nf; ++r) {
    const int b = member_start[std::size_t(r)], e = member_start[std::size_t(r) + 1];
    if (e - b < 2) continue;
    boundary.clear();
    bool simple = true;  // no vertex left by two boundary edges
    int first = -1;      // the loop starts at the smallest vertex (as the sorted edges did)
    for (int m = b; m < e; ++m) {
      const int f = members[std::size_t(m)];
      for (int c = faces.begin(f); c < faces.end(f); ++c) {
        if (interior[std::size_t(c)] != 0) continue;
        const int u = faces.vertex[std::size_t(c)];
        int& slot = leaving[std::size_t(u)];
        if (slot >= 0) simple = false;
        slot = int(boundary.size());
        boundary.push_back({u, faces.vertex[std::size_t(faces.next(f, c))], faces.line[std::size_t(c)]});
        if (first < 0 || u < first) first = u;
      }
    }
    simple = simple && boundary.size() >= 3;
    bool merged = false;
    if (simple) {
      // One loop through every boundary edge: a simple polygon.
      const std::size_t mark = added.vertex.size();
      added.open_face(faces.support[std::size_t(r)], faces.flip[std::size_t(r)] != 0);
      int u = first;
      do {
        const int i = leaving[std::size_t(u)];
        if (i < 0) break;
        added.add_corner(u, boundary[std::size_t(i)].line);
        u = boundary[std::size_t(i)].w;
      } while (u != first && added.vertex.size() - mark <= boundary.size());
      if (added.vertex.size() - mark == boundary.size()) {
        for (int m = b; m < e; ++m) removed[std::size_t(members[std::size_t(m)])] = 1;
        merged = true;
      } else {  // several loops or a broken one: disks below
        added.drop_last_face();
      }
    }
    for (const Boundary& x : boundary) leaving[std::size_t(x.u)] = -1;
    if (merged) continue;
    // With holes (or pinched): as few disks as the greedy growth finds.
    if (!grower) grower.emplace(faces, vertex_count), disk.assign(std::size_t(nf), -1);
    grower->run(std::span<const int>(members.data() + b, std::size_t(e - b)), neighbours, disk, added, removed);
  }
  // The kept faces compacted in place (corners and faces only move towards the front), then
  // the merged ones appended.
  std::size_t at = 0;
  int kept = 0;
  for (int f = 0; f < nf; ++f) {
    if (removed[std::size_t(f)] != 0) continue;
    const int b = faces.begin(f), e = faces.end(f);
    faces.start[std::size_t(kept)] = int(at);
    faces.support[std::size_t(kept)] = faces.support[std::size_t(f)];
    faces.flip[std::size_t(kept)] = faces.flip[std::size_t(f)];
    ++kept;
    for (int c = b; c < e; ++c, ++at) {
      faces.vertex[at] = faces.vertex[std::size_t(c)];
      faces.line[at] = faces.line[std::size_t(c)];
    }
  }
  faces.start.resize(std::size_t(kept) + 1);
  faces.start.back() = int(at);
  faces.support.resize(std::size_t(kept));
  faces.flip.resize(std::size_t(kept));
  faces.vertex.resize(at);
  faces.line.resize(at);
  for (int g = 0; g < added.size(); ++g) faces.copy_face(added, g);
  return faces;
}

FaceList remove_straight_vertices(FaceList faces, int vertex_count, const VertexGeometry& geometry) {
  const std::size_t nv = std::size_t(vertex_count);
  // Exactly two distinct neighbours per vertex: keep the first two seen, mark a third.
  std::vector<std::array<int, 2>> seen(nv, {-1, -1});
  std::vector<std::uint8_t> more(nv, 0);
  auto link = [&](int v, int w) {
    auto& sv = seen[std::size_t(v)];
    if (sv[0] == w || sv[1] == w) return;
    if (sv[0] < 0)
      sv[0] = w;
    else if (sv[1] < 0)
      sv[1] = w;
    else
      more[std::size_t(v)] = 1;
  };
  for (int f = 0; f < faces.size(); ++f)
    for (int c = faces.begin(f); c < faces.end(f); ++c) {
      const int u = faces.vertex[std::size_t(c)], w = faces.vertex[std::size_t(faces.next(f, c))];
      link(u, w);
      link(w, u);
    }
  std::vector<std::uint8_t> removable(nv, 0);
  bool any = false;
  for (std::size_t v = 0; v < nv; ++v) any |= (removable[v] = seen[v][1] >= 0 && more[v] == 0) != 0;
  if (!any) return faces;
  // A vertex goes only if it is straight in every face that uses it: the next vertex lies on
  // the line of the incoming edge (support ∩ that edge's plane), decided exactly. (Every vertex
  // of a face lies on its support: fragment corners by construction, T-junction inserts because
  // they were found on the edge's line, merged faces keep their fragments' corners; so only the
  // edge's plane is tested.)
  for (int f = 0; f < faces.size(); ++f) {
    const int m = faces.count(f);
    for (int c = faces.begin(f); c < faces.end(f); ++c) {
      const auto v = std::size_t(faces.vertex[std::size_t(c)]);
      if (removable[v] == 0) continue;
      const int w = faces.vertex[std::size_t(faces.next(f, c))];
      const std::int32_t in_line = faces.line[std::size_t(c == faces.begin(f) ? faces.end(f) - 1 : c - 1)];
      if (m <= 3 || !geometry.on_plane(w, in_line)) removable[v] = 0;
    }
  }
  // The faces compacted in place (corners only move towards the front; faces keep their
  // order and planes).
  std::size_t at = 0;
  for (int f = 0; f < faces.size(); ++f) {
    const int b = faces.begin(f), e = faces.end(f);
    int kept = 0;
    for (int c = b; c < e; ++c) kept += removable[std::size_t(faces.vertex[std::size_t(c)])] == 0;
    const bool all = kept == e - b || kept < 3;
    faces.start[std::size_t(f)] = int(at);
    for (int c = b; c < e; ++c)  // the incoming edge's line goes on
      if (all || removable[std::size_t(faces.vertex[std::size_t(c)])] == 0) {
        faces.vertex[at] = faces.vertex[std::size_t(c)];
        faces.line[at] = faces.line[std::size_t(c)];
        ++at;
      }
  }
  faces.start.back() = int(at);
  faces.vertex.resize(at);
  faces.line.resize(at);
  return faces;
}

}  // namespace sculpt::bsp::detail
