#include "bsp/tree/boundary_fragments.hpp"
#include "base/cancel.hpp"
#include "base/dispose.hpp"
#include "base/parallel.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <span>
#include <tuple>
#include <utility>

#include "bsp/tree/node_polygons.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::Side;

namespace {

// The nodes of a subtree breadth-first (children after parents), with the positions of each
// node's children in that order (0: a leaf; position 0 is the subtree's root, nobody's child).
struct BreadthFirst {
  std::vector<TreeRef> order;
  std::vector<std::array<std::size_t, 2>> children;  // [negative, positive]
};

// `expected`: room made at once (a whole tree: tens of MB that would otherwise be moved while
// they double, between two Ctrl-C checks).
BreadthFirst breadth_first(std::span<const BspNode> nodes, TreeRef root, std::size_t expected = 0) {
  BreadthFirst b;
  b.order.reserve(expected);
  b.children.reserve(expected);
  CancelPoll poll;
  if (!is_leaf(root)) b.order.push_back(root);
  for (std::size_t j = 0; j < b.order.size(); ++j) {
    poll.tick();
    const BspNode& m = nodes[std::size_t(b.order[j])];
    std::array<std::size_t, 2> at{0, 0};
    for (int side = 0; side < 2; ++side) {
      const TreeRef c = side == 0 ? m.negative : m.positive;
      if (is_leaf(c)) continue;
      at[std::size_t(side)] = b.order.size();
      b.order.push_back(c);
    }
    b.children.push_back(at);
  }
  return b;
}

// Pushes node polygons down a tree (nodes `nodes`, planes and their opposites in `arena`).
class Extractor {
 public:
  Extractor(std::span<const BspNode> nodes, const Arena& arena) : nodes_(nodes), arena_(arena) {}

  // Pushes `poly` down the subtree `t` and calls out(piece, in) for every leaf reached.
  template <typename Out>
  void push_down(TreeRef t, ConvexPolygon poly, Out&& out) {
    stack_.clear();
    const kernel::CornerBox box = kernel::corner_box(poly);
    stack_.push_back({t, std::move(poly), box});
    // The polygon on top of the stack descends in place; only splits push a second one. Its
    // corner box is kept with it, so most nodes are passed with one quick box test.
    while (!stack_.empty()) {
      poll_.tick();  // Ctrl-C (base/cancel.hpp)
      Piece& top = stack_.back();
      const TreeRef r = top.at;
      if (is_leaf(r)) {
        out(std::move(top.polygon), r == kIn);
        stack_.pop_back();
        continue;
      }
      const BspNode& n = nodes_[std::size_t(r)];
      const Side quick = kernel::box_side(top.box, arena_.planes[n.plane]);
      if (quick == Side::Negative || quick == Side::Positive) {
        top.at = quick == Side::Negative ? n.negative : n.positive;
        continue;
      }
      const std::int32_t opp = arena_.opposite_of[std::size_t(n.plane)];  // made beforehand
      kernel::PolygonSplit s = kernel::split(arena_.planes, top.polygon, n.plane, opp);
      switch (s.side) {
        case Side::Negative: top.at = n.negative; break;
        case Side::Positive: top.at = n.positive; break;
        case Side::Both: {
          const kernel::CornerBox nb = kernel::corner_box(s.negative), pb = kernel::corner_box(s.positive);
          top = {n.negative, std::move(s.negative), nb};
          stack_.push_back({n.positive, std::move(s.positive), pb});
          break;
        }
        case Side::On: {  // a descendant on the same plane violates the invariant; follow both
          top.at = n.negative;
          Piece copy = top;
          copy.at = n.positive;
          stack_.push_back(std::move(copy));
          break;
        }
      }
    }
  }

  // The boundary pieces on the planes of nodes tree.order[begin, end), polygon(j) giving node
  // tree.order[j]'s sub-hyperplane and size[j] its subtree's node count: each polygon is pushed
  // down both subtrees and the pieces with an in-cell on exactly one side are kept. Every node's
  // opposite plane must be in the arena already (opposites_of_nodes): several extractors then
  // read the arena at once.
  template <typename Polygon>
  void collect(const BreadthFirst& tree, std::span<const std::int32_t> size, std::size_t begin, std::size_t end,
               Polygon&& polygon, FragmentList& out) {
    // The polygon goes first into the smaller subtree, so fewer pieces travel through the larger.
    auto size_of = [&](std::size_t c) { return c ? size[c] : 0; };
    std::vector<std::pair<ConvexPolygon, bool>> negative_pieces;
    for (std::size_t j = begin; j < end; ++j) {
      const BspNode& n = nodes_[std::size_t(tree.order[j])];
      // An auxiliary plane carries no face of any operand, hence no boundary (the boundary of
      // a regularized set operation lies on its operands' boundaries).
      if (arena_.planes.auxiliary(n.plane)) continue;
      const bool neg_first = size_of(tree.children[j][0]) <= size_of(tree.children[j][1]);
      const TreeRef first = neg_first ? n.negative : n.positive, second = neg_first ? n.positive : n.negative;
      negative_pieces.clear();
      push_down(first, polygon(j), [&](ConvexPolygon p, bool in) { negative_pieces.emplace_back(std::move(p), in); });
      for (auto& [piece, first_in] : negative_pieces) {
        const bool fi = first_in;
        push_down(second, std::move(piece), [&](ConvexPolygon p, bool second_in) {
          if (fi != second_in) out.push_back({std::move(p), neg_first ? second_in : fi});
        });
      }
    }
  }

 private:
  std::span<const BspNode> nodes_;
  const Arena& arena_;
  CancelPoll poll_;
  struct Piece {
    TreeRef at;
    ConvexPolygon polygon;
    kernel::CornerBox box;
  };
  std::vector<Piece> stack_;
};

// Node counts of the subtrees of `tree` (children come after parents).
std::vector<std::int32_t> subtree_sizes(const BreadthFirst& tree) {
  std::vector<std::int32_t> size(tree.order.size(), 1);
  for (std::size_t j = tree.order.size(); j-- > 0;)
    for (const std::size_t c : tree.children[j])
      if (c) size[j] += size[c];
  return size;
}

// Adds the opposite of every node's plane to the arena, in the order of `tree`, so that the
// extraction only reads the plane table (and the table's indices do not depend on threads).
void opposites_of_nodes(Arena& arena, std::span<const BspNode> nodes, const BreadthFirst& tree) {
  CancelPoll poll;
  for (const TreeRef t : tree.order) {
    poll.tick();
    (void)arena.opposite(nodes[std::size_t(t)].plane);
  }
}

// Nodes whose polygons one task pushes down (docs/bsp.md, "What runs in parallel"): chunks of
// the breadth-first order; the output is joined in chunk order, the same for any thread count.
constexpr std::size_t kNodesPerChunk = 512;

// The boundary pieces of every node of `tree` (Extractor::collect), the nodes in chunks run in
// parallel; each chunk's pieces go to chunks[k], joined into `out` in order at the end.
template <typename Polygon>
void collect_in_parallel(std::span<const BspNode> nodes, Arena& arena, const BreadthFirst& tree, Polygon&& polygon,
                         std::vector<FragmentList>& chunks, FragmentList& out) {
  opposites_of_nodes(arena, nodes, tree);
  const std::vector<std::int32_t> size = subtree_sizes(tree);
  const std::size_t n = tree.order.size();
  chunks.resize((n + kNodesPerChunk - 1) / kNodesPerChunk);
  parallel_chunks(n, kNodesPerChunk, [&](std::size_t begin, std::size_t end) {
    Extractor(nodes, arena).collect(tree, size, begin, end, polygon, chunks[begin / kNodesPerChunk]);
  });
  std::size_t total = out.size();
  for (const FragmentList& c : chunks) total += c.size();
  out.reserve(total);
  for (FragmentList& c : chunks) out.append(std::move(c));
}

}  // namespace

Fragments boundary_fragments(const Solid& solid) {
  // Nodes reachable from the root (storage may hold unreachable nodes, see Solid).
  const BreadthFirst tree = breadth_first(solid.nodes(), solid.root(), solid.nodes().size());
  Arena arena;
  const PolygonStore* polygons = &solid.polygons();
  if (std::any_of(solid.polygons().begin(), solid.polygons().end(), pending)) {
    arena = with_node_polygons(solid);  // its plane table extends the solid's
    polygons = &arena.polygons;
  } else {
    arena.copy_planes(solid.planes());
  }
  Fragments result;
  std::vector<FragmentList> chunks;
  try {
    collect_in_parallel(
        solid.nodes(), arena, tree, [&](std::size_t j) { return (*polygons)[std::size_t(tree.order[j])]; }, chunks,
        result.fragments);
  } catch (const Cancelled&) {
    // Stopped by Ctrl-C: millions of polygons are freed on another thread (base/dispose.hpp).
    dispose_in_background(std::make_tuple(std::move(arena), std::move(result), std::move(chunks)));
    throw;
  }
  result.planes = std::move(arena.planes);
  return result;
}

FragmentList subtree_boundary(Arena& arena, TreeRef root, std::span<const std::int32_t> path) {
  FragmentList out;
  const BreadthFirst tree = breadth_first(arena.nodes, root);
  if (tree.order.empty()) return out;
  // The subtree's polygons, pending ones computed from their paths (depth-first, parents first).
  std::vector<ConvexPolygon> polygons(tree.order.size());
  struct Frame {
    std::size_t position;  // in tree.order
    std::size_t depth;     // path length of the parent's cell
    std::int32_t add;      // half-space this node adds to its parent's path, -1 at the root
  };
  std::vector<std::int32_t> cell(path.begin(), path.end());
  std::vector<Frame> stack{{0, cell.size(), -1}};
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  while (!stack.empty()) {
    poll.tick();
    const Frame f = stack.back();
    stack.pop_back();
    cell.resize(f.depth);
    if (f.add >= 0) cell.push_back(f.add);
    const TreeRef t = tree.order[f.position];
    const BspNode n = arena.nodes[std::size_t(t)];
    polygons[f.position] =
        pending(arena.polygons[std::size_t(t)]) ? node_polygon(arena, n.plane, cell) : arena.polygons[std::size_t(t)];
    const auto [negative, positive] = tree.children[f.position];
    if (positive) stack.push_back({positive, cell.size(), arena.opposite(n.plane)});
    if (negative) stack.push_back({negative, cell.size(), n.plane});
  }
  // arena.nodes does not change while pieces are pushed (only planes are added).
  std::vector<FragmentList> chunks;
  collect_in_parallel(
      arena.nodes, arena, tree, [&](std::size_t j) { return std::move(polygons[j]); }, chunks, out);
  return out;
}

}  // namespace sculpt::bsp::detail
