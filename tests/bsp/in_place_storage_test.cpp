// The storage of in-place set operations (bsp/tree/tree_arena.hpp: reclaim_added,
// scan_for_free_planes, compact): many strokes and set operations done in place give the same sets
// as the copying operations; every reference of the workpiece stays in range; an operation leaves
// the planes and nodes that were there before it where they were, keeps no plane or node it added
// and left unused, and lists as free exactly node slots the tree does not reach (cleared) and
// plane slots nothing refers to; free slots are taken by later operations.
#include <gtest/gtest.h>

#include "bsp/local/cell_merge.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rebuild.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/sweep.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/solid_access.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

// What the reachable tree and the boundary of a solid refer to, found independently of the
// library's bookkeeping (a traversal from the root and a scan of the boundary).
struct References {
  std::vector<bool> plane_used;  // by a reachable node, its polygon or a boundary fragment
  std::vector<bool> node_reached;
  bool in_range = true;        // every plane and node index within the storage
  bool supports_match = true;  // a reachable node's polygon lies on its plane (or is pending)
};

References references(const Solid& s) {
  References r;
  r.plane_used.assign(std::size_t(s.planes().size()), false);
  r.node_reached.assign(s.nodes().size(), false);
  for (int i = 0; i < 6; ++i) r.plane_used[std::size_t(i)] = true;  // the world box
  auto use = [&](std::int32_t p) {
    if (p < 0 || p >= s.planes().size())
      r.in_range = false;
    else
      r.plane_used[std::size_t(p)] = true;
  };
  auto use_polygon = [&](kernel::PolygonView poly) {
    use(poly.support);
    for (const auto& c : poly.corners) use(c.edge), use(c.p), use(c.q);
  };
  std::vector<TreeRef> stack{s.root()};
  while (!stack.empty()) {
    const TreeRef t = stack.back();
    stack.pop_back();
    if (is_leaf(t)) continue;
    if (std::size_t(t) >= s.nodes().size()) {
      r.in_range = false;
      continue;
    }
    r.node_reached[std::size_t(t)] = true;
    const BspNode& n = s.nodes()[std::size_t(t)];
    use(n.plane);
    const auto& poly = s.polygons()[std::size_t(t)];
    use_polygon(poly);
    if (!poly.corners.empty() && poly.support != n.plane) r.supports_match = false;
    stack.push_back(n.negative);
    stack.push_back(n.positive);
  }
  for (const FragmentRef f : s.boundary()) use_polygon(f.polygon);
  return r;
}

// Every node slot is reached or listed free (cleared, each once): no slot leaks, none is listed
// twice; every free plane slot is beyond the world box, listed once, referred to by nothing.
void expect_slots_accounted(const Solid& work, const References& after, const std::string& where) {
  const bsp::detail::FreeSlots& free = bsp::detail::SolidAccess::free_slots(work);
  std::vector<bool> listed(work.nodes().size(), false);
  for (const std::int32_t t : free.nodes) {
    ASSERT_TRUE(t >= 0 && std::size_t(t) < work.nodes().size()) << where;
    EXPECT_FALSE(after.node_reached[std::size_t(t)]) << where << " free node " << t;
    EXPECT_FALSE(listed[std::size_t(t)]) << where << " free node " << t << " listed twice";
    listed[std::size_t(t)] = true;
    const BspNode& n = work.nodes()[std::size_t(t)];
    EXPECT_TRUE(n.plane == 0 && n.negative == kOut && n.positive == kOut) << where << " free node " << t;
    EXPECT_TRUE(work.polygons()[std::size_t(t)].corners.empty()) << where << " free node " << t;
  }
  for (std::size_t i = 0; i < work.nodes().size(); ++i)
    EXPECT_TRUE(after.node_reached[i] || listed[i]) << where << " node slot " << i << " neither reached nor free";
  std::vector<bool> plane_listed(after.plane_used.size(), false);
  for (const std::int32_t p : free.planes) {
    ASSERT_TRUE(p >= kernel::kWorldPlanes && std::size_t(p) < after.plane_used.size()) << where;
    EXPECT_FALSE(after.plane_used[std::size_t(p)]) << where << " free plane " << p << " is referred to";
    EXPECT_FALSE(plane_listed[std::size_t(p)]) << where << " free plane " << p << " listed twice";
    plane_listed[std::size_t(p)] = true;
  }
}

// `count` operations on `work` (large enough that each runs in place: the larger operand's
// storage is reused): strokes carving and adding, a box subtracted, a ball united then a box
// intersected; each checked against the copying operation and the storage checked as above.
void run_operations(Solid work, int count) {
  const Solid ball = sphere(0.2, {.segments = 8});
  int reused_slots = 0;       // planes put in slots nothing referred to
  int reused_node_slots = 0;  // nodes put in slots the tree did not reach
  int scans_in_progress = 0;  // operations after which a scan for free planes was under way
  int free_plane_lists = 0;   // operations after which free plane slots were listed
  for (int k = 0; k < count; ++k) {
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 6; ++i) {
      const double t = 0.7 * k + 0.2 * i;
      path.emplace_back(0.6 * std::cos(t), 0.6 * std::sin(t), 0.1 * std::sin(3.0 * t) - 0.05 * (k % 4));
    }
    const Solid swept = sweep(ball, path);
    const double c = 0.3 * std::sin(1.3 * k);
    const Solid cutter = box({c - 0.15, -0.9, -0.3}, {c + 0.15, 0.9, 0.2});
    const Solid lump = sphere(0.25, {.segments = 10});
    const Solid lump_at = translate(lump, {0.5 * std::cos(0.9 * k), 0.5 * std::sin(0.9 * k), -0.1});
    // The operation k does, copying and in place.
    auto copying = [&](const Solid& w) {
      switch (k % 5) {
        case 0: case 1: return w - swept;  // carve(w, ball, path)
        case 2: return w | swept;          // add(w, ball, path)
        case 3: return w - cutter;
        default: return (w | lump_at) & box({-0.95, -0.95, -0.95}, {0.95, 0.95, 0.2});
      }
    };
    auto in_place = [&](Solid&& w) {
      switch (k % 5) {
        case 0: return std::move(w) - swept;  // the set operation alone
        case 1: return carve(std::move(w), ball, path);  // that and rebuild_region: two operations
        case 2: return std::move(w) | swept;
        case 3: return std::move(w) - cutter;
        default: return intersect(std::move(w) | lump_at, box({-0.95, -0.95, -0.95}, {0.95, 0.95, 0.2}));
      }
    };
    ASSERT_GT(work.nodes().size(), 3 * (swept.nodes().size() + lump.nodes().size()));
    const Solid copied = copying(work);
    const std::vector<kernel::Plane> planes_before = work.planes().to_vector();
    const std::vector<BspNode> nodes_before = work.nodes();
    const References before = references(work);
    work = in_place(std::move(work));
    ASSERT_TRUE((work - copied).is_empty()) << "operation " << k;
    ASSERT_TRUE((copied - work).is_empty()) << "operation " << k;
    const References after = references(work);
    ASSERT_TRUE(after.in_range) << "operation " << k;
    EXPECT_TRUE(after.supports_match) << "operation " << k;
    ASSERT_EQ(work.polygons().size(), work.nodes().size());
    // Planes are never renumbered in place: every plane referenced before is where it was
    // (slots of planes nothing referred to may have been given to new planes), and every plane
    // added since is referenced (the unused ones were reclaimed).
    const std::size_t p0 = planes_before.size();
    ASSERT_GE(after.plane_used.size(), std::size_t(6));
    // (Operations 1 and 4 are two in-place operations each: the first may leave planes it added
    // to old nodes the second frees, or free slots the second takes; each operation alone is
    // checked in 0, 2 and 3, and rebuild_region alone by the RegionRebuild tests.)
    const bool single = k % 5 == 0 || k % 5 == 2 || k % 5 == 3;
    for (std::size_t i = 0; i < p0; ++i)
      if (before.plane_used[i] && single) {
        ASSERT_LT(i, after.plane_used.size());
        ASSERT_EQ(work.planes()[std::int32_t(i)], planes_before[i]) << "operation " << k << " plane " << i;
      }
    if (single) {
      for (std::size_t i = p0; i < after.plane_used.size(); ++i) {
        EXPECT_TRUE(after.plane_used[i]) << "operation " << k << " plane " << i;
      }
    }
    for (std::size_t i = 0; i < std::min(p0, after.plane_used.size()); ++i) reused_slots += after.plane_used[i] && !before.plane_used[i];
    // Nodes are never moved in place: an old node still reached keeps its plane, and every node slot is
    // reached or listed free (cleared, each once): no slot leaks, none is listed twice.
    // (Unless the storage was compacted: rebuild_region may have freed more than half of it.)
    const std::size_t n0 = nodes_before.size();
    const bool compacted = work.nodes().size() < n0;
    if (compacted) {
      ASSERT_FALSE(single) << "operation " << k;
      EXPECT_TRUE(bsp::detail::SolidAccess::free_slots(work).nodes.empty()) << "operation " << k;
    }
    for (std::size_t i = 0; i < n0 && !compacted; ++i) {
      if (before.node_reached[i] && after.node_reached[i] && single) {
        ASSERT_EQ(work.nodes()[i].plane, nodes_before[i].plane) << "operation " << k;
      }
      reused_node_slots += !before.node_reached[i] && after.node_reached[i];
    }
    expect_slots_accounted(work, after, "operation " + std::to_string(k));
    const bsp::detail::FreeSlots& free = bsp::detail::SolidAccess::free_slots(work);
    scans_in_progress += !free.plane_marked.empty();
    free_plane_lists += !free.planes.empty();
  }
  // Over a long run: free node and plane slots were taken by later operations, and the scan for
  // free planes spanned several operations (what they wrote during it was marked).
  if (count >= 10) {
    EXPECT_GT(reused_node_slots, 0);
    EXPECT_GT(scans_in_progress, 0);
  }
  if (count >= 30) {
    EXPECT_GT(reused_slots, 0);
    EXPECT_GT(free_plane_lists, 0);
  }
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(work)));
}

Solid workpiece() { return sphere(1.0, {.segments = 48}) & box({-2, -2, -2}, {2, 2, 0.1}); }

TEST(InPlaceStorage, ManyOperationsKeepTheOldStorageAndNoUnusedAdditions) { run_operations(workpiece(), 30); }

TEST(InPlaceStorage, AWorkpieceWithPendingPolygons) {
  // A translated solid keeps its tree as given, its nodes' polygons pending (computed when a
  // merge reaches them: those refer to opposites the operation adds).
  const Solid work = translate(workpiece(), {0.125, 0, 0});
  EXPECT_GT(std::count_if(work.polygons().begin(), work.polygons().end(), [](const auto& p) { return p.corners.empty(); }), 100);
  run_operations(work, 10);
}

TEST(InPlaceStorage, AWorkpieceWithoutItsBoundary) {
  // Without a carried boundary the first operation extracts it (on planes it adds).
  const Solid in_place = workpiece();  // (holds free node slots: copied below, they would not be listed)
  const Solid full = in_place & box({-3, -3, -3}, {3, 3, 3});  // the copying operation: compacted
  ASSERT_EQ(std::size_t(tree_stats(full).nodes), full.nodes().size());
  Solid work = bsp::detail::SolidAccess::make(full.planes(), full.nodes(), full.polygons(), full.root());
  ASSERT_FALSE(work.has_boundary());
  run_operations(std::move(work), 10);
}


TEST(InPlaceStorage, AnOperationThatCutsAwayMostOfTheTreeCompactsIt) {
  // More than half of the node slots free after an operation: the solid is compacted (every slot
  // reached, no free slots kept), and it is the set the copying operation gives; later in-place
  // operations go on from there.
  // The copying operation by the same (classic) merge: fragment for fragment the same boundary.
  const bsp::detail::ScopedCellMergeThreshold classic(bsp::detail::kClassicMergeOnly);
  Solid work = sphere(1.0, {.segments = 96});
  ASSERT_GT(work.nodes().size(), std::size_t(4096));
  const Solid cutter = box({-2, -2, -0.9}, {2, 2, 2});  // leaves a thin cap of the sphere
  const Solid copied = work - cutter;
  const std::size_t slots_before = work.nodes().size();
  work = std::move(work) - cutter;
  EXPECT_TRUE((work - copied).is_empty());
  EXPECT_TRUE((copied - work).is_empty());
  const References r = references(work);
  ASSERT_TRUE(r.in_range);
  EXPECT_LT(2 * work.nodes().size(), slots_before);
  EXPECT_EQ(std::count(r.node_reached.begin(), r.node_reached.end(), true), std::ptrdiff_t(work.nodes().size()));
  EXPECT_TRUE(bsp::detail::SolidAccess::free_slots(work).nodes.empty());
  EXPECT_EQ(work.boundary().size(), copied.boundary().size());
  const Solid ball = sphere(0.2, {.segments = 8});
  const Solid lump = translate(ball, {0, 0, -0.9});
  const Solid united = work | lump;
  work = std::move(work) | lump;
  EXPECT_TRUE((work - united).is_empty());
  EXPECT_TRUE((united - work).is_empty());
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(work)));
}

// A workpiece carved by `strokes` strokes without the strokes' own tidying (the set operation
// alone), so that its tree keeps every plane the strokes brought.
Solid grown_workpiece(int strokes) {
  Solid work = workpiece();
  const Solid ball = sphere(0.2, {.segments = 8});
  for (int k = 0; k < strokes; ++k) {
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 6; ++i) {
      const double t = 0.7 * k + 0.2 * i;
      path.emplace_back(0.6 * std::cos(t), 0.6 * std::sin(t), 0.1 * std::sin(3.0 * t) - 0.05 * (k % 4));
    }
    work = std::move(work) - sweep(ball, path);
  }
  return work;
}

// rebuild_region alone: the same set; fewer nodes; old nodes outside the rebuilt subtrees stay
// where they were with their planes, the rebuilt ones' slots are free, every added plane is used.
void expect_region_rebuilt(Solid work, const Eigen::AlignedBox3d& region, const RegionRebuildOptions& options,
                           bool expect_change) {
  const Solid copy = work;
  const std::vector<kernel::Plane> planes_before = work.planes().to_vector();
  const std::vector<BspNode> nodes_before = work.nodes();
  const References before = references(work);
  RegionRebuildStats stats;
  work = rebuild_region(std::move(work), region, options, &stats);
  ASSERT_TRUE((work - copy).is_empty());
  ASSERT_TRUE((copy - work).is_empty());
  const References after = references(work);
  ASSERT_TRUE(after.in_range);
  EXPECT_TRUE(after.supports_match);
  expect_slots_accounted(work, after, "rebuild_region");
  if (!expect_change) {
    EXPECT_EQ(stats.rebuilt, 0);
    EXPECT_EQ(tree_stats(work).nodes, tree_stats(copy).nodes);
    return;
  }
  EXPECT_GT(stats.rebuilt, 0);
  EXPECT_LT(stats.nodes_after, stats.nodes_before);
  EXPECT_EQ(tree_stats(copy).nodes - tree_stats(work).nodes, stats.nodes_before - stats.nodes_after);
  // Unless the storage was compacted (more than half of it free), nothing else moved.
  const bool compacted = work.nodes().size() < nodes_before.size();
  if (compacted) {
    EXPECT_TRUE(bsp::detail::SolidAccess::free_slots(work).nodes.empty());
  }
  for (std::size_t i = 0; i < nodes_before.size() && !compacted; ++i) {
    if (before.node_reached[i] && after.node_reached[i]) {
      ASSERT_EQ(work.nodes()[i].plane, nodes_before[i].plane) << "node " << i;
    }
  }
  for (std::size_t i = 0; i < planes_before.size() && !compacted; ++i) {
    if (before.plane_used[i]) {
      ASSERT_EQ(work.planes()[std::int32_t(i)], planes_before[i]) << "plane " << i;
    }
  }
  for (std::size_t i = compacted ? 0 : planes_before.size(); i < after.plane_used.size(); ++i)
    EXPECT_TRUE(after.plane_used[i]) << "plane " << i;
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(work)));
  // In-place operations go on from the rebuilt storage.
  const Solid cutter = box({-0.3, -0.3, -2}, {0.3, 0.3, 2});
  const Solid cut = work - cutter;
  work = std::move(work) - cutter;
  EXPECT_TRUE((work - cut).is_empty());
  EXPECT_TRUE((cut - work).is_empty());
  expect_slots_accounted(work, references(work), "after the rebuild");
}

TEST(RegionRebuild, SubtreesInTheRegionBecomeSmallerAndTheSetStays) {
  const Solid work = grown_workpiece(12);
  expect_region_rebuilt(work, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 0.2)),
                        {.min_subtree_nodes = 16}, true);
  // A small region at the carved rim; small subtrees and a tight budget.
  expect_region_rebuilt(work, Eigen::AlignedBox3d(Eigen::Vector3d(0.4, 0.2, -0.3), Eigen::Vector3d(0.8, 0.6, 0.2)),
                        {.max_subtree_nodes = 300, .min_subtree_nodes = 8, .max_nodes = 900}, true);
}

TEST(RegionRebuild, TheWholeTreeAsOneSubtreeIsTheSetRebuildFromBoundaryGives) {
  const Solid work = grown_workpiece(8);
  const Solid whole = rebuild_from_boundary(work);
  RegionRebuildStats stats;
  const Solid rebuilt = rebuild_region(Solid(work), Eigen::AlignedBox3d(Eigen::Vector3d(-3, -3, -3), Eigen::Vector3d(3, 3, 3)),
                                       {.max_subtree_nodes = 1 << 30, .max_nodes = 1 << 30}, &stats);
  EXPECT_EQ(stats.rebuilt, 1);
  EXPECT_EQ(stats.nodes_before, tree_stats(work).nodes);
  EXPECT_TRUE((rebuilt - whole).is_empty());
  EXPECT_TRUE((whole - rebuilt).is_empty());
  EXPECT_LT(tree_stats(rebuilt).nodes, tree_stats(work).nodes);
}

TEST(RegionRebuild, ARegionAwayFromTheSolidOrTinyChangesNothing) {
  const Solid work = grown_workpiece(6);
  expect_region_rebuilt(work, Eigen::AlignedBox3d(Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(6, 6, 6)), {}, false);
  expect_region_rebuilt(work, Eigen::AlignedBox3d(), {}, false);  // empty
  const Solid leaf = rebuild_region(Solid::leaf(true), Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)));
  EXPECT_EQ(leaf.root(), kIn);
}

TEST(RegionRebuild, PendingPolygonsAndAWorkpieceWithoutItsBoundary) {
  // A translated workpiece: its polygons pending (computed from the paths for the extraction).
  const Solid moved = translate(grown_workpiece(6), {0.125, 0, 0});
  expect_region_rebuilt(moved, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1.2, 1, 0.2)),
                        {.min_subtree_nodes = 16}, true);
  const Solid grown = grown_workpiece(6);
  const Solid full = grown & box({-3, -3, -3}, {3, 3, 3});
  const Solid bare = bsp::detail::SolidAccess::make(full.planes(), full.nodes(), full.polygons(), full.root());
  ASSERT_FALSE(bare.has_boundary());
  expect_region_rebuilt(bare, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 0.2)),
                        {.min_subtree_nodes = 16}, true);
}

TEST(RegionRebuild, StrokesKeepTheTreeSmallerThanTheSetOperationsAlone) {
  // carve and add rebuild what each stroke touched: the same set as the set operations alone,
  // with a smaller tree.
  Solid tidy = workpiece(), plain = workpiece();
  const Solid ball = sphere(0.2, {.segments = 8});
  for (int k = 0; k < 16; ++k) {
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 6; ++i) {
      const double t = 0.7 * k + 0.2 * i;
      path.emplace_back(0.6 * std::cos(t), 0.6 * std::sin(t), 0.1 * std::sin(3.0 * t) - 0.05 * (k % 4));
    }
    if (k % 4 == 3) {
      tidy = add(std::move(tidy), ball, path);
      plain = std::move(plain) | sweep(ball, path);
    } else {
      tidy = carve(std::move(tidy), ball, path);
      plain = std::move(plain) - sweep(ball, path);
    }
  }
  EXPECT_TRUE((tidy - plain).is_empty());
  EXPECT_TRUE((plain - tidy).is_empty());
  EXPECT_LT(tree_stats(tidy).nodes, tree_stats(plain).nodes);
  expect_slots_accounted(tidy, references(tidy), "after the strokes");
}

}  // namespace
}  // namespace sculpt
