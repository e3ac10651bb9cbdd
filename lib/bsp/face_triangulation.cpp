#include "bsp/face_triangulation.hpp"

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
    if (!clipped) break;  // numerically stuck: emit the rest as a fan (never expected)
  }
  for (std::size_t i = 1; i + 1 < idx.size(); ++i)
    out.push_back({face[std::size_t(idx[0])], face[std::size_t(idx[i])], face[std::size_t(idx[i + 1])]});
  return out;
}

}  // namespace sculpt::detail
