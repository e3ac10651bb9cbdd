#include "render/detail/edges.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::render::detail {
namespace {

/// Whether faces a and b can meet between the centres of pixel (x, y) and its right (or lower)
/// neighbour: their depth planes at the midpoint differ by at most half their slopes' difference
/// along the step, plus the slack.
bool continuous(const FaceInfo& a, const FaceInfo& b, int x, int y, bool right, double slack) {
  const double mx = right ? x + 1.0 : x + 0.5, my = right ? y + 0.5 : y + 1.0;
  const double gap = std::abs((a.dx - b.dx) * mx + (a.dy - b.dy) * my + (a.d0 - b.d0));
  const double slopes = right ? std::abs(a.dx - b.dx) : std::abs(a.dy - b.dy);
  return gap <= 0.5 * slopes + slack;
}

/// Clears the crease pixels whose 8-connected group has fewer than `least` pixels and touches no
/// outline pixel: the specks a fine triangulated mesh shows where a sliver's normal turns away.
void drop_specks(const DepthBuffer& buffer, std::vector<bool>& crease, const std::vector<bool>& outline, int least) {
  std::vector<bool> seen(crease.size(), false);
  std::vector<std::size_t> group, stack;
  for (std::size_t start = 0; start < crease.size(); ++start) {
    if (!crease[start] || seen[start]) continue;
    group.clear();
    stack.assign(1, start);
    seen[start] = true;
    bool touches_outline = false;
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      group.push_back(p);
      const int x = static_cast<int>(p % static_cast<std::size_t>(buffer.width));
      const int y = static_cast<int>(p / static_cast<std::size_t>(buffer.width));
      for (int v = std::max(0, y - 1); v <= std::min(buffer.height - 1, y + 1); ++v)
        for (int u = std::max(0, x - 1); u <= std::min(buffer.width - 1, x + 1); ++u) {
          const std::size_t q = buffer.index(u, v);
          touches_outline = touches_outline || outline[q];
          if (crease[q] && !seen[q]) {
            seen[q] = true;
            stack.push_back(q);
          }
        }
    }
    if (!touches_outline && static_cast<int>(group.size()) < least)
      for (std::size_t p : group) crease[p] = false;
  }
}

}  // namespace

std::vector<bool> edge_pixels(const DepthBuffer& buffer, const std::vector<FaceInfo>& faces, double cos_threshold,
                              double depth_slack, int least_crease) {
  // Outlines (silhouettes, occlusion boundaries, borders between solids) and creases (feature
  // edges of a continuous surface) are found apart, so that specks can be told from creases.
  std::vector<bool> line(buffer.face.size(), false), crease(buffer.face.size(), false);
  // Decides the pair of neighbouring pixels p = (x, y) and q (right of or below it, with
  // different faces) and marks the nearer one.
  auto consider = [&](int x, int y, bool right) {
    const std::size_t p = buffer.index(x, y), q = right ? p + 1 : p + static_cast<std::size_t>(buffer.width);
    const int a = buffer.face[p], b = buffer.face[q];
    if (a == b) return;
    const std::size_t nearer = buffer.depth[p] >= buffer.depth[q] ? p : q;
    if (a < 0 || b < 0) {
      line[a < 0 ? q : p] = true;
      return;
    }
    const FaceInfo& fa = faces[static_cast<std::size_t>(a)];
    const FaceInfo& fb = faces[static_cast<std::size_t>(b)];
    if (fa.solid != fb.solid || !continuous(fa, fb, x, y, right, depth_slack))
      line[nearer] = true;
    else if (fa.normal.dot(fb.normal) < cos_threshold)
      crease[nearer] = true;
  };
  for (int y = 0; y < buffer.height; ++y) {
    check_cancel();  // Ctrl-C (base/cancel.hpp), once a row
    for (int x = 0; x < buffer.width; ++x) {
      if (x + 1 < buffer.width) consider(x, y, true);
      if (y + 1 < buffer.height) consider(x, y, false);
    }
  }
  if (least_crease > 1) drop_specks(buffer, crease, line, least_crease);
  for (std::size_t p = 0; p < line.size(); ++p) line[p] = line[p] || crease[p];
  return line;
}

std::vector<bool> widen_lines(const DepthBuffer& buffer, const std::vector<bool>& lines, int width) {
  std::vector<bool> wide(lines.size(), false);
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int y = 0; y < buffer.height; ++y) {
    check_cancel();  // Ctrl-C (base/cancel.hpp), once a row
    for (int x = 0; x < buffer.width; ++x) {
      if (!lines[buffer.index(x, y)]) continue;
      for (int v = std::max(0, y + lo); v <= std::min(buffer.height - 1, y + hi); ++v)
        for (int u = std::max(0, x + lo); u <= std::min(buffer.width - 1, x + hi); ++u)
          if (buffer.face[buffer.index(u, v)] >= 0) wide[buffer.index(u, v)] = true;
    }
  }
  return wide;
}

}  // namespace sculpt::render::detail
