#include "bsp/tree_builder.hpp"
#include "base/cancel.hpp"
#include "bsp/tree/solid_access.hpp"

#include <algorithm>

#include <stdexcept>

#include "bsp/tree/node_polygons.hpp"
#include "bsp/tree/tree_arena.hpp"

namespace sculpt {

using kernel::ConvexPolygon;
using kernel::Side;

TreeBuilder::TreeBuilder() = default;

std::int32_t TreeBuilder::add_plane(const kernel::Plane& plane, bool auxiliary) { return planes_.add(plane, auxiliary); }

namespace {

// Room for a set operation in place (set_operations.cpp appends the other operand and the merge's
// copies): reserved address space is not touched until used.
std::size_t room_for(std::size_t nodes) { return nodes + nodes / 2 + 64; }

void check_child(TreeRef c, std::size_t nodes) {
  if (c != kIn && c != kOut && (c < 0 || std::size_t(c) >= nodes)) throw std::out_of_range("TreeBuilder: unknown child");
}

// True if `nodes` is exactly the pre-order layout of the tree at `root`: the root at 0, each node
// followed by its negative subtree, then its positive one, nothing shared or unreachable. By
// induction from the last index: node i's subtree then fills [i, i + size[i]).
bool in_preorder(const std::vector<BspNode>& nodes, TreeRef root) {
  if (root != 0) return false;
  const std::size_t count = nodes.size();
  std::vector<std::uint32_t> size(count);
  for (std::size_t i = count; i-- > 0;) {
    const BspNode& n = nodes[i];
    std::size_t end = i + 1;  // one past the subtree's last node so far
    for (const TreeRef c : {n.negative, n.positive}) {
      if (is_leaf(c)) continue;
      if (std::size_t(c) != end || end >= count) return false;
      end += size[end];
    }
    size[i] = std::uint32_t(end - i);
  }
  return count > 0 && size[0] == count;
}

// The tree at `root` copied depth-first into pre-order (a node shared by two parents is copied for
// each), with room for `room` nodes.
std::vector<BspNode> copy_preorder(const std::vector<BspNode>& from, TreeRef root, std::size_t room) {
  std::vector<BspNode> nodes;
  nodes.reserve(room);
  struct Frame {
    TreeRef source;
    std::int32_t parent;  // copied node whose child receives this one, -1 = the root
    int side;
  };
  std::vector<Frame> stack{{root, -1, 0}};
  while (!stack.empty()) {
    const Frame f = stack.back();
    stack.pop_back();
    TreeRef out = f.source;
    if (!is_leaf(f.source)) {
      const BspNode& n = from[std::size_t(f.source)];
      out = TreeRef(nodes.size());
      nodes.push_back({n.plane, kOut, kOut});
      stack.push_back({n.positive, out, 1});
      stack.push_back({n.negative, out, 0});
    }
    if (f.parent >= 0) (f.side == 0 ? nodes[std::size_t(f.parent)].negative : nodes[std::size_t(f.parent)].positive) = out;
  }
  return nodes;
}

}  // namespace

void TreeBuilder::reserve(std::size_t planes, std::size_t nodes) {
  planes_.reserve(planes);
  nodes_.reserve(room_for(nodes));  // build_as_given keeps this vector and wants that room
}

TreeRef TreeBuilder::add_node(std::int32_t plane, TreeRef negative, TreeRef positive) {
  if (plane < 0 || plane >= planes_.size()) throw std::out_of_range("TreeBuilder: unknown plane");
  for (TreeRef c : {negative, positive}) check_child(c, nodes_.size());
  nodes_.push_back({plane, negative, positive});
  return TreeRef(nodes_.size() - 1);
}

TreeRef TreeBuilder::open_nodes(std::int32_t count) {
  if (count < 0) throw std::out_of_range("TreeBuilder: negative node count");
  const auto first = TreeRef(nodes_.size());
  // Marked unset by plain stores: resize(n, {-1, kOut, kOut}) built each copy on the stack with
  // a byte store and read it back whole (a store-forwarding stall per node, 7 % of sphere(32)).
  nodes_.resize(nodes_.size() + std::size_t(count));
  for (auto n = nodes_.begin() + first; n != nodes_.end(); ++n) *n = {-1, kOut, kOut};
  unset_ += count;
  return first;
}

// set_node's checks failed: which one (set_node is inline in the header, for SectorTree's loops).
void TreeBuilder::reject_node(TreeRef node, std::int32_t plane, TreeRef negative, TreeRef positive) const {
  if (node < 0 || std::size_t(node) >= nodes_.size()) throw std::out_of_range("TreeBuilder: unknown node");
  if (plane < 0 || plane >= planes_.size()) throw std::out_of_range("TreeBuilder: unknown plane");
  for (TreeRef c : {negative, positive}) check_child(c, nodes_.size());
  throw std::logic_error("TreeBuilder: set_node rejected a valid node");
}

TreeRef TreeBuilder::add_convex_chain(const std::vector<std::int32_t>& face_planes, TreeRef inside,
                                      TreeRef outside) {
  TreeRef t = inside;
  for (auto it = face_planes.rbegin(); it != face_planes.rend(); ++it) t = add_node(*it, t, outside);
  return t;
}

Solid TreeBuilder::build(TreeRef root) && { return std::move(*this).build(root, BuildOptions{}); }

Solid TreeBuilder::build(TreeRef root, FragmentList boundary, const BuildOptions& options) && {
  if (unset_ != 0) throw std::logic_error("TreeBuilder: a node made by open_nodes was never set");
  check_child(root, nodes_.size());
  using bsp::detail::SolidAccess;
  if (options.nodes_cut_cells) return SolidAccess::at_grid(std::move(*this).build_as_given(root, std::move(boundary)), options.grid);
  return SolidAccess::at_grid(std::move(*this).build_with(root, std::move(boundary)), options.grid);
}

Solid TreeBuilder::build(TreeRef root, const BuildOptions& options) && {
  if (unset_ != 0) throw std::logic_error("TreeBuilder: a node made by open_nodes was never set");
  check_child(root, nodes_.size());
  using bsp::detail::SolidAccess;
  if (options.nodes_cut_cells) return SolidAccess::at_grid(std::move(*this).build_as_given(root, std::nullopt), options.grid);
  return SolidAccess::at_grid(std::move(*this).build_with(root, std::nullopt), options.grid);
}

// Every node cuts its cell: the tree in pre-order from the root (as laid out, or copied), with
// pending sub-hyperplanes (node_polygons.hpp).
Solid TreeBuilder::build_as_given(TreeRef root, std::optional<FragmentList> boundary) && {
  if (is_leaf(root)) return Solid::leaf(root == kIn);
  const std::size_t room = room_for(nodes_.size());
  std::vector<BspNode> nodes;
  if (in_preorder(nodes_, root)) {  // laid out top-down already (open_nodes): kept as it is
    nodes = std::move(nodes_);
    nodes.reserve(room);
  } else {
    nodes = copy_preorder(nodes_, root, room);
  }
  // Pending sub-hyperplanes: aggregate initialization writes the support and the corners' header
  // only (value initialization would zero each 272-byte polygon first).
  // Straight into the solid's store (a std::vector here was moved element by element into one).
  // Exactly one slot per node: the store grows by blocks that never move, so an in-place
  // operation appending to it copies nothing, and spare slots would cost a small solid most of its
  // memory (16 + 32 + 64 polygons of ~200 bytes for a box's tree of a dozen nodes).
  PolygonStore polygons;
  polygons.reserve(nodes.size());
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp): a large tree's polygons take a while to write
  for (const BspNode& n : nodes) {
    poll.tick();
    polygons.push_back(ConvexPolygon{.support = n.plane, .corners = {}});
  }
  return bsp::detail::SolidAccess::make(std::move(planes_), std::move(nodes), std::move(polygons), 0, bsp::detail::FreeSlots{}, std::move(boundary));
}

Solid TreeBuilder::build_with(TreeRef root, std::optional<FragmentList> boundary) && {
  bsp::detail::Arena arena;
  arena.planes = std::move(planes_);
  // Every builder node is kept at most once (unless shared) and adds its plane's opposite.
  const std::size_t room = room_for(nodes_.size());
  arena.nodes.reserve(room);
  arena.polygons.reserve(room);
  arena.planes.reserve(std::size_t(arena.planes.size()) + nodes_.size());
  arena.opposite_of.reserve(std::size_t(arena.planes.size()) + nodes_.size());
  if (is_leaf(root)) return Solid::leaf(root == kIn);

  // Top-down: each node's sub-hyperplane is its plane's world polygon clipped by the ancestors'
  // half-spaces. A node whose polygon is empty does not cut its cell and is replaced by the
  // child on the cell's side; the witness for that side is the nearest kept ancestor's polygon,
  // which lies on the cell's boundary (or the origin, inside the world box, at the root).
  struct Frame {
    TreeRef source;         // builder node or leaf
    std::size_t depth;      // constraints inherited from the ancestors
    std::int32_t add;       // constraint this child adds (plane index), -1 for the root
    std::int32_t parent;    // arena node whose child receives the result, -1 = the root
    int side;               // 0 = negative child, 1 = positive child
  };
  std::vector<std::int32_t> constraints;  // plane indices; the cell is on their negative side
  TreeRef result_root = kOut;
  std::vector<Frame> stack{{root, 0, -1, -1, 0}};
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  while (!stack.empty()) {
    poll.tick();
    const Frame f = stack.back();
    stack.pop_back();
    constraints.resize(f.depth);
    if (f.add >= 0) constraints.push_back(f.add);
    TreeRef src = f.source;
    TreeRef out = src;
    while (!is_leaf(src)) {
      const BspNode n = nodes_[std::size_t(src)];
      ConvexPolygon poly;
      std::int32_t on = -1;
      const bsp::detail::CellCut cut = bsp::detail::clip_to_cell(arena.planes, n.plane, constraints, poly, on);
      int cell_side = cut == bsp::detail::CellCut::Negative ? -1 : (cut == bsp::detail::CellCut::Positive ? 1 : 0);
      const bool empty = cut == bsp::detail::CellCut::Empty;
      if (on >= 0 && !arena.planes.auxiliary(n.plane)) {  // the ancestor's plane takes over the faces
        arena.planes.set_auxiliary(on, false);
        arena.planes.set_auxiliary(arena.opposite(on), false);
      }
      if (empty) {
        if (f.parent < 0) {
          cell_side = kernel::orient(kernel::GridPoint{}, arena.planes[n.plane]) == kernel::Sign::Negative ? -1 : 1;
        } else {
          const Side ws = kernel::classify(arena.planes, arena.polygons[f.parent], n.plane);
          cell_side = ws == Side::Negative ? -1 : 1;  // On is impossible: the planes differ
        }
      }
      if (cell_side != 0) {
        src = cell_side < 0 ? n.negative : n.positive;
        out = src;
        continue;
      }
      const auto id = std::int32_t(arena.nodes.size());
      arena.nodes.push_back({n.plane, kOut, kOut});
      arena.polygons.push_back(std::move(poly));
      const std::int32_t opp = arena.opposite(n.plane);
      stack.push_back({n.positive, constraints.size(), opp, id, 1});
      stack.push_back({n.negative, constraints.size(), n.plane, id, 0});
      out = id;
      break;
    }
    if (f.parent < 0)
      result_root = out;
    else if (f.side == 0)
      arena.nodes[std::size_t(f.parent)].negative = out;
    else
      arena.nodes[std::size_t(f.parent)].positive = out;
  }
  // Nodes were made top-down, each once, so they are already compact and depth-first with the
  // root first; compaction is needed only where a node's two children are the same leaf.
  const bool collapsible = std::any_of(arena.nodes.begin(), arena.nodes.end(), [](const BspNode& n) {
    return is_leaf(n.negative) && n.negative == n.positive;
  });
  if (collapsible || result_root != 0 || is_leaf(result_root)) {
    arena.boundary = std::move(boundary);
    return bsp::detail::compact(arena, result_root);
  }
  return bsp::detail::SolidAccess::make(std::move(arena.planes), std::move(arena.nodes), std::move(arena.polygons), result_root, bsp::detail::FreeSlots{},
               std::move(boundary));
}

}  // namespace sculpt
