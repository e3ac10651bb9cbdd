#include "bsp/assembly/face_triangulation.hpp"

#include <cmath>

namespace sculpt::detail {

std::vector<std::array<int, 3>> triangulate_face(const std::vector<Eigen::Vector3d>& points,
                                                 const std::vector<int>& face, const Eigen::Vector3d& normal) {
  std::vector<std::array<int, 3>> out;
  // Project along the dominant axis of the normal, keeping the orientation counter-clockwise.
  int k = 0;
  normal.cwiseAbs().maxCoeff(&k);
  const int u = (k + 1) % 3, v = (k + 2) % 3;
  const double flip = normal[k] < 0 ? -1.0 : 1.0;
  std::vector<Eigen::Vector2d> p;
  for (int i : face) p.emplace_back(points[std::size_t(i)][u], flip * points[std::size_t(i)][v]);
  auto cross = [&](int a, int b, int c) {
    const Eigen::Vector2d e = p[std::size_t(b)] - p[std::size_t(a)], f = p[std::size_t(c)] - p[std::size_t(a)];
    return e.x() * f.y() - e.y() * f.x();
  };
  double scale = 0;
  for (const auto& q : p) scale = std::max(scale, q.cwiseAbs().maxCoeff());
  const double tiny = 1e-14 * scale * scale;  // collinear triples: no zero-area triangles
  std::vector<int> idx(face.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = int(i);
  while (idx.size() > 3) {
    bool clipped = false;
    const std::size_t m = idx.size();
    for (std::size_t i = 0; i < m && !clipped; ++i) {
      const int a = idx[(i + m - 1) % m], b = idx[i], c = idx[(i + 1) % m];
      if (cross(a, b, c) <= tiny) continue;  // reflex or straight corner
      bool empty = true;
      for (std::size_t j = 0; j < m && empty; ++j) {
        const int d = idx[j];
        if (d == a || d == b || d == c || p[std::size_t(d)] == p[std::size_t(a)] || p[std::size_t(d)] == p[std::size_t(b)] ||
            p[std::size_t(d)] == p[std::size_t(c)])
          continue;
        empty = !(cross(a, b, d) >= 0 && cross(b, c, d) >= 0 && cross(c, a, d) >= 0);
      }
      if (!empty) continue;
      out.push_back({face[std::size_t(a)], face[std::size_t(b)], face[std::size_t(c)]});
      idx.erase(idx.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) break;  // every convex ear holds a vertex on its diagonal (collinear runs)
  }
  // The rest as a fan, from an apex that sees every other edge with positive area when there is
  // one (a reflex vertex where collinear runs meet, as in a disc with a quadrant cut out).
  const std::size_t m = idx.size();
  std::size_t apex = 0;
  for (std::size_t r = 0; r < m; ++r) {
    bool good = true;
    for (std::size_t i = 1; i + 1 < m && good; ++i) good = cross(idx[r], idx[(r + i) % m], idx[(r + i + 1) % m]) > tiny;
    if (good) {
      apex = r;
      break;
    }
  }
  if (m == 3 && out.size() > 0) {
    // A last triangle with a straight vertex b (ears were clipped around a collinear run): the
    // diagonal c -> a belongs to an emitted triangle (a, c, x); split it at b instead, as (a, b, x)
    // and (b, c, x), and drop the flat one.
    for (std::size_t r = 0; r < 3; ++r) {
      const int a = idx[r], b = idx[(r + 1) % 3], c = idx[(r + 2) % 3];
      if (cross(a, b, c) > tiny) continue;
      const Eigen::Vector2d ab = p[std::size_t(b)] - p[std::size_t(a)], bc = p[std::size_t(c)] - p[std::size_t(b)];
      if (ab.dot(bc) <= 0) continue;  // b is not between a and c
      for (auto& t : out)
        for (int e = 0; e < 3; ++e)
          if (t[std::size_t(e)] == face[std::size_t(a)] && t[std::size_t((e + 1) % 3)] == face[std::size_t(c)]) {
            const int x = t[std::size_t((e + 2) % 3)];
            t = {face[std::size_t(a)], face[std::size_t(b)], x};
            out.push_back({face[std::size_t(b)], face[std::size_t(c)], x});
            return out;
          }
    }
  }
  for (std::size_t i = 1; i + 1 < m; ++i)
    out.push_back({face[std::size_t(idx[apex])], face[std::size_t(idx[(apex + i) % m])], face[std::size_t(idx[(apex + i + 1) % m])]});
  return out;
}

}  // namespace sculpt::detail
