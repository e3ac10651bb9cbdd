#include "render/detail/edges.hpp"

#include <algorithm>

namespace sculpt::render::detail {
namespace {

bool share_vertex(const std::vector<int>& a, const std::vector<int>& b) {
  auto i = a.begin(), j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    if (*i < *j) ++i;
    else ++j;
  }
  return false;
}

}  // namespace

std::vector<bool> edge_pixels(const DepthBuffer& buffer, const std::vector<FaceInfo>& faces, double cos_threshold) {
  std::vector<bool> line(buffer.face.size(), false);
  // Decides the pair of neighbouring pixels p, q (different faces) and marks the nearer one.
  auto consider = [&](std::size_t p, std::size_t q) {
    const int a = buffer.face[p], b = buffer.face[q];
    if (a == b) return;
    const std::size_t nearer = buffer.depth[p] >= buffer.depth[q] ? p : q;
    if (a < 0 || b < 0) {
      line[a < 0 ? q : p] = true;
      return;
    }
    const FaceInfo& fa = faces[static_cast<std::size_t>(a)];
    const FaceInfo& fb = faces[static_cast<std::size_t>(b)];
    if (fa.solid != fb.solid || !share_vertex(fa.vertices, fb.vertices) || fa.normal.dot(fb.normal) < cos_threshold)
      line[nearer] = true;
  };
  for (int y = 0; y < buffer.height; ++y)
    for (int x = 0; x < buffer.width; ++x) {
      const std::size_t p = buffer.index(x, y);
      if (x + 1 < buffer.width) consider(p, p + 1);
      if (y + 1 < buffer.height) consider(p, p + buffer.width);
    }
  return line;
}

std::vector<bool> widen_lines(const DepthBuffer& buffer, const std::vector<bool>& lines, int width) {
  std::vector<bool> wide(lines.size(), false);
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int y = 0; y < buffer.height; ++y)
    for (int x = 0; x < buffer.width; ++x) {
      if (!lines[buffer.index(x, y)]) continue;
      for (int v = std::max(0, y + lo); v <= std::min(buffer.height - 1, y + hi); ++v)
        for (int u = std::max(0, x + lo); u <= std::min(buffer.width - 1, x + hi); ++u)
          if (buffer.face[buffer.index(u, v)] >= 0) wide[buffer.index(u, v)] = true;
    }
  return wide;
}

}  // namespace sculpt::render::detail
