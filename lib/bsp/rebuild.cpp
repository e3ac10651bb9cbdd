#include "bsp/rebuild.hpp"

#include <algorithm>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/partition/autopartition.hpp"
#include "bsp/partition/mesh_build_options.hpp"
#include "bsp/tree/boundary_fragments.hpp"
#include "bsp/tree/solid_access.hpp"

namespace sculpt {

using bsp::detail::Arena;

Solid rebuild_from_boundary(const Solid& solid) {
  if (is_leaf(solid.root())) return solid;
  Arena arena;
  (void)arena.append(solid);
  FragmentList fragments = arena.boundary_of(solid);
  if (fragments.empty()) return solid;  // no boundary: a leaf in effect
  return bsp::detail::SolidAccess::at_grid(bsp::detail::autopartition(arena, std::move(fragments)), solid.grid());
}

Solid rebuild_from_boundary(const Solid& solid, const FromMeshOptions& options) {
  if (is_leaf(solid.root())) return solid;
  Arena arena;
  (void)arena.append(solid);
  FragmentList fragments = arena.boundary_of(solid);
  if (fragments.empty()) return solid;
  const bsp::detail::AutopartitionOptions build = bsp::detail::mesh_build_options(options);
  return bsp::detail::SolidAccess::at_grid(bsp::detail::autopartition(arena, std::move(fragments), build),
                                           solid.grid());
}

namespace {

// Nodes of the subtree at `t`, counted up to limit + 1.
int count_nodes(const std::vector<BspNode>& nodes, TreeRef t, int limit, std::vector<TreeRef>& stack) {
  int count = 0;
  stack.clear();
  stack.push_back(t);
  while (!stack.empty() && count <= limit) {
    const TreeRef r = stack.back();
    stack.pop_back();
    if (is_leaf(r)) continue;
    ++count;
    stack.push_back(nodes[std::size_t(r)].negative);
    stack.push_back(nodes[std::size_t(r)].positive);
  }
  return count;
}

struct Candidate {
  TreeRef node;
  TreeRef parent;  // -1: the root
  int side;        // of the parent
  int size;
  std::vector<std::int32_t> path;  // half-spaces from the root to the node's cell
};

}  // namespace

Solid rebuild_region(Solid&& solid, const Eigen::AlignedBox3d& region, const RegionRebuildOptions& options,
                     RegionRebuildStats* stats) {
  RegionRebuildStats local;
  RegionRebuildStats& st = stats ? *stats : local;
  st = {};
  if (is_leaf(solid.root()) || region.isEmpty()) return std::move(solid);
  if (solid.has_boundary()) {  // the tree's nodes per fragment, without reading the tree
    const std::size_t live = solid.nodes().size() - bsp::detail::SolidAccess::free_slots(solid).nodes.size();
    if (double(live) <= options.above_nodes_per_fragment * double(solid.boundary().size())) return std::move(solid);
  }
  const kernel::Grid grid = solid.grid();
  kernel::CornerBox box;  // the region in grid units, widened by a step (box_side is conservative)
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = grid.to_grid(region.min()[a]) - 1.0;
    box.hi[a] = grid.to_grid(region.max()[a]) + 1.0;
  }
  box.valid = true;

  Arena arena;
  TreeRef root = arena.adopt(std::move(solid));
  const bsp::detail::AddedStorage added{.first_plane = arena.planes.size(), .first_node = arena.nodes.size()};
  bsp::detail::WrittenStorage written;  // the rebuilt subtrees' parents and roots
  written.boundary_changed_from = arena.boundary ? arena.boundary->size() : 0;  // the boundary is not written

  // Candidates: the highest subtrees meeting the region with at most max_subtree_nodes nodes.
  std::vector<Candidate> candidates;
  {
    struct Frame {
      TreeRef node, parent;
      int side;
      std::size_t depth;
      std::int32_t add;
    };
    std::vector<std::int32_t> path;
    std::vector<Frame> stack{{root, -1, 0, 0, -1}};
    std::vector<TreeRef> scratch;
    while (!stack.empty()) {
      const Frame f = stack.back();
      stack.pop_back();
      path.resize(f.depth);
      if (f.add >= 0) path.push_back(f.add);
      const int size = count_nodes(arena.nodes, f.node, options.max_subtree_nodes, scratch);
      if (size <= options.max_subtree_nodes) {
        if (size >= options.min_subtree_nodes) candidates.push_back({f.node, f.parent, f.side, size, path});
        continue;
      }
      const BspNode n = arena.nodes[std::size_t(f.node)];
      const kernel::Side s = kernel::box_side(box, arena.planes[n.plane]);
      if (!is_leaf(n.positive) && s != kernel::Side::Negative)
        stack.push_back({n.positive, f.node, 1, path.size(), arena.opposite(n.plane)});
      if (!is_leaf(n.negative) && s != kernel::Side::Positive)
        stack.push_back({n.negative, f.node, 0, path.size(), n.plane});
    }
  }
  st.candidates = int(candidates.size());
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.size > b.size; });

  // Each chosen subtree from the boundary in its cell; the candidates are disjoint subtrees.
  int budget = options.max_nodes;
  for (const Candidate& c : candidates) {
    if (c.size > budget) continue;
    budget -= c.size;
    const FragmentList fragments = bsp::detail::subtree_boundary(arena, c.node, c.path);
    if (fragments.empty()) continue;  // no boundary in the cell: left as it is
    // A tree from n fragments has about 0.55-0.8 n nodes (the goblet's strokes): a subtree with
    // about as many nodes as fragments is not rebuilt (that would not reach keep_below).
    if (double(fragments.size()) * options.nodes_per_fragment > options.keep_below * double(c.size)) continue;
    const std::size_t before = arena.nodes.size();
    const TreeRef made = bsp::detail::autopartition_into(arena, fragments, c.path);
    const auto made_nodes = int(arena.nodes.size() - before);
    if (is_leaf(made) || double(made_nodes) > options.keep_below * double(c.size)) {
      arena.nodes.resize(before);  // not worth it (planes it added nothing refers to: reclaimed)
      arena.polygons.resize(before);
      continue;
    }
    if (c.parent < 0) {
      root = made;
    } else {
      BspNode& p = arena.nodes[std::size_t(c.parent)];
      (c.side == 0 ? p.negative : p.positive) = made;
      // Written nodes are listed once (reclaim_added forwards their children's indices): two
      // rebuilt siblings share their parent.
      if (std::find(written.merged.begin(), written.merged.end(), c.parent) == written.merged.end())
        written.merged.push_back(c.parent);
    }
    written.dropped.push_back(c.node);
    ++st.rebuilt;
    st.nodes_before += c.size;
    st.nodes_after += made_nodes;
  }
  return bsp::detail::SolidAccess::at_grid(
      bsp::detail::finish_in_place(arena, bsp::detail::reclaim_added(arena, root, added, written)), grid);
}

Solid rebuild_region(Solid&& solid, const Solid& near, const RegionRebuildOptions& options, RegionRebuildStats* stats) {
  Eigen::AlignedBox3d box;  // grid units of near
  if (near.has_boundary()) {
    for (const FragmentRef f : near.boundary()) {
      const kernel::CornerBox b = kernel::corner_box(f.polygon);
      if (!b.valid) {
        box.setEmpty();
        break;
      }
      box.extend(Eigen::Vector3d(b.lo[0], b.lo[1], b.lo[2])).extend(Eigen::Vector3d(b.hi[0], b.hi[1], b.hi[2]));
    }
  }
  const Eigen::AlignedBox3d region = !box.isEmpty() ? Eigen::AlignedBox3d(near.grid().to_world(box.min()), near.grid().to_world(box.max()))
                                                   : bounding_box(near);
  return rebuild_region(std::move(solid), region, options, stats);
}

}  // namespace sculpt
