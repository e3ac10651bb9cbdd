#include "mesh/detail/certified_stars.hpp"

#include <algorithm>
#include <span>
#include <utility>
#include "base/cancel.hpp"

namespace sculpt::mesh::detail {
namespace {

using Eigen::Vector3d;

/// Per vertex id, the projection its star is judged in: the axis of the largest coordinate of its
/// triangles' summed area vectors (only chooses the axis; the tests are exact) and that
/// coordinate's sign (0: none).
struct VertexFrames {
  std::vector<signed char> axis, orientation;
};

/// The frames, and links.start counted (links.turned set from the orientations).
VertexFrames frames_and_starts(const std::vector<StarTriangle>& tris, size_t n, StarLinks& links) {
  std::vector<int>& start = links.start;
  start.assign(n + 1, 0);
  std::vector<Vector3d> normal(n, Vector3d::Zero());
  for (const StarTriangle& t : tris)
    for (int id : t.ids) {
      ++start[size_t(id) + 1];
      normal[size_t(id)] += Vector3d(t.normal[0], t.normal[1], t.normal[2]);
    }
  for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  VertexFrames frames{std::vector<signed char>(n, 0), std::vector<signed char>(n, 0)};
  for (size_t v = 0; v < n; ++v) {
    int k = 0;
    normal[v].cwiseAbs().maxCoeff(&k);
    frames.axis[v] = static_cast<signed char>(k);
    frames.orientation[v] = static_cast<signed char>(normal[v][k] > 0 ? 1 : normal[v][k] < 0 ? -1 : 0);
  }
  links.turned.resize(n);
  for (size_t v = 0; v < n; ++v) links.turned[v] = frames.orientation[v] < 0;
  return frames;
}

/// The link edges' endpoints a -> b form one cycle through distinct vertices (with the winding
/// number 1, several cycles are excluded already): the starts are distinct and are the ends.
/// Pairwise for short links, else sorted (`from`, `to`: scratch).
bool one_cycle(std::span<const StarLinks::Link> edges, std::vector<int>& from, std::vector<int>& to) {
  if (edges.size() <= 16) {
    for (size_t i = 0; i < edges.size(); ++i) {
      int starts = 0, ends = 0;
      for (const StarLinks::Link& l : edges) starts += l.a == edges[i].a ? 1 : 0, ends += l.b == edges[i].a ? 1 : 0;
      if (starts != 1 || ends != 1) return false;
    }
    return true;
  }
  from.clear();
  to.clear();
  for (const StarLinks::Link& l : edges) from.push_back(l.a), to.push_back(l.b);
  std::sort(from.begin(), from.end());
  std::sort(to.begin(), to.end());
  return from == to && std::adjacent_find(from.begin(), from.end()) == from.end();
}

}  // namespace

StarTriangle star_triangle(const PreparedTriangle& t) {
  StarTriangle r;
  r.ids = t.ids;
  const Orient3dPlane plane = plane_of(t);
  for (int k = 0; k < 3; ++k) {
    const double m = plane.minor[k];
    r.normal[size_t(k)] = m;
    r.sign[size_t(k)] = static_cast<signed char>(certified_minor(plane, k) ? (m > 0 ? 1 : -1) : kUndecided);
  }
  return r;
}

CertifiedStars certified_stars(const std::vector<StarTriangle>& tris, const std::vector<Vector3d>& points) {
  const size_t n = points.size();
  CertifiedStars result;
  StarLinks& links = result.links;
  const VertexFrames frames = frames_and_starts(tris, n, links);
  const std::vector<signed char>& axis = frames.axis;
  const std::vector<signed char>& orientation = frames.orientation;
  const std::vector<int>& start = links.start;
  // The link edges a -> b grouped by vertex (turned round where the projection is mirrored, so
  // that the sectors turn left), each vertex's upward crossings counted, failures marked.
  std::vector<StarLinks::Link>& link = links.link;
  link.resize(static_cast<size_t>(start[n]));
  std::vector<int> upward(n, 0);
  std::vector<char> failed(n, 0);
  {
    std::vector<int> next(start.begin(), start.end() - 1);
    for (size_t ti = 0; ti < tris.size(); ++ti)
      for (int k = 0; k < 3; ++k) {
        const StarTriangle& t = tris[ti];
        const size_t v = size_t(t.ids[size_t(k)]);
        const int along = axis[v];
        int sign = t.sign[size_t(along)];
        const Vector3d &pv = points[v], &p1 = points[size_t(t.ids[size_t((k + 1) % 3)])],
                       &p2 = points[size_t(t.ids[size_t((k + 2) % 3)])];
        if (sign == kUndecided) sign = orient2d(drop(pv, along), drop(p1, along), drop(p2, along));
        failed[v] |= static_cast<char>(sign != orientation[v] || orientation[v] == 0);
        int a = t.ids[size_t((k + 1) % 3)], b = t.ids[size_t((k + 2) % 3)];
        const Vector3d *pa = &p1, *pb = &p2;
        if (orientation[v] < 0) std::swap(a, b), std::swap(pa, pb);
        const int height = (along + 2) % 3;  // drop()'s second coordinate
        upward[v] += ((*pa)[height] <= pv[height] && pv[height] < (*pb)[height]) ? 1 : 0;
        link[size_t(next[v]++)] = {int(ti), a, b};
      }
  }
  result.certified.assign(n, 0);
  std::vector<int> from, to;
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  for (size_t v = 0; v < n; ++v) {
    poll.tick();
    if (failed[v] || upward[v] != 1 || start[v + 1] - start[v] < 3) continue;
    if (one_cycle({link.data() + start[v], link.data() + start[v + 1]}, from, to))
      result.certified[v] = static_cast<signed char>(1 + 2 * axis[v] + (orientation[v] > 0 ? 1 : 0));
  }
  return result;
}

}  // namespace sculpt::mesh::detail
