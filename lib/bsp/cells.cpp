#include "bsp/cells.hpp"

#include <cmath>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "bsp/tree/tree_arena.hpp"

namespace sculpt {

using kernel::ConvexPolygon;
using kernel::Side;

namespace {

// A convex cell as its face polygons (each face plane has the cell on its negative side).
using Cell = std::vector<ConvexPolygon>;

// The part of `cell` on the negative side of plane q (empty if none). The cap on q is q's world
// polygon clipped by every face plane of the cell.
Cell clip(bsp::detail::Arena& a, const Cell& cell, std::int32_t q) {
  const std::int32_t q_opp = a.opposite(q);
  bool any_negative = false, any_positive = false;
  std::vector<kernel::PolygonSplit> parts;
  parts.reserve(cell.size());
  for (const ConvexPolygon& f : cell) {
    parts.push_back(kernel::split(a.planes, f, q, q_opp));
    const Side s = parts.back().side;
    any_negative |= s == Side::Negative || s == Side::Both;
    any_positive |= s == Side::Positive || s == Side::Both;
  }
  if (!any_positive) return cell;  // entirely on the negative side (or touching)
  if (!any_negative) return {};    // entirely on the positive side
  Cell out;
  for (std::size_t i = 0; i < cell.size(); ++i) {
    switch (parts[i].side) {
      case Side::Negative: out.push_back(cell[i]); break;
      case Side::Both: out.push_back(std::move(parts[i].negative)); break;
      case Side::On:
        if (a.planes[cell[i].support] == a.planes[q]) out.push_back(cell[i]);
        break;
      case Side::Positive: break;
    }
  }
  ConvexPolygon cap = kernel::world_polygon(a.planes, q);
  for (const ConvexPolygon& f : cell) {
    const std::int32_t p = f.support;
    kernel::PolygonSplit s = kernel::split(a.planes, cap, p, a.opposite(p));
    if (s.side == Side::Positive || s.side == Side::On) {
      cap.corners.clear();
      break;
    }
    if (s.side == Side::Both) cap = std::move(s.negative);
  }
  if (!cap.empty()) out.push_back(std::move(cap));
  return out;
}

LeafCell to_leaf_cell(const Cell& cell, int depth, bool inside, const kernel::Grid& grid) {
  LeafCell lc;
  lc.depth = depth;
  lc.inside = inside;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int count = 0;
  for (const ConvexPolygon& f : cell) {
    std::vector<int> face;
    for (const auto& c : f.corners) {
      const Eigen::Vector3d p = grid.to_world(Eigen::Vector3d(c.at().x, c.at().y, c.at().z));
      int id = -1;
      for (std::size_t v = 0; v < lc.vertices.size() && id < 0; ++v)
        if ((lc.vertices[v] - p).norm() <= 1e-12 * (grid.unit() + p.norm())) id = int(v);
      if (id < 0) {
        id = int(lc.vertices.size());
        lc.vertices.push_back(p);
      }
      face.push_back(id);
      centre += p;
      ++count;
    }
    lc.faces.push_back(std::move(face));
  }
  centre /= double(std::max(count, 1));
  for (const auto& f : lc.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
      lc.volume += (lc.vertices[std::size_t(f[0])] - centre)
                       .dot((lc.vertices[std::size_t(f[i])] - centre).cross(lc.vertices[std::size_t(f[i + 1])] - centre)) /
                   6.0;
  return lc;
}

}  // namespace

void for_each_leaf_cell(const Solid& solid, const Eigen::AlignedBox3d& box,
                        const std::function<void(LeafCell)>& visit) {
  if (box.isEmpty()) throw InvalidInput("leaf_cells: empty sample box");
  const kernel::GridPoint lo = solid.grid().snap(box.min()), hi = solid.grid().snap(box.max());
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) throw InvalidInput("leaf_cells: sample box thinner than the grid step");
  bsp::detail::Arena a;
  a.copy_planes(solid.planes());
  using kernel::Int128;
  const std::int32_t box_planes[6] = {
      a.planes.add(kernel::make_plane(1, 0, 0, -Int128(hi.x))), a.planes.add(kernel::make_plane(-1, 0, 0, Int128(lo.x))),
      a.planes.add(kernel::make_plane(0, 1, 0, -Int128(hi.y))), a.planes.add(kernel::make_plane(0, -1, 0, Int128(lo.y))),
      a.planes.add(kernel::make_plane(0, 0, 1, -Int128(hi.z))), a.planes.add(kernel::make_plane(0, 0, -1, Int128(lo.z)))};
  Cell start;
  for (std::int32_t p : box_planes) {
    ConvexPolygon f = kernel::world_polygon(a.planes, p);
    for (std::int32_t q : box_planes) {
      if (q == p) continue;
      kernel::PolygonSplit s = kernel::split(a.planes, f, q, a.opposite(q));
      if (s.side == Side::Both) f = std::move(s.negative);
    }
    start.push_back(std::move(f));
  }
  struct Frame {
    TreeRef t;
    Cell cell;
    int depth;
  };
  std::vector<Frame> stack;
  stack.push_back({solid.root(), std::move(start), 0});
  CancelPoll poll;
  while (!stack.empty()) {
    poll.tick();  // Ctrl-C (base/cancel.hpp)
    Frame f = std::move(stack.back());
    stack.pop_back();
    if (is_leaf(f.t)) {
      visit(to_leaf_cell(f.cell, f.depth, f.t == kIn, solid.grid()));
      continue;
    }
    const BspNode& n = solid.nodes()[std::size_t(f.t)];
    Cell neg = clip(a, f.cell, n.plane);
    Cell pos = clip(a, f.cell, a.opposite(n.plane));
    if (!neg.empty()) stack.push_back({n.negative, std::move(neg), f.depth + 1});
    if (!pos.empty()) stack.push_back({n.positive, std::move(pos), f.depth + 1});
  }
}

std::vector<LeafCell> leaf_cells(const Solid& solid, const Eigen::AlignedBox3d& box) {
  std::vector<LeafCell> out;
  for_each_leaf_cell(solid, box, [&](LeafCell cell) { out.push_back(std::move(cell)); });
  return out;
}

}  // namespace sculpt
