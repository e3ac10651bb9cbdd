#include "bsp/winding_solid.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "bsp/partition/autopartition.hpp"
#include "bsp/tree/node_polygons.hpp"
#include "bsp/tree/solid_access.hpp"
#include "bsp/tree/triangle_fragment.hpp"
#include "kernel/predicates.hpp"
#include "mesh/edge_incidence.hpp"

namespace sculpt {

using kernel::ConvexPolygon;
using kernel::GridPoint;
using kernel::Int128;
using kernel::Side;

namespace {

using bsp::detail::Arena;

/// A leaf cell: the child slot `side` (0 negative, 1 positive) of a node.
inline std::size_t leaf_id(TreeRef node, int side) { return 2 * std::size_t(node) + std::size_t(side); }

/// The mesh is closed when every edge between two snapped points is used as often in one
/// direction as in the other; else the message names up to three unmatched edges.
void expect_closed(const PolygonMesh& mesh, const std::vector<GridPoint>& g) {
  using Key = std::array<std::int64_t, 6>;  // (lo, hi) -> uses lo -> hi minus uses hi -> lo
  std::map<Key, int> balance;
  for (const auto& f : mesh.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const GridPoint& a = g[std::size_t(f[i])];
      const GridPoint& b = g[std::size_t(f[(i + 1) % f.size()])];
      if (a == b) continue;
      if (std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z))
        ++balance[{a.x, a.y, a.z, b.x, b.y, b.z}];
      else
        --balance[{b.x, b.y, b.z, a.x, a.y, a.z}];
    }
  std::size_t open = 0;
  std::ostringstream list;
  for (const auto& [edge, n] : balance) {
    if (n == 0) continue;
    if (++open > 3) continue;
    list << (open > 1 ? "; " : "") << "(" << edge[0] << ", " << edge[1] << ", " << edge[2] << ")-(" << edge[3] << ", "
         << edge[4] << ", " << edge[5] << ")";
  }
  if (open > 0)
    throw GeometryError("positive_winding_solid: the mesh is not closed: " + std::to_string(open) +
                        " edges are not matched by as many uses in the opposite direction (grid units: " + list.str() +
                        (open > 3 ? "; ..." : "") + ")");
}

/// The pieces of `poly` (a polygon in the closure of child slot `side` of `node`) in the leaves of
/// that subtree, each with its leaf cell (explicit stack).
void push_down(Arena& arena, TreeRef node, int side, ConvexPolygon poly,
               std::vector<std::pair<ConvexPolygon, std::size_t>>& out) {
  struct Item {
    ConvexPolygon poly;
    TreeRef parent;
    int side;
  };
  std::vector<Item> stack;
  stack.push_back({std::move(poly), node, side});
  ConvexPolygon neg, pos;
  while (!stack.empty()) {
    Item it = std::move(stack.back());
    stack.pop_back();
    const BspNode& p = arena.nodes[std::size_t(it.parent)];
    const TreeRef child = it.side == 0 ? p.negative : p.positive;
    if (is_leaf(child)) {
      out.emplace_back(std::move(it.poly), leaf_id(it.parent, it.side));
      continue;
    }
    const std::int32_t plane = arena.nodes[std::size_t(child)].plane;
    const Side s = kernel::split(arena.planes, it.poly, plane, arena.opposite(plane), neg, pos);
    switch (s) {
      case Side::Negative:
        stack.push_back({std::move(it.poly), child, 0});
        break;
      case Side::Positive:
        stack.push_back({std::move(it.poly), child, 1});
        break;
      case Side::Both:
        stack.push_back({neg, child, 0});
        stack.push_back({pos, child, 1});
        break;
      case Side::On:
        throw std::logic_error("positive_winding_solid: a polygon lies on a plane below its node");
    }
  }
}

/// A face piece used up at a node and its sign: +1 if its outward normal (corner order) is the
/// node plane's normal (crossing it forwards leaves the face's inside), -1 if opposite.
struct UsedPiece {
  ConvexPolygon poly;
  kernel::CornerBox box;
  int sign;
};

/// The pieces of every fragment at the nodes whose plane they lie on (explicit stack).
std::vector<std::vector<UsedPiece>> used_pieces(Arena& arena, TreeRef root, const FragmentList& fragments) {
  std::vector<std::vector<UsedPiece>> used(arena.nodes.size());
  std::vector<std::pair<ConvexPolygon, TreeRef>> stack;
  ConvexPolygon neg, pos;
  CancelPoll poll;
  for (const FragmentRef f : fragments) {
    stack.emplace_back(ConvexPolygon::copy_of(f.polygon), root);
    while (!stack.empty()) {
      poll.tick();
      auto [poly, at] = std::move(stack.back());
      stack.pop_back();
      if (is_leaf(at)) throw std::logic_error("positive_winding_solid: a face piece reached a leaf");
      const BspNode& n = arena.nodes[std::size_t(at)];
      const kernel::Plane& np = arena.planes[n.plane];
      const kernel::Plane& fp = arena.planes[poly.support];
      if (fp == np || fp == np.opposite()) {
        const kernel::CornerBox box = kernel::corner_box(poly);
        used[std::size_t(at)].push_back({std::move(poly), box, fp == np ? 1 : -1});
        continue;
      }
      const Side s = kernel::split(arena.planes, poly, n.plane, arena.opposite(n.plane), neg, pos);
      switch (s) {
        case Side::Negative:
          stack.emplace_back(std::move(poly), n.negative);
          break;
        case Side::Positive:
          stack.emplace_back(std::move(poly), n.positive);
          break;
        case Side::Both:
          stack.emplace_back(neg, n.negative);
          stack.emplace_back(pos, n.positive);
          break;
        case Side::On:
          throw std::logic_error("positive_winding_solid: a face piece on a plane it is not on");
      }
    }
  }
  return used;
}

bool boxes_apart(const kernel::CornerBox& a, const kernel::CornerBox& b) {
  if (!a.valid || !b.valid) return false;
  for (int i = 0; i < 3; ++i)
    if (a.hi[i] < b.lo[i] || b.hi[i] < a.lo[i]) return true;
  return false;
}

/// The signed number of `faces` that cover the piece `region` (on their plane) at its points:
/// the sum is the same over the whole piece (no face edge runs through the cell pair's interface
/// without changing a side's winding number), so the piece is clipped by each face's edge planes
/// until it lies inside or outside it, and the faces are counted at the points of what is left.
int covering_count(Arena& arena, ConvexPolygon region, const std::vector<UsedPiece>& faces) {
  int count = 0;
  ConvexPolygon neg, pos;
  kernel::CornerBox box = kernel::corner_box(region);
  for (const UsedPiece& face : faces) {
    if (boxes_apart(box, face.box)) continue;
    bool inside = true;
    for (const kernel::Corner& c : face.poly.corners) {
      const Side s = kernel::split(arena.planes, region, c.edge, arena.opposite(c.edge), neg, pos);
      if (s == Side::Negative) continue;
      if (s == Side::Both) {
        region = neg;
        box = kernel::corner_box(region);
        continue;
      }
      inside = false;  // Positive (On cannot happen: the edge planes are transverse to the face)
      break;
    }
    if (inside) count += face.sign;
  }
  return count;
}

}  // namespace

WindingSolid positive_winding_solid(const PolygonMesh& mesh, const WindingSolidOptions& options) {
  check_face_indices(mesh, "positive_winding_solid");
  const kernel::Grid& grid = options.grid;
  WindingSolid result;
  result.solid = Solid::leaf(false, grid);
  std::vector<GridPoint> g;
  g.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) g.push_back(grid.snap(v));
  expect_closed(mesh, g);

  // 1. Every face as a fan of triangles, each on its own plane oriented by its corner order; a fan's
  // triangles have the face's boundary (the diagonals cancel), whatever the face's shape.
  Arena arena;
  FragmentList fragments;
  for (const auto& f : mesh.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const GridPoint v[3] = {g[std::size_t(f[0])], g[std::size_t(f[i])], g[std::size_t(f[i + 1])]};
      const GridPoint u{v[1].x - v[0].x, v[1].y - v[0].y, v[1].z - v[0].z};
      const GridPoint w{v[2].x - v[0].x, v[2].y - v[0].y, v[2].z - v[0].z};
      if (Int128(u.y) * w.z - Int128(u.z) * w.y == 0 && Int128(u.z) * w.x - Int128(u.x) * w.z == 0 &&
          Int128(u.x) * w.y - Int128(u.y) * w.x == 0)
        continue;  // zero area: bounds nothing
      const std::int32_t support = arena.planes.add(kernel::plane_through(v[0], v[1], v[2]));
      fragments.push_back({bsp::detail::triangle_polygon(arena.planes, support, v), false});
    }
  if (fragments.empty()) return result;
  const TreeRef root = bsp::detail::autopartition_into(arena, fragments, {},
                                                       {.split_weight = 3.0,
                                                        .score = bsp::detail::PartitionScore::ExpectedDepth,
                                                        .point_sample = 128,
                                                        .carry_boundary = false});
  if (is_leaf(root)) return result;
  bsp::detail::fill_node_polygons(arena, root);

  // 2. Where leaf cells meet across a node's plane, and the change of the winding number there.
  const std::vector<std::vector<UsedPiece>> used = used_pieces(arena, root, fragments);
  struct Link {
    std::size_t negative, positive;  // leaf cells on the node plane's two sides
    int jump;                        // winding(negative) - winding(positive)
  };
  std::vector<Link> links;
  std::vector<std::pair<ConvexPolygon, std::size_t>> below, across;
  CancelPoll poll;
  for (std::size_t n = 0; n < arena.nodes.size(); ++n) {
    poll.tick();
    below.clear();
    push_down(arena, TreeRef(n), 0, arena.polygons[n], below);
    for (auto& [piece, negative] : below) {
      across.clear();
      push_down(arena, TreeRef(n), 1, std::move(piece), across);
      for (auto& [contact, positive] : across)
        links.push_back({negative, positive, used[n].empty() ? 0 : covering_count(arena, std::move(contact), used[n])});
    }
  }

  // 3. Winding numbers from the leaf that holds a point beyond the mesh's box (0 there).
  std::vector<std::vector<std::size_t>> at(2 * arena.nodes.size());  // links of each leaf cell
  for (std::size_t i = 0; i < links.size(); ++i) {
    at[links[i].negative].push_back(i);
    at[links[i].positive].push_back(i);
  }
  GridPoint far = g[0];
  for (const GridPoint& p : g) far = {std::max(far.x, p.x), std::max(far.y, p.y), std::max(far.z, p.z)};
  far = {far.x + 1, far.y + 1, far.z + 1};
  TreeRef node = root;
  std::size_t start = 0;
  for (;;) {
    const BspNode& nd = arena.nodes[std::size_t(node)];
    const int side = kernel::orient(far, arena.planes[nd.plane]) == kernel::Sign::Positive ? 1 : 0;
    const TreeRef child = side == 0 ? nd.negative : nd.positive;
    if (is_leaf(child)) {
      start = leaf_id(node, side);
      break;
    }
    node = child;
  }
  constexpr int kUnknown = std::numeric_limits<int>::min();
  std::vector<int> winding(at.size(), kUnknown);
  winding[start] = 0;
  std::deque<std::size_t> queue{start};
  while (!queue.empty()) {
    const std::size_t leaf = queue.front();
    queue.pop_front();
    for (const std::size_t i : at[leaf]) {
      const Link& l = links[i];
      const bool from_negative = l.negative == leaf;
      const std::size_t other = from_negative ? l.positive : l.negative;
      const int w = from_negative ? winding[leaf] - l.jump : winding[leaf] + l.jump;
      if (winding[other] == kUnknown) {
        winding[other] = w;
        queue.push_back(other);
      } else if (winding[other] != w) {
        throw std::logic_error("positive_winding_solid: winding numbers disagree across a face");
      }
    }
  }
  for (std::size_t n = 0; n < arena.nodes.size(); ++n)
    for (int side = 0; side < 2; ++side) {
      TreeRef& child = side == 0 ? arena.nodes[n].negative : arena.nodes[n].positive;
      if (!is_leaf(child)) continue;
      const int w = winding[leaf_id(TreeRef(n), side)];
      if (w == kUnknown) throw std::logic_error("positive_winding_solid: a leaf cell no face piece reaches");
      ++result.cells;
      result.inside_cells += w > 0;
      result.multiple_cells += w > 1;
      result.negative_cells += w < 0;
      child = w > 0 ? kIn : kOut;
    }
  result.solid = bsp::detail::SolidAccess::at_grid(bsp::detail::compact(arena, root), grid);
  return result;
}

}  // namespace sculpt
