#include "bsp/hull.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <Eigen/Core>
#include <optional>
#include <tuple>

#include "bsp/boundary.hpp"
#include "bsp/tree_builder.hpp"
#include "kernel/convex_hull.hpp"
#include "kernel/convex_polygon.hpp"
#include "kernel/plane.hpp"

namespace sculpt {
namespace {

using kernel::GridPoint;
using kernel::Int128;
using kernel::Plane;

constexpr std::size_t kChainFaces = 32;  ///< a cell with at most this many faces is a chain of them
constexpr int kMaxSplitDepth = 48;

/// A cell of the splitting tree: an axis-aligned box [lo, hi] (grid units) and the hull's faces
/// that reach into it; its subtree becomes child `side` of split `parent` (-1: the root).
struct HullCell {
  std::array<std::int64_t, 3> lo, hi;
  std::vector<int> faces;
  int parent = -1;
  int side = 0;  ///< 0: negative child, 1: positive child
  int depth = 0;
};

/// The polytope as a balanced tree (no recursion): axis-aligned auxiliary planes at the median of
/// the faces split the cells (a kd-tree over the faces), and a cell with few faces is the chain of
/// their planes. Inside a convex cell R, P ∩ R is the intersection of R with the half-spaces of
/// the faces that meet R (a point of R outside P leaves P, on the segment from a point of P ∩ R,
/// through a face that meets R); a cell that no face meets is all inside or all outside.
class ConvexTree {
 public:
  ConvexTree(const kernel::ConvexHull& h, const kernel::Grid& grid) : h_(h), grid_(grid) {
    for (const auto& t : h.triangles) planes_.push_back(kernel::plane_through(h.vertices[t[0]], h.vertices[t[1]], h.vertices[t[2]]));
    // A grid point strictly inside: the apex of the cone splits (else the polytope is thinner than
    // the grid somewhere near its centre, and axis-aligned splits are used).
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const GridPoint& v : h.vertices) mean += Eigen::Vector3d(double(v.x), double(v.y), double(v.z));
    mean /= double(h.vertices.size());
    const GridPoint c{std::llround(mean.x()), std::llround(mean.y()), std::llround(mean.z())};
    if (std::all_of(planes_.begin(), planes_.end(), [&](const Plane& p) { return p.eval(c) < 0; })) apex_ = c;
  }

  Solid build() && {
    const std::int64_t w = kernel::PlaneTable::kWorld;
    HullCell root{{-w, -w, -w}, {w, w, w}, {}, -1, 0, 0};
    root.faces.resize(h_.triangles.size());
    for (std::size_t f = 0; f < root.faces.size(); ++f) root.faces[f] = static_cast<int>(f);
    TreeRef top = kOut;
    std::vector<HullCell> stack;
    stack.push_back(std::move(root));
    while (!stack.empty()) {
      HullCell cell = std::move(stack.back());
      stack.pop_back();
      const TreeRef made = subtree(cell, stack);
      if (cell.parent < 0) top = made;
      else (cell.side == 0 ? splits_[cell.parent].negative : splits_[cell.parent].positive) = made;
    }
    for (const Split& s : splits_) b_.set_node(s.node, s.plane, s.negative, s.positive);
    return std::move(b_).build(top, BuildOptions{.grid = grid_});
  }

 private:
  /// The subtree for `cell`: a leaf, a chain, or an opened split node whose two children go on
  /// the stack.
  TreeRef subtree(HullCell& cell, std::vector<HullCell>& stack) {
    if (cell.faces.empty()) return inside(cell) ? kIn : kOut;
    if (cell.faces.size() > kChainFaces && cell.depth < kMaxSplitDepth) {
      std::optional<Plane> plane;
      int axis = -1;
      std::int64_t at = 0;
      if (apex_) {
        plane = cone_split(cell);
      } else if (auto split = choose_split(cell)) {
        std::tie(axis, at) = *split;
        std::array<std::int64_t, 4> n{0, 0, 0, -at};
        n[axis] = 1;
        plane = kernel::make_plane(n[0], n[1], n[2], n[3]);
      }
      if (plane) {
        const int split_index = static_cast<int>(splits_.size());
        HullCell below{cell.lo, cell.hi, {}, split_index, 0, cell.depth + 1}, above = below;
        if (axis >= 0) {
          below.hi[axis] = at;
          above.lo[axis] = at;
        }
        above.side = 1;
        for (int f : cell.faces) {
          bool under = false, over = false;
          for (int k = 0; k < 3; ++k) {
            const Int128 e = plane->eval(h_.vertices[h_.triangles[f][k]]);
            under |= e < 0;
            over |= e > 0;
          }
          if (under || !over) below.faces.push_back(f);  // a face in the plane goes to both sides
          if (over || !under) above.faces.push_back(f);
        }
        // Split only where it pays: faces crossing the plane go to both sides. In cone mode a side
        // without faces cannot happen (each cone meets the boundary); chain rather than guess.
        const bool empty_side = apex_ && (below.faces.empty() || above.faces.empty());
        if (!empty_side && 2 * (below.faces.size() + above.faces.size()) <= 3 * cell.faces.size()) {
          const std::int32_t id = b_.add_plane(*plane, /*auxiliary=*/true);
          const TreeRef node = b_.open_nodes(1);
          splits_.push_back({node, id, kOut, kOut});
          stack.push_back(std::move(below));
          stack.push_back(std::move(above));
          return node;
        }
      }
    }
    std::vector<Plane> planes;
    for (int f : cell.faces) planes.push_back(planes_[f]);
    auto key = [](const Plane& p) { return std::tuple(p.a, p.b, p.c, p.d); };
    std::sort(planes.begin(), planes.end(), [&](const Plane& p, const Plane& q) { return key(p) < key(q); });
    planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
    std::vector<std::int32_t> ids;
    for (const Plane& p : planes) ids.push_back(b_.add_plane(p));
    return b_.add_convex_chain(ids);
  }

  /// A plane through the apex: the coordinate planes for the first three levels (eight octant
  /// cones), then the plane that contains the cell's mean direction and halves its faces' directions
  /// across the widest spread (a sector tree around the apex, as for solids of revolution).
  std::optional<Plane> cone_split(const HullCell& cell) const {
    const GridPoint& c = *apex_;
    if (cell.depth < 3) {
      std::array<std::int64_t, 3> n{0, 0, 0};
      n[cell.depth] = 1;
      return kernel::make_plane(n[0], n[1], n[2], -(Int128(n[0]) * c.x + Int128(n[1]) * c.y + Int128(n[2]) * c.z));
    }
    std::vector<Eigen::Vector3d> u;
    u.reserve(cell.faces.size());
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (int f : cell.faces) {
      Eigen::Vector3d d = -3.0 * Eigen::Vector3d(double(c.x), double(c.y), double(c.z));
      for (int k = 0; k < 3; ++k) {
        const GridPoint& v = h_.vertices[h_.triangles[f][k]];
        d += Eigen::Vector3d(double(v.x), double(v.y), double(v.z));
      }
      u.push_back(d.normalized());
      m += u.back();
    }
    if (!(m.norm() > 0)) return std::nullopt;
    m.normalize();
    // The widest spread across m, then the split angle at the median of the ratios.
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& x : u) {
      const Eigen::Vector3d w = x - x.dot(m) * m;
      cov += w * w.transpose();
    }
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    for (int a = 0; a < 3; ++a)
      if (cov(a, a) > e.dot(cov * e) || e.isZero()) {
        Eigen::Vector3d axis = Eigen::Vector3d::Unit(a);
        axis -= axis.dot(m) * m;
        if (axis.norm() > 1e-9 && (e.isZero() || axis.normalized().dot(cov * axis.normalized()) > e.dot(cov * e)))
          e = axis.normalized();
      }
    if (e.isZero()) return std::nullopt;
    std::vector<double> ratio;
    for (const auto& x : u) ratio.push_back(x.dot(e) / std::max(x.dot(m), 1e-12));
    std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
    const Eigen::Vector3d normal = e - ratio[ratio.size() / 2] * m;
    const double scale = double(1 << 20) / normal.cwiseAbs().maxCoeff();
    const std::int64_t a = std::llround(normal.x() * scale), b = std::llround(normal.y() * scale),
                       cz = std::llround(normal.z() * scale);
    if (a == 0 && b == 0 && cz == 0) return std::nullopt;
    return kernel::make_plane(a, b, cz, -(Int128(a) * c.x + Int128(b) * c.y + Int128(cz) * c.z));
  }

  /// The median of the faces' first corners along the cell's longest side, strictly inside it.
  std::optional<std::pair<int, std::int64_t>> choose_split(const HullCell& cell) const {
    std::array<std::int64_t, 3> lo{cell.hi}, hi{cell.lo};
    for (int f : cell.faces)
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) {
          const std::int64_t c = std::clamp(coordinate(h_.vertices[h_.triangles[f][k]], a), cell.lo[a], cell.hi[a]);
          lo[a] = std::min(lo[a], c);
          hi[a] = std::max(hi[a], c);
        }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    if (hi[axis] - lo[axis] < 2) return std::nullopt;
    std::vector<std::int64_t> c;
    c.reserve(cell.faces.size());
    for (int f : cell.faces) {
      const auto& t = h_.triangles[f];
      c.push_back((coordinate(h_.vertices[t[0]], axis) + coordinate(h_.vertices[t[1]], axis) +
                   coordinate(h_.vertices[t[2]], axis)) / 3);
    }
    std::nth_element(c.begin(), c.begin() + c.size() / 2, c.end());
    const std::int64_t at = std::clamp(c[c.size() / 2], lo[axis] + 1, hi[axis] - 1);
    return std::pair{axis, at};
  }

  /// A cell that no face meets lies wholly inside or outside: test its centre (in half units).
  bool inside(const HullCell& cell) const {
    const Int128 x = Int128(cell.lo[0]) + cell.hi[0], y = Int128(cell.lo[1]) + cell.hi[1], z = Int128(cell.lo[2]) + cell.hi[2];
    for (const Plane& p : planes_)
      if (p.a * x + p.b * y + p.c * z + 2 * p.d > 0) return false;
    return true;
  }

  static std::int64_t coordinate(const GridPoint& p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

  const kernel::ConvexHull& h_;
  kernel::Grid grid_;
  std::vector<Plane> planes_;
  std::optional<GridPoint> apex_;  ///< a grid point strictly inside, if there is one
  TreeBuilder b_;
  struct Split {
    TreeRef node;
    std::int32_t plane;
    TreeRef negative, positive;
  };
  std::vector<Split> splits_;  ///< opened split nodes; their children are set when made
};

}  // namespace

Solid hull(std::span<const Eigen::Vector3d> points, const kernel::Grid& grid) {
  std::vector<GridPoint> snapped;
  snapped.reserve(points.size());
  for (const Eigen::Vector3d& p : points) snapped.push_back(grid.snap(p));
  const kernel::ConvexHull h = kernel::convex_hull(snapped);
  if (h.dimension < 3) return Solid::leaf(false, grid);
  return ConvexTree(h, grid).build();
}

Solid hull(std::span<const Solid> solids) {
  std::vector<Eigen::Vector3d> points;
  Solid common;  // a leaf until the first solid with planes: its grid is the result's
  for (const Solid& s : solids) {
    (void)common_grid(common, s);  // GridMismatch for a second grid
    if (!is_leaf(s.root())) common = s;
    const PolygonMesh m = to_mesh(s, {.clean = false});
    points.insert(points.end(), m.vertices.begin(), m.vertices.end());
  }
  return hull(points, common.grid());
}

}  // namespace sculpt
