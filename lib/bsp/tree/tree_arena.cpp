#include "bsp/tree/tree_arena.hpp"
#include "base/cancel.hpp"
#include "bsp/tree/solid_access.hpp"

#include <algorithm>
#include <iterator>
#include <limits>

#include "bsp/tree/boundary_fragments.hpp"

#include <utility>

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;

std::int32_t Arena::opposite(std::int32_t i) {
  if (i < branched_at_) return parent_opposite(i);  // never for an arena that is no branch
  // opposite_of[k] is plane k + branched_at_'s.
  const auto own = std::size_t(planes.size() - branched_at_), at = std::size_t(i - branched_at_);
  if (opposite_of.size() < own) {
    if (opposite_of.capacity() < own) opposite_of.reserve(2 * own);
    opposite_of.resize(own, -1);
  }
  if (opposite_of[at] < 0) {
    const kernel::Plane o = planes[i].opposite();
    const std::int32_t j = planes.add(o, planes.auxiliary(i));
    opposite_of.resize(own + 1, -1);
    opposite_of[at] = j;
    opposite_of[std::size_t(j - branched_at_)] = i;
  }
  return opposite_of[at];
}

std::int32_t Arena::parent_opposite(std::int32_t i) {
  if (std::size_t(i) < parent_opposites_->size() && (*parent_opposites_)[std::size_t(i)] >= 0)
    return (*parent_opposites_)[std::size_t(i)];
  for (const auto& [p, q] : parent_opposites_made_)
    if (p == i) return q;
  const std::int32_t j = planes.add(planes[i].opposite(), planes.auxiliary(i));
  parent_opposites_made_.emplace_back(i, j);
  opposite_of.resize(std::size_t(planes.size() - branched_at_), -1);
  opposite_of[std::size_t(j - branched_at_)] = i;
  return j;
}

Arena Arena::branch() const {
  Arena b;
  b.copy_planes(planes);
  b.parent_opposites_ = &opposite_of;
  b.branched_at_ = planes.size();
  return b;
}

Arena::BranchPlanes Arena::added_planes() const {
  BranchPlanes added;
  added.from = branched_at_;
  added.parent_opposites = parent_opposites_made_;
  for (std::int32_t p = branched_at_; p < planes.size(); ++p) {
    added.planes.push_back(planes[p]);
    added.auxiliary.push_back(planes.auxiliary(p) ? 1 : 0);
    const auto k = std::size_t(p - branched_at_);
    added.opposites.push_back(k < opposite_of.size() ? opposite_of[k] : -1);
  }
  return added;
}

Arena::PlaneMap Arena::take_planes(const BranchPlanes& added) {
  PlaneMap map;
  map.from = added.from;
  map.added.reserve(added.planes.size());
  for (std::size_t k = 0; k < added.planes.size(); ++k)
    map.added.push_back(planes.add(added.planes[k], added.auxiliary[k] != 0));
  opposite_of.resize(std::size_t(planes.size()), -1);
  for (std::size_t k = 0; k < added.planes.size(); ++k)
    if (added.opposites[k] >= 0) opposite_of[std::size_t(map.added[k])] = map(added.opposites[k]);
  for (const auto& [p, q] : added.parent_opposites) opposite_of[std::size_t(p)] = map(q);
  return map;
}

void Arena::copy_planes(const kernel::PlaneTable& from) {
  planes = from;  // shares the planes' blocks; the ones the arena writes into are copied then
}

TreeRef Arena::append(const Solid& solid) {
  if (is_leaf(solid.root())) return solid.root();
  const std::int32_t shift = planes.size() - 6;  // the world box planes 0..5 are shared
  last_shift_ = shift;
  auto map = [shift](std::int32_t p) { return p < 6 ? p : p + shift; };
  if (planes.size() == 6)
    planes = solid.planes();  // the first solid: its blocks shared (kernel/plane_table.hpp), none copied
  else
    planes.append(solid.planes(), 6);  // block by block: the table is never copied whole to grow
  const auto node_shift = std::int32_t(nodes.size());
  for (const BspNode& n : solid.nodes())
    nodes.push_back({map(n.plane), is_leaf(n.negative) ? n.negative : n.negative + node_shift,
                     is_leaf(n.positive) ? n.positive : n.positive + node_shift});
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp): a large tree takes a while to copy
  for (const ConvexPolygon& poly : solid.polygons()) {
    poll.tick();
    if (poly.corners.empty()) {  // pending (node_polygons.hpp): the support alone, no corner storage copied
      polygons.push_back(ConvexPolygon{.support = map(poly.support), .corners = {}});
      continue;
    }
    ConvexPolygon& q = polygons.emplace_back(poly);
    q.support = map(q.support);
    for (auto& c : q.corners) c.edge = map(c.edge), c.p = map(c.p), c.q = map(c.q);
  }
  return solid.root() + node_shift;
}

TreeRef Arena::adopt(Solid&& solid) {
  SolidAccess::Storage s = SolidAccess::release(std::move(solid));
  planes = std::move(s.planes);
  nodes = std::move(s.nodes);
  polygons = std::move(s.polygons);
  opposite_of.clear();
  free = std::move(s.free);
  boundary = std::move(s.boundary);
  boundary_boxes = std::move(s.boundary_boxes);
  last_shift_ = 0;
  return s.root;
}

FragmentList Arena::boundary_of(const Solid& solid) {
  const std::int32_t shift = last_shift_;
  const std::int32_t own = solid.planes().size();
  std::vector<std::int32_t> extra;  // extracted fragments may use opposites beyond the solid's planes
  auto remap = [&](FragmentList& fragments, const kernel::PlaneTable& from) {
    auto map = [&](std::int32_t p) {
      if (p < 6) return p;
      if (p < own) return p + shift;
      const auto k = std::size_t(p - own);
      if (extra.size() <= k) extra.resize(k + 1, -1);
      if (extra[k] < 0) extra[k] = planes.add(from[p], from.auxiliary(p));
      return extra[k];
    };
    fragments.renumber_planes(map);
  };
  if (solid.has_boundary()) {
    FragmentList out = solid.boundary();
    if (shift != 0) remap(out, solid.planes());
    return out;
  }
  Fragments f = boundary_fragments(solid);
  remap(f.fragments, f.planes);
  return std::move(f.fragments);
}

void complement_in_place(Arena& arena, TreeRef& root) {
  auto flip = [](TreeRef& r) { r = r == kIn ? kOut : kIn; };
  if (is_leaf(root)) return flip(root);
  std::vector<TreeRef> stack{root};
  while (!stack.empty()) {
    BspNode& n = arena.nodes[stack.back()];
    stack.pop_back();
    for (TreeRef* c : {&n.negative, &n.positive}) {
      if (is_leaf(*c))
        flip(*c);
      else
        stack.push_back(*c);
    }
  }
}

namespace {

// Calls at(p) for the support plane and every corner plane of a polygon.
template <class Polygon, class At>
void each_plane(Polygon&& poly, At&& at) {
  at(poly.support);
  for (auto& c : poly.corners) at(c.edge), at(c.p), at(c.q);
}

// A free node slot: referring to plane 0 only (the world box, never freed), no children.
void clear_node(Arena& arena, TreeRef t) {
  arena.nodes[std::size_t(t)] = {0, kOut, kOut};
  arena.polygons[std::size_t(t)] = ConvexPolygon{};
  arena.polygons[std::size_t(t)].support = 0;
}

}  // namespace

Reclaimed reclaim_added(Arena& arena, TreeRef root, const AddedStorage& added, const WrittenStorage& written) {
  const std::size_t n0 = added.first_node;
  const std::int32_t p0 = added.first_plane;
  std::vector<BspNode>& nodes = arena.nodes;
  PolygonStore& polygons = arena.polygons;
  FreeSlots& free = arena.free;
  // 1. The added nodes the result reaches, in pre-order: they hang below the reused nodes of
  // tree a (or are the root); an added node's children are added nodes (partitioned subtrees of
  // the other operand, moved, never shared), so older nodes are not visited.
  const bool nodes_added = nodes.size() > n0;
  std::vector<std::int32_t> node_map(nodes_added ? nodes.size() - n0 : 0, -1);  // pre-order number, later the slot
  std::vector<TreeRef> order;
  std::vector<TreeRef> stack;
  auto is_added = [n0](TreeRef r) { return !is_leaf(r) && std::size_t(r) >= n0; };
  auto push = [&](TreeRef r) {  // -2: on the stack
    if (is_added(r) && node_map[std::size_t(r) - n0] == -1) {
      node_map[std::size_t(r) - n0] = -2;
      stack.push_back(r);
    }
  };
  auto reach = [&](TreeRef from) {
    push(from);
    while (!stack.empty()) {
      const TreeRef t = stack.back();
      stack.pop_back();
      node_map[std::size_t(t) - n0] = std::int32_t(order.size());
      order.push_back(t);
      const BspNode& n = nodes[std::size_t(t)];
      push(n.positive);
      push(n.negative);
    }
  };
  if (nodes_added) {
    reach(root);
    for (const TreeRef t : written.merged) {
      if (std::size_t(t) >= n0) continue;  // not a reused node (reached from the root, if at all)
      reach(nodes[std::size_t(t)].negative);
      reach(nodes[std::size_t(t)].positive);
    }
  }
  // The older nodes the result no longer reaches: reused nodes the merge collapsed (both
  // children the same leaf) and the subtrees of tree a it replaced by a leaf (a tree: nothing
  // else reaches their nodes). They are cleared now (a collapsed node's polygon may have been
  // computed by the merge on planes that go) and become free slots once this operation's nodes
  // are placed. The cost is the number of nodes freed.
  std::vector<TreeRef> freed;
  for (const TreeRef t : written.merged) {
    const BspNode& n = nodes[std::size_t(t)];
    if (std::size_t(t) < n0 && is_leaf(n.negative) && n.negative == n.positive) {
      clear_node(arena, t);
      freed.push_back(t);
    }
  }
  for (const TreeRef d : written.dropped) {
    stack.push_back(d);
    while (!stack.empty()) {
      const TreeRef t = stack.back();
      stack.pop_back();
      if (is_leaf(t) || std::size_t(t) >= n0) continue;  // (added nodes are never below tree a's)
      const BspNode n = nodes[std::size_t(t)];
      stack.push_back(n.negative);
      stack.push_back(n.positive);
      clear_node(arena, t);
      freed.push_back(t);
    }
  }
  // The fragments the operation may have written: changed blocks, and all from a point on.
  FragmentList* fragments = arena.boundary ? &*arena.boundary : nullptr;
  std::vector<std::size_t> fragments_written;  // fragment indices, each once
  if (fragments) {
    const std::size_t count = fragments->size();
    const std::size_t from = added.all_fragments ? 0 : std::min(written.boundary_changed_from, count);
    for (const std::size_t i : written.boundary_changed)
      if (i < from) fragments_written.push_back(i);
    std::sort(fragments_written.begin(), fragments_written.end());
    fragments_written.erase(std::unique(fragments_written.begin(), fragments_written.end()), fragments_written.end());
    for (std::size_t i = from; i < count; ++i) fragments_written.push_back(i);
  }
  // Every reference to a plane the operation may have written: kept added nodes (plane,
  // polygon), the reused nodes' polygons (a pending one the merge computed refers to new
  // opposites), the written fragments.
  auto each_reference = [&](auto&& at) {
    for (const TreeRef t : order) {
      at(nodes[std::size_t(t)].plane);
      each_plane(polygons[std::size_t(t)], at);
    }
    for (const TreeRef t : written.merged)
      if (std::size_t(t) < n0) each_plane(polygons[std::size_t(t)], at);
    for (const std::size_t i : fragments_written)
      fragments->renumber_planes(i, [&](std::int32_t p) {
        at(p);
        return p;
      });
  };
  // While a scan for free planes is in progress, what is written is marked (the scan may have
  // passed its place already).
  std::vector<bool>& marks = free.plane_marked;
  auto mark = [&marks](std::int32_t p) {
    if (std::size_t(p) < marks.size()) marks[std::size_t(p)] = true;
  };
  // 2. The added planes something references are kept; the others are dropped.
  const std::int32_t p1 = arena.planes.size();
  if (p1 > p0) {
    std::vector<std::int32_t> plane_map(std::size_t(p1 - p0), -1);
    each_reference([&](std::int32_t& p) {
      if (p >= p0) plane_map[std::size_t(p - p0)] = 0;
    });
    // The kept ones go to free slots (below p0: nothing refers to them), then in order from p0.
    struct Kept {
      kernel::Plane plane;
      bool auxiliary;
      std::int32_t to;
    };
    std::vector<Kept> kept;
    std::int32_t next = p0;
    for (std::int32_t i = p0; i < p1; ++i)
      if (plane_map[std::size_t(i - p0)] >= 0) {
        std::int32_t to = next;
        if (!free.planes.empty() && free.planes.back() < p0) {
          to = free.planes.back();
          free.planes.pop_back();
        } else {
          ++next;
        }
        plane_map[std::size_t(i - p0)] = to;
        kept.push_back({arena.planes[i], arena.planes.auxiliary(i), to});
      }
    arena.planes.truncate(p0);
    for (const Kept& k : kept)
      if (k.to < p0)
        arena.planes.replace(k.to, k.plane, k.auxiliary);
      else
        arena.planes.add(k.plane, k.auxiliary);
    each_reference([&](std::int32_t& p) {
      if (p >= p0) p = plane_map[std::size_t(p - p0)];
      mark(p);
    });
  } else if (!marks.empty()) {
    each_reference([&](std::int32_t& p) { mark(p); });
  }
  arena.opposite_of.clear();  // indices changed
  // 3. The kept added nodes take free slots, then go to n0 on, in pre-order; references to them
  // rewritten.
  if (nodes_added) {
    std::size_t next = n0;
    for (const TreeRef t : order) {
      std::int32_t to;
      if (!free.nodes.empty()) {
        to = free.nodes.back();
        free.nodes.pop_back();
      } else {
        to = std::int32_t(next++);
      }
      node_map[std::size_t(t) - n0] = to;
    }
    auto forward = [&](TreeRef& r) {
      if (is_added(r)) r = node_map[std::size_t(r) - n0];
    };
    std::vector<BspNode> kept_nodes;
    std::vector<ConvexPolygon> kept_polygons;
    kept_nodes.reserve(order.size());
    kept_polygons.reserve(order.size());
    for (const TreeRef t : order) {
      BspNode n = nodes[std::size_t(t)];
      forward(n.negative);
      forward(n.positive);
      kept_nodes.push_back(n);
      kept_polygons.push_back(std::move(polygons[std::size_t(t)]));
    }
    for (const TreeRef t : written.merged)
      if (std::size_t(t) < n0) forward(nodes[std::size_t(t)].negative), forward(nodes[std::size_t(t)].positive);
    forward(root);
    nodes.resize(n0);
    polygons.resize(n0);
    for (std::size_t i = 0; i < order.size(); ++i) {
      const auto to = std::size_t(node_map[std::size_t(order[i]) - n0]);
      if (to < n0) {
        nodes[to] = kept_nodes[i];
        polygons[to] = std::move(kept_polygons[i]);
      } else {
        nodes.push_back(kept_nodes[i]);
        polygons.push_back(std::move(kept_polygons[i]));
      }
    }
  }
  free.nodes.insert(free.nodes.end(), freed.begin(), freed.end());
  return {root, order.size() + freed.size()};
}

void scan_for_free_planes(Arena& arena, std::size_t budget) {
  FreeSlots& free = arena.free;
  std::vector<bool>& marks = free.plane_marked;
  if (marks.empty()) {  // a new scan
    marks.assign(std::size_t(arena.planes.size()), false);
    free.node_cursor = 0;
    free.fragment_cursor = 0;
  }
  auto mark = [&marks](std::int32_t p) {
    if (std::size_t(p) < marks.size()) marks[std::size_t(p)] = true;
  };
  const std::size_t node_end = std::min(arena.nodes.size(), free.node_cursor + budget);
  for (std::size_t i = free.node_cursor; i < node_end; ++i) {
    mark(arena.nodes[i].plane);
    each_plane(arena.polygons[i], mark);
  }
  budget -= node_end - std::min(node_end, free.node_cursor);
  free.node_cursor = std::max(free.node_cursor, node_end);
  const std::size_t fragment_count = arena.boundary ? arena.boundary->size() : 0;
  const std::size_t fragment_end = std::min(fragment_count, free.fragment_cursor + budget);
  for (std::size_t i = free.fragment_cursor; i < fragment_end; ++i) each_plane((*arena.boundary)[i].polygon, mark);
  free.fragment_cursor = std::max(free.fragment_cursor, fragment_end);
  if (free.node_cursor < arena.nodes.size() || free.fragment_cursor < fragment_count) return;
  // The scan is complete: what it left unmarked nothing refers to.
  free.planes.clear();
  for (std::size_t i = std::size_t(kernel::kWorldPlanes); i < marks.size(); ++i)
    if (!marks[i]) free.planes.push_back(std::int32_t(i));
  marks.clear();
}

Solid finish_in_place(Arena& arena, const Reclaimed& reclaimed) {
  const TreeRef root = reclaimed.root;
  constexpr std::size_t kScanPerNode = 2;
  constexpr std::size_t kMinScanSlice = 512;
  constexpr std::size_t kMinCompactNodes = 4096;
  if (is_leaf(root)) return Solid::leaf(root == kIn);
  if (arena.free.nodes.size() > arena.nodes.size() / 2 && arena.nodes.size() > kMinCompactNodes)
    return compact(arena, root, {.keep_capacity = true});
  scan_for_free_planes(arena, std::max(kMinScanSlice, kScanPerNode * reclaimed.nodes_touched));
  return SolidAccess::make(std::move(arena.planes), std::move(arena.nodes), std::move(arena.polygons), root,
                           std::move(arena.free), std::move(arena.boundary), std::move(arena.boundary_boxes));
}

Solid compact(Arena& arena, TreeRef root, const CompactOptions& options) {
  if (is_leaf(root)) return Solid::leaf(root == kIn);
  // Post-order: a node is emitted after both children, so collapses propagate upwards.
  std::vector<TreeRef> result(arena.nodes.size(), kOut);
  struct Frame {
    TreeRef node;
    bool expanded;
  };
  std::vector<Frame> stack{{root, false}};
  std::vector<BspNode> kept;  // children refer to `result` values (new indices or leaves)
  while (!stack.empty()) {
    Frame f = stack.back();
    stack.pop_back();
    const BspNode& n = arena.nodes[f.node];
    if (!f.expanded) {
      stack.push_back({f.node, true});
      if (!is_leaf(n.positive)) stack.push_back({n.positive, false});
      if (!is_leaf(n.negative)) stack.push_back({n.negative, false});
      continue;
    }
    const TreeRef neg = is_leaf(n.negative) ? n.negative : result[n.negative];
    const TreeRef pos = is_leaf(n.positive) ? n.positive : result[n.positive];
    if (is_leaf(neg) && neg == pos) {
      result[f.node] = neg;
      continue;
    }
    result[f.node] = TreeRef(kept.size());
    kept.push_back({n.plane, neg, pos});
  }
  const TreeRef new_root = result[root];
  if (is_leaf(new_root)) return Solid::leaf(new_root == kIn);

  // Renumber planes: only those used by nodes and polygons survive.
  std::vector<std::int32_t> plane_map(std::size_t(arena.planes.size()), -1);
  kernel::PlaneTable table;
  table.reserve(std::size_t(arena.planes.size()));  // at most all of them: no regrowth while adding
  for (std::int32_t i = 0; i < 6; ++i) plane_map[i] = i;
  auto use = [&](std::int32_t p) {
    if (plane_map[p] < 0) plane_map[p] = table.add(arena.planes[p], arena.planes.auxiliary(p));
    return plane_map[p];
  };
  // Post-order puts the root last; reverse to have the root first (index 0). The arena's own
  // buffers are reused (no new allocation: their pages are already mapped, and the capacity is
  // kept for the next in-place operations); kept node i goes to slot k - 1 - i.
  const std::size_t k = kept.size();
  auto flip = [k](TreeRef r) { return is_leaf(r) ? r : TreeRef(k - 1 - std::size_t(r)); };
  // Polygons by cycles of the permutation: `result` holds each kept node's post-order number,
  // negative for the others; a slot whose number is cleared to -1 is free or final.
  PolygonStore& polygons = arena.polygons;
  auto target = [&](std::size_t i) { return result[i] < 0 ? std::size_t(-1) : k - 1 - std::size_t(result[i]); };
  ConvexPolygon carried[2];  // the polygon on its way and the one it displaces (two moves each)
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    std::size_t t = target(i);
    if (t == std::size_t(-1) || t == i) continue;
    int c = 0;
    carried[c] = std::move(polygons[i]);
    result[i] = -1;
    while (true) {
      const std::size_t next = target(t);
      if (next == std::size_t(-1)) {
        polygons[t] = std::move(carried[c]);
        break;
      }
      carried[1 - c] = std::move(polygons[t]);
      polygons[t] = std::move(carried[c]);
      c = 1 - c;
      result[t] = -1;
      t = next;
    }
  }
  polygons.resize(k);
  arena.nodes.resize(k);
  for (std::size_t i = 0; i < k; ++i) {  // the order of the plane renumbering is part of the result
    const std::size_t j = k - 1 - i;
    arena.nodes[j] = {use(kept[i].plane), flip(kept[i].negative), flip(kept[i].positive)};
    ConvexPolygon& poly = polygons[j];
    poly.support = use(poly.support);
    for (auto& c : poly.corners) c.edge = use(c.edge), c.p = use(c.p), c.q = use(c.q);
  }
  if (!options.keep_capacity && polygons.capacity() > k + k / 4) {
    arena.nodes.shrink_to_fit();
    polygons.shrink_to_fit();
  }
  std::optional<FragmentList> boundary;
  FragmentBoxes boxes = std::move(arena.boundary_boxes);
  if (arena.boundary) {
    boundary = std::move(*arena.boundary);
    arena.boundary.reset();
    boundary->renumber_planes(use);
  }
  return SolidAccess::make(std::move(table), std::move(arena.nodes), std::move(arena.polygons), flip(new_root), FreeSlots{},
               std::move(boundary), std::move(boxes));
}

}  // namespace sculpt::bsp::detail
