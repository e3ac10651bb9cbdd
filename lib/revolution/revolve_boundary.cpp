#include "revolution/revolve_boundary.hpp"

#include <algorithm>
#include <map>
#include <utility>

#include "revolution/trees/revolve_plane_tree.hpp"

namespace sculpt::revolution {

using namespace detail;  // the trees of trees/
namespace {

class BoundaryBuilder {
 public:
  explicit BoundaryBuilder(const ConvexPath& path) : path_(path), n_(path.edges()) {}

  /// Ring at radius r and height z: n vertices, or a single one on the axis. Shared by key.
  int ring(double r, double z) {
    const auto key = std::make_pair(z, r);
    if (auto it = rings_.find(key); it != rings_.end()) return it->second;
    const int first = static_cast<int>(mesh_.vertices.size());
    if (r == 0.0)
      mesh_.vertices.emplace_back(0.0, 0.0, z);
    else
      for (const auto& v : path_.vertices) mesh_.vertices.emplace_back(r * v.x(), r * v.y(), z);
    rings_[key] = first;
    return first;
  }
  int at(int ring_first, double r, int j) const { return r == 0.0 ? ring_first : ring_first + (j % n_); }

  /// Quad a_j, a_j+1, b_j+1, b_j for every path edge j; a point ring makes it a triangle.
  void band(int a, double ra, int b, double rb, bool reverse) {
    for (int j = 0; j < n_; ++j) {
      std::vector<int> f{at(a, ra, j), at(a, ra, j + 1), at(b, rb, j + 1), at(b, rb, j)};
      if (reverse) std::reverse(f.begin(), f.end());
      std::vector<int> g;
      for (int v : f)
        if (g.empty() || g.back() != v) g.push_back(v);
      if (g.size() > 1 && g.front() == g.back()) g.pop_back();
      if (g.size() >= 3) mesh_.faces.push_back(g);
    }
  }

  /// Face in the level z where the solid's radius goes from r_below to r_above (0: nothing there).
  void level(double z, double r_below, double r_above) {
    if (r_below == r_above) return;
    const bool up = r_below > r_above;  // the solid is below the face's outer part
    const double outer = up ? r_below : r_above, inner = up ? r_above : r_below;
    const int o = ring(outer, z);
    if (inner == 0.0) {  // a cap: one polygon, counter-clockwise seen from above when facing up
      std::vector<int> f;
      for (int j = 0; j < n_; ++j) f.push_back(o + j);
      if (!up) std::reverse(f.begin(), f.end());
      mesh_.faces.push_back(f);
      return;
    }
    band(o, outer, ring(inner, z), inner, !up);
  }

  PolygonMesh take() { return std::move(mesh_); }

 private:
  const ConvexPath& path_;
  int n_;
  PolygonMesh mesh_;
  std::map<std::pair<double, double>, int> rings_;
};

}  // namespace

PolygonMesh revolve_boundary(const std::vector<Eigen::Vector2d>& profile_in, const ConvexPath& path) {
  const std::vector<Eigen::Vector2d> profile = monotone_profile(profile_in);
  const std::vector<RevolveSlab> slabs = revolve_slabs(profile);
  BoundaryBuilder b(path);
  double below = 0.0;  // radius of the solid just below the current level
  for (const RevolveSlab& s : slabs) {
    b.level(s.z0, below, s.r0);
    if (s.r0 != 0.0 || s.r1 != 0.0) b.band(b.ring(s.r0, s.z0), s.r0, b.ring(s.r1, s.z1), s.r1, false);
    below = s.r1;
  }
  b.level(slabs.back().z1, below, 0.0);
  return b.take();
}

double revolved_volume(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path) {
  const double area = path.area();
  double volume = 0.0;
  for (const RevolveSlab& s : revolve_slabs(monotone_profile(profile)))
    volume += (s.z1 - s.z0) / 3.0 * area * (s.r0 * s.r0 + s.r1 * s.r1 + s.r0 * s.r1);
  return volume;
}

}  // namespace sculpt::revolution
