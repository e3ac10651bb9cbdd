#include "revolution/trees/revolve_plane_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::revolution::detail {

void check_profile_point(std::size_t i, const Eigen::Vector2d& p) {
  if (!p.allFinite()) throw InvalidInput("profile point " + std::to_string(i) + " is not finite");
  if (p.x() < 0.0)
    throw InvalidInput("profile point " + std::to_string(i) + " has r = " + std::to_string(p.x()) +
                       " < 0 (profiles live in the half-plane r >= 0)");
}

std::vector<Eigen::Vector2d> monotone_profile(const std::vector<Eigen::Vector2d>& profile) {
  if (profile.size() < 2)
    throw InvalidInput("profile needs at least 2 points, got " + std::to_string(profile.size()));
  int direction = 0, turn = -1;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const auto& p = profile[i];
    check_profile_point(i, p);
    if (i == 0) continue;
    const int s = (p.y() > profile[i - 1].y()) - (p.y() < profile[i - 1].y());
    if (s == 0) continue;
    if (direction == 0) direction = s;
    if (s != direction && turn < 0) turn = static_cast<int>(i) - 1;
  }
  if (direction == 0) throw InvalidInput("profile is flat (all z equal): it encloses no volume");
  if (turn >= 0)
    throw InvalidInput("profile is not monotone in z: it turns at point " + std::to_string(turn) +
                       " (z = " + std::to_string(profile[turn].y()) +
                       "); to revolve the region a profile encloses, close it: end it with its first point, "
                       "or pass closed=true (see docs/revolution.md)");
  std::vector<Eigen::Vector2d> out = profile;
  if (direction < 0) std::reverse(out.begin(), out.end());
  return out;
}

std::vector<RevolveSlab> revolve_slabs(const std::vector<Eigen::Vector2d>& profile) {
  std::vector<RevolveSlab> slabs;
  // Within a run of equal z only the run's first and last radius matter (below / above it).
  for (std::size_t i = 0; i + 1 < profile.size(); ++i)
    if (profile[i + 1].y() > profile[i].y())
      slabs.push_back(segment_slab(profile[i].y(), profile[i + 1].y(), profile[i].x(), profile[i + 1].x()));
  return slabs;
}

std::vector<double> revolve_levels(const std::vector<Eigen::Vector2d>& profile) {
  std::vector<double> levels;
  for (const auto& s : revolve_slabs(profile)) levels.push_back(s.z0);
  levels.push_back(profile.back().y());
  return levels;
}

std::vector<double> slab_levels(const std::vector<RevolveSlab>& slabs) {
  std::vector<double> levels;
  for (const auto& s : slabs) levels.push_back(s.z0);
  if (!slabs.empty()) levels.push_back(slabs.back().z1);
  return levels;
}

Eigen::Vector4d lifted_plane(const ConvexPath& path, int from, int to, const RevolveSlab& slab) {
  const Eigen::Vector2d& p = path.vertices[from];
  const Eigen::Vector2d& q = path.vertices[to];
  const Eigen::Vector2d n(q.y() - p.y(), p.x() - q.x());  // right of p -> q
  const double c = n.dot(p), h = slab.z1 - slab.z0;
  // n.(x, y) = c r(z), r(z) = r0 + (r1 - r0)(z - z0)/h, times h.
  Eigen::Vector4d plane(h * n.x(), h * n.y(), -c * (slab.r1 - slab.r0), -c * (slab.r0 * slab.z1 - slab.r1 * slab.z0));
  return plane / plane.head<3>().norm();
}

PlaneTree revolve_plane_tree(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path,
                             const RevolveOptions& options) {
  return revolve_slab_tree(revolve_slabs(monotone_profile(profile)), path, options);
}

PlaneTree revolve_slab_tree(const std::vector<RevolveSlab>& slabs, const ConvexPath& path,
                            const RevolveOptions& options) {
  const PathTree path_tree = build_path_tree(path, {.face_only_below = options.face_only_below});

  PlaneTree tree;
  // Levels z_0 < ... < z_K (K = slabs); interval 0 is below z_0, interval k + 1 is slab k,
  // interval K + 1 above z_K. Balanced: each range of planes splits at its median.
  const std::vector<double> levels = slab_levels(slabs);

  struct Task {
    int lo, hi;       // planes lo..hi (may be empty: lo > hi), intervals lo..hi+1
    int parent;       // -1: root
    bool above;
  };
  auto attach = [&](const Task& t, int child) {
    if (t.parent < 0)
      tree.root = child;
    else if (t.above)
      tree.nodes[t.parent].above = child;
    else
      tree.nodes[t.parent].below = child;
  };
  auto lift_slab = [&](int k) -> int {  // the subtree of slab k; returns its root reference
    const RevolveSlab& s = slabs[k];
    if (s.r0 == 0.0 && s.r1 == 0.0) return kOut;
    const int base = static_cast<int>(tree.nodes.size());
    auto map = [&](int child) { return child >= 0 ? child + base : child; };
    for (const auto& n : path_tree.nodes)
      tree.nodes.push_back({lifted_plane(path, n.from, n.to, s), map(n.inside), map(n.outside), k, n.from, n.to});
    return map(path_tree.root);
  };

  std::vector<Task> stack{{0, static_cast<int>(levels.size()) - 1, -1, false}};
  while (!stack.empty()) {
    const Task t = stack.back();
    stack.pop_back();
    if (t.lo > t.hi) {
      const int interval = t.lo;  // a single interval remains
      const bool outside = interval == 0 || interval == static_cast<int>(levels.size());
      attach(t, outside ? kOut : lift_slab(interval - 1));
      continue;
    }
    const int mid = (t.lo + t.hi) / 2;
    tree.nodes.push_back({Eigen::Vector4d(0.0, 0.0, 1.0, -levels[mid]), kOut, kOut, -1, mid, -1});
    const int k = static_cast<int>(tree.nodes.size()) - 1;
    attach(t, k);
    stack.push_back({t.lo, mid - 1, k, false});
    stack.push_back({mid + 1, t.hi, k, true});
  }
  return tree;
}

int PlaneTree::classify(const Eigen::Vector3d& p) const {
  int k = root;
  while (k >= 0) {
    const Node& n = nodes[k];
    k = n.plane.head<3>().dot(p) + n.plane[3] > 0.0 ? n.above : n.below;
  }
  return k;
}

int PlaneTree::height() const {
  int best = 0;
  std::vector<std::array<int, 2>> stack;
  if (root >= 0) stack.push_back({root, 1});
  while (!stack.empty()) {
    const auto [k, d] = stack.back();
    stack.pop_back();
    best = std::max(best, d);
    for (int c : {nodes[k].below, nodes[k].above})
      if (c >= 0) stack.push_back({c, d + 1});
  }
  return best;
}

}  // namespace sculpt::revolution::detail
