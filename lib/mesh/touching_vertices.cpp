#include "mesh/touching_vertices.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <Eigen/Geometry>

#include "base/cancel.hpp"
#include "base/parallel.hpp"
#include "mesh/detail/box_grid.hpp"
#include "mesh/predicates.hpp"
#include "mesh/triangulate.hpp"

namespace sculpt {
namespace {

using V3 = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

/// Rounds of search and insertion: a face that gets a fan in one round is searched again in the
/// next, for a second vertex inside it (now inside one of the fan's triangles or on its edges).
constexpr int kMaxRounds = 8;

/// A vertex touching a face: inside it (edge = -1), or inside its edge from corner `edge` to the
/// next corner.
struct Contact {
  int face, vertex, edge;
};

/// A face seen in the coordinate plane that drops the largest component of its (Newell) normal;
/// `flip` when the projection turns its counter-clockwise order clockwise.
struct Projection {
  int x = 0, y = 1;
  bool flip = false;
  [[nodiscard]] V2 of(const V3& p) const { return {p[x], p[y]}; }
};

Projection projection_of(const PolygonMesh& m, const std::vector<int>& f) {
  V3 n = V3::Zero();
  for (size_t i = 0; i < f.size(); ++i) {
    const V3& a = m.vertices[size_t(f[i])];
    const V3& b = m.vertices[size_t(f[(i + 1) % f.size()])];
    n += V3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
  }
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  return {.x = (axis + 1) % 3, .y = (axis + 2) % 3, .flip = n[axis] < 0};
}

enum class Where { Outside, Inside, InsideNotStar, OnEdge };

/// Where vertex v lies against face f (v is on f's plane and at none of its corners), decided
/// exactly in the projection (one to one on the plane: checked by the caller). Inside means
/// strictly inside and every edge sees v strictly on its inner side, so that the fan of
/// triangles from v to the edges tiles the face; `edge` is set for OnEdge.
Where locate(const PolygonMesh& m, const std::vector<int>& f, const Projection& pr, const V2& q, int& edge) {
  int winding = 0;
  bool star = true;
  for (size_t i = 0; i < f.size(); ++i) {
    const V2 p = pr.of(m.vertices[size_t(f[i])]), r = pr.of(m.vertices[size_t(f[(i + 1) % f.size()])]);
    const int s = orient2d(p, r, q);
    if (s == 0) {
      const int c = p.x() != r.x() ? 0 : 1;  // a coordinate in which the edge's ends differ
      if (std::min(p[c], r[c]) < q[c] && q[c] < std::max(p[c], r[c])) {
        edge = int(i);
        return Where::OnEdge;
      }
    }
    if ((pr.flip ? -s : s) <= 0) star = false;
    // Winding number by upward and downward crossings (exact: only comparisons and orient2d).
    if (p.y() <= q.y()) {
      if (r.y() > q.y() && s > 0) ++winding;
    } else if (r.y() <= q.y() && s < 0) {
      --winding;
    }
  }
  if (winding == 0) return Where::Outside;
  return star ? Where::Inside : Where::InsideNotStar;
}

/// What the tests against one face need: its projection and three corners whose projections are
/// not collinear (so the projection is one to one on the plane they span, which is the face's:
/// exact faces are planar); `third` is 0 for a degenerate face.
struct FacePlane {
  Projection projection;
  size_t third = 0;
};

FacePlane face_plane(const PolygonMesh& m, const std::vector<int>& face) {
  FacePlane fp{projection_of(m, face), 2};
  const Projection& pr = fp.projection;
  const V2 a = pr.of(m.vertices[size_t(face[0])]), b = pr.of(m.vertices[size_t(face[1])]);
  while (fp.third < face.size() && orient2d(a, b, pr.of(m.vertices[size_t(face[fp.third])])) == 0) ++fp.third;
  if (fp.third == face.size()) fp.third = 0;  // degenerate (cannot happen for an exact boundary)
  return fp;
}

/// Where vertex v touches face f, if it does. Its own corners first (a face's box holds them, and
/// on the face's plane the filter cannot decide: each took an exact orient3d), then the plane
/// test (constant time; almost every other pair ends there), then copies of the corners, then the
/// position in the face.
std::optional<Contact> contact(const PolygonMesh& m, int f, const FacePlane& fp, int v, int& left) {
  if (fp.third == 0) return std::nullopt;
  const std::vector<int>& face = m.faces[size_t(f)];
  if (std::find(face.begin(), face.end(), v) != face.end()) return std::nullopt;  // a corner
  const V3& x = m.vertices[size_t(v)];
  const V3 &pa = m.vertices[size_t(face[0])], &pb = m.vertices[size_t(face[1])],
           &pc = m.vertices[size_t(face[fp.third])];
  const int side = orient3d_filtered(pa, pb, pc, x);
  if (side != kUndecided || orient3d(pa, pb, pc, x) != 0) return std::nullopt;  // off the plane
  for (const int c : face)
    if (m.vertices[size_t(c)] == x) return std::nullopt;  // a copy of a corner
  const Projection& pr = fp.projection;
  int edge = -1;
  switch (locate(m, face, pr, pr.of(x), edge)) {
    case Where::Outside:
      return std::nullopt;
    case Where::Inside:
      return Contact{f, v, -1};
    case Where::OnEdge:
      return Contact{f, v, edge};
    case Where::InsideNotStar:
      ++left;
      return std::nullopt;
  }
  return std::nullopt;
}

/// Every contact of an exact vertex with a face whose corners are all exact (the boxes of faces
/// and of vertices through one grid: each vertex-face pair whose boxes meet is tested once).
std::vector<Contact> find_contacts(const PolygonMesh& m, const std::vector<char>& exact, int& left) {
  const size_t nv = m.vertices.size();
  std::vector<char> used(nv, 0);
  std::vector<int> faces;
  for (size_t f = 0; f < m.faces.size(); ++f) {
    bool all_exact = m.faces[f].size() >= 3;
    for (const int v : m.faces[f]) {
      used[size_t(v)] = 1;
      all_exact = all_exact && exact[size_t(v)] != 0;
    }
    if (all_exact) faces.push_back(int(f));
  }
  std::vector<int> vertices;
  for (size_t v = 0; v < nv; ++v)
    if (exact[v] != 0 && used[v] != 0) vertices.push_back(int(v));
  if (faces.empty() || vertices.empty()) return {};
  std::vector<Eigen::AlignedBox3d> boxes;
  boxes.reserve(faces.size() + vertices.size());
  for (const int f : faces) {
    Eigen::AlignedBox3d box;
    for (const int v : m.faces[size_t(f)]) box.extend(m.vertices[size_t(v)]);
    boxes.push_back(box);
  }
  for (const int v : vertices) boxes.emplace_back(m.vertices[size_t(v)], m.vertices[size_t(v)]);
  const mesh::detail::BoxGrid grid(boxes);
  const int nf = int(faces.size());
  std::vector<FacePlane> planes(faces.size());
  constexpr size_t kFaceChunk = 4096, kCellChunk = 1024;
  parallel_chunks(faces.size(), kFaceChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) planes[i] = face_plane(m, m.faces[size_t(faces[i])]);
  });
  // The cells in chunks on every core, each chunk's contacts and count kept apart and joined in
  // cell order: the same contacts, in the same order, for any thread count.
  const size_t chunks = (grid.cells() + kCellChunk - 1) / kCellChunk;
  std::vector<std::vector<Contact>> found(chunks);
  std::vector<int> lefts(chunks, 0);
  parallel_chunks(grid.cells(), kCellChunk, [&](size_t begin, size_t end) {
    std::vector<Contact>& out = found[begin / kCellChunk];
    int& mine = lefts[begin / kCellChunk];
    CancelPoll poll;
    for (size_t k = begin; k < end; ++k) {
      const std::span<const int> members = grid.cell(k);  // ascending: faces first, then vertices
      const auto split = std::lower_bound(members.begin(), members.end(), nf);
      for (auto vi = split; vi != members.end(); ++vi)
        for (auto fj = members.begin(); fj != split; ++fj) {
          poll.tick();
          const int v = vertices[size_t(*vi - nf)];
          if (!boxes[size_t(*fj)].contains(m.vertices[size_t(v)]) || !grid.owns(k, *fj, *vi)) continue;
          if (const std::optional<Contact> c = contact(m, faces[size_t(*fj)], planes[size_t(*fj)], v, mine))
            out.push_back(*c);
        }
    }
  });
  std::vector<Contact> out;
  for (size_t c = 0; c < chunks; ++c) {
    out.insert(out.end(), found[c].begin(), found[c].end());
    left += lefts[c];
  }
  return out;
}

std::uint64_t edge_key(int u, int w) { return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(w); }

/// Applies one round's contacts: each edge contact to both faces along the edge (one copy of the
/// vertex for the pair), then one inside contact per face not changed yet (a fan around a new
/// copy). False if nothing could be applied.
bool apply(PolygonMesh& m, std::vector<char>& exact, const std::vector<Contact>& contacts, bool triangles,
           TouchingVertices& report) {
  std::unordered_map<std::uint64_t, std::pair<int, int>> half_edges;  // (u, w) -> (face, corner)
  half_edges.reserve(4 * m.faces.size());
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (size_t c = 0; c < m.faces[f].size(); ++c)
      half_edges.emplace(edge_key(m.faces[f][c], m.faces[f][(c + 1) % m.faces[f].size()]), std::pair(int(f), int(c)));
  auto copy_of = [&](int v) {
    m.vertices.push_back(m.vertices[size_t(v)]);
    exact.push_back(1);
    return int(m.vertices.size()) - 1;
  };
  std::vector<char> touched(m.faces.size(), 0);
  std::map<int, std::vector<std::pair<int, int>>> inserts;  // face -> (corner, vertex to insert after it)
  std::map<std::tuple<int, int, int>, int> done;            // (vertex, lower end, higher end) -> its copy
  for (const Contact& c : contacts) {
    if (c.edge < 0) continue;
    const std::vector<int>& face = m.faces[size_t(c.face)];
    const int u = face[size_t(c.edge)], w = face[(size_t(c.edge) + 1) % face.size()];
    const auto key = std::tuple(c.vertex, std::min(u, w), std::max(u, w));
    if (done.contains(key)) continue;  // found from the face on the other side too
    const auto opposite = half_edges.find(edge_key(w, u));
    if (opposite == half_edges.end()) continue;  // an open edge: not a closed solid's boundary
    const int copy = copy_of(c.vertex);
    done.emplace(key, copy);
    inserts[c.face].emplace_back(c.edge, copy);
    inserts[opposite->second.first].emplace_back(opposite->second.second, copy);
    touched[size_t(c.face)] = touched[size_t(opposite->second.first)] = 1;
    ++report.into_edges;
  }
  std::vector<std::pair<int, int>> fans;  // (face, copy at its centre)
  for (const Contact& c : contacts)
    if (c.edge < 0 && touched[size_t(c.face)] == 0) {
      touched[size_t(c.face)] = 1;
      fans.emplace_back(c.face, copy_of(c.vertex));
      ++report.into_faces;
    }
  if (inserts.empty() && fans.empty()) return false;

  PolygonTriangulator triangulator;
  std::vector<IndexTriangle> pieces;
  auto replace = [&](int f, std::vector<std::vector<int>> made) {
    m.faces[size_t(f)] = std::move(made.front());
    for (size_t i = 1; i < made.size(); ++i) m.faces.push_back(std::move(made[i]));
  };
  for (auto& [f, list] : inserts) {
    const std::vector<int> face = m.faces[size_t(f)];
    std::vector<int> grown;
    for (size_t k = 0; k < face.size(); ++k) {
      grown.push_back(face[k]);
      // The copies inside the edge from corner k, in order from its start: along a coordinate in
      // which its ends differ (exact comparisons of the copies' coordinates).
      const V3 &a = m.vertices[size_t(face[k])], &b = m.vertices[size_t(face[(k + 1) % face.size()])];
      const int axis = a.x() != b.x() ? 0 : a.y() != b.y() ? 1 : 2;
      std::vector<int> here;
      for (const auto& [corner, copy] : list)
        if (size_t(corner) == k) here.push_back(copy);
      std::sort(here.begin(), here.end(), [&](int p, int q) {
        return (b[axis] > a[axis]) == (m.vertices[size_t(p)][axis] < m.vertices[size_t(q)][axis]);
      });
      grown.insert(grown.end(), here.begin(), here.end());
    }
    if (!triangles) {
      replace(f, {std::move(grown)});
      continue;
    }
    pieces.clear();
    triangulator.append(m.vertices, grown, pieces);  // exact ear clipping: no zero-area triangle
    std::vector<std::vector<int>> made;
    for (const IndexTriangle& t : pieces) made.push_back({t[0], t[1], t[2]});
    replace(f, std::move(made));
  }
  for (const auto& [f, centre] : fans) {
    const std::vector<int> face = m.faces[size_t(f)];
    std::vector<std::vector<int>> made;
    for (size_t k = 0; k < face.size(); ++k) made.push_back({centre, face[k], face[(k + 1) % face.size()]});
    replace(f, std::move(made));
  }
  return true;
}

}  // namespace

TouchingVertices insert_touching_vertices(PolygonMesh& mesh, std::vector<char>& exact, bool triangles) {
  TouchingVertices report;
  if (exact.size() != mesh.vertices.size()) return report;
  for (int round = 0; round < kMaxRounds; ++round) {
    int left = 0;
    const std::vector<Contact> contacts = find_contacts(mesh, exact, left);
    report.left = left;
    if (contacts.empty() || !apply(mesh, exact, contacts, triangles, report)) break;
  }
  return report;
}

}  // namespace sculpt
