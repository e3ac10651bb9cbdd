#include "reports/cell_clipper.hpp"

#include <algorithm>
#include <cmath>

#include "kernel/grid.hpp"

namespace sculpt::reports {
namespace {

using Face = std::vector<Eigen::Vector3d>;
using Polyhedron = std::vector<Face>;

Polyhedron box_polyhedron(const Eigen::AlignedBox3d& b) {
  const Eigen::Vector3d lo = b.min(), hi = b.max();
  auto v = [&](int i) { return Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z()); };
  const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  Polyhedron p;
  for (const auto& q : f) p.push_back({v(q[0]), v(q[1]), v(q[2]), v(q[3])});
  return p;
}

/// The part of p where n.x + d <= 0 (keep_negative) or >= 0.
Polyhedron clip(const Polyhedron& p, Eigen::Vector3d n, double d, bool keep_negative) {
  if (!keep_negative) {
    n = -n;
    d = -d;
  }
  // Nothing to cut (this also covers a plane through a whole face): all kept or all dropped.
  double lo = 0, hi = 0;
  for (const Face& f : p)
    for (const auto& x : f) {
      lo = std::min(lo, n.dot(x) + d);
      hi = std::max(hi, n.dot(x) + d);
    }
  if (hi <= 0) return p;
  if (lo >= 0) return {};
  Polyhedron out;
  std::vector<Eigen::Vector3d> cut;
  for (const Face& f : p) {
    Face g;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const Eigen::Vector3d& a = f[i];
      const Eigen::Vector3d& b = f[(i + 1) % f.size()];
      const double fa = n.dot(a) + d, fb = n.dot(b) + d;
      if (fa <= 0) g.push_back(a);
      if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
        const Eigen::Vector3d x = a + (b - a) * (fa / (fa - fb));
        g.push_back(x);
        cut.push_back(x);
      } else if (fa == 0) {
        cut.push_back(a);
      }
    }
    if (g.size() >= 3) out.push_back(g);
  }
  if (cut.size() >= 3) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& x : cut) c += x / double(cut.size());
    const Eigen::Vector3d u = n.unitOrthogonal(), w = n.normalized().cross(u);
    std::sort(cut.begin(), cut.end(), [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::atan2((a - c).dot(w), (a - c).dot(u)) < std::atan2((b - c).dot(w), (b - c).dot(u));
    });
    out.push_back(cut);
  }
  return out;
}

double polyhedron_volume(const Polyhedron& p) {
  if (p.size() < 4) return 0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  int count = 0;
  for (const Face& f : p)
    for (const auto& x : f) c += x, ++count;
  c /= count;
  double v = 0;
  for (const Face& f : p) {
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < f.size(); ++i) normal += f[i].cross(f[(i + 1) % f.size()]);
    const double area = 0.5 * normal.norm();
    if (area == 0) continue;
    v += area * std::abs(normal.normalized().dot(f[0] - c)) / 3;
  }
  return v;
}

}  // namespace

std::vector<ClippedCell> clipped_cells(const Solid& solid, const Eigen::AlignedBox3d& box) {
  std::vector<ClippedCell> cells;
  struct Item {
    TreeRef ref;
    int depth;
    Polyhedron cell;
  };
  std::vector<Item> stack{{solid.root(), 0, box_polyhedron(box)}};
  while (!stack.empty()) {
    Item item = std::move(stack.back());
    stack.pop_back();
    if (item.cell.size() < 4) continue;
    if (is_leaf(item.ref)) {
      const double v = polyhedron_volume(item.cell);
      if (v > 0) cells.push_back({v, item.depth, item.ref == kIn});
      continue;
    }
    const BspNode& node = solid.nodes()[std::size_t(item.ref)];
    const kernel::Plane& pl = solid.planes()[node.plane];
    const Eigen::Vector3d n(double(pl.a), double(pl.b), double(pl.c));
    const double d = double(pl.d) * kernel::kGridStep;  // world units
    const double scale = n.norm();
    stack.push_back({node.negative, item.depth + 1, clip(item.cell, n / scale, d / scale, true)});
    stack.push_back({node.positive, item.depth + 1, clip(item.cell, n / scale, d / scale, false)});
  }
  return cells;
}

}  // namespace sculpt::reports
