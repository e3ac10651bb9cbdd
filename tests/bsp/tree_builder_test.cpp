// TreeBuilder::build against the straightforward builder it replaced (kept here as the
// reference): every node's sub-hyperplane is its plane's world polygon split by the ancestors'
// half-spaces with kernel::split, nearest ancestor first; a node whose polygon is empty or lies
// on an ancestor's plane is dropped. Same recipe in, the same tree must come out: nodes, planes
// (by value), auxiliary marks, leaves, and the polygons corner for corner (labels and the bits
// of the approximations), on sphere recipes and on random recipes full of redundant planes.
#include "bsp/tree_builder.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "bsp/boundary.hpp"
#include "bsp/tree/node_polygons.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rings/ring_solid.hpp"
#include "bsp/transform.hpp"

namespace sculpt {
namespace {

using bsp::detail::Ring;
using bsp::detail::revolve_rings;
using kernel::ConvexPolygon;
using kernel::Plane;
using kernel::PlaneTable;
using kernel::Side;

/// A tree of planes before building: what TreeBuilder::add_plane / add_node receive.
struct Recipe {
  std::vector<Plane> planes;
  std::vector<bool> auxiliary;
  std::vector<BspNode> nodes;  // plane = index into `planes`, children may be leaves
  TreeRef root = kOut;
};

/// The result of the reference builder, before any compaction.
struct Built {
  PlaneTable planes;
  std::vector<BspNode> nodes;
  std::vector<ConvexPolygon> polygons;
  TreeRef root = kOut;
};

// The builder logic before the in-place clipping (TreeBuilder::build as of commit 6963a4e).
Built reference_build(const Recipe& r) {
  Built out;
  std::vector<std::int32_t> index;
  for (std::size_t i = 0; i < r.planes.size(); ++i) index.push_back(out.planes.add(r.planes[i], r.auxiliary[i]));
  std::vector<std::int32_t> opposite_of;
  auto opposite = [&](std::int32_t i) {
    if (std::size_t(i) >= opposite_of.size()) opposite_of.resize(std::size_t(out.planes.size()), -1);
    if (opposite_of[std::size_t(i)] < 0) {
      const std::int32_t o = out.planes.add(out.planes[i].opposite(), out.planes.auxiliary(i));
      opposite_of.resize(std::size_t(out.planes.size()), -1);
      opposite_of[std::size_t(i)] = o;
      opposite_of[std::size_t(o)] = i;
    }
    return opposite_of[std::size_t(i)];
  };
  if (is_leaf(r.root)) {
    out.root = r.root;
    return out;
  }
  struct Frame {
    TreeRef source;
    std::size_t depth;
    std::int32_t add, parent;
    int side;
  };
  std::vector<std::int32_t> constraints;
  std::vector<Frame> stack{{r.root, 0, -1, -1, 0}};
  while (!stack.empty()) {
    const Frame f = stack.back();
    stack.pop_back();
    constraints.resize(f.depth);
    if (f.add >= 0) constraints.push_back(f.add);
    TreeRef src = f.source, result = src;
    while (!is_leaf(src)) {
      const BspNode n{index[std::size_t(r.nodes[std::size_t(src)].plane)], r.nodes[std::size_t(src)].negative,
                      r.nodes[std::size_t(src)].positive};
      ConvexPolygon poly = kernel::world_polygon(out.planes, n.plane);
      int cell_side = 0;
      bool empty = false;
      for (auto it = constraints.rbegin(); it != constraints.rend(); ++it) {
        const std::int32_t c = *it;
        kernel::PolygonSplit s = kernel::split(out.planes, poly, c, opposite(c));
        if (s.side == Side::On) {
          cell_side = out.planes[c] == out.planes[n.plane] ? -1 : +1;
          if (!out.planes.auxiliary(n.plane)) {
            out.planes.set_auxiliary(c, false);
            out.planes.set_auxiliary(opposite(c), false);
          }
          break;
        }
        if (s.side == Side::Positive) {
          empty = true;
          break;
        }
        if (s.side == Side::Both) poly = std::move(s.negative);
      }
      if (empty) {
        const Side ws = f.parent < 0 ? (kernel::orient(kernel::GridPoint{}, out.planes[n.plane]) == kernel::Sign::Negative
                                            ? Side::Negative
                                            : Side::Positive)
                                     : kernel::classify(out.planes, out.polygons[std::size_t(f.parent)], n.plane);
        cell_side = ws == Side::Negative ? -1 : 1;
      }
      if (cell_side != 0) {
        src = cell_side < 0 ? n.negative : n.positive;
        result = src;
        continue;
      }
      const auto id = std::int32_t(out.nodes.size());
      out.nodes.push_back({n.plane, kOut, kOut});
      out.polygons.push_back(std::move(poly));
      stack.push_back({n.positive, constraints.size(), opposite(n.plane), id, 1});
      stack.push_back({n.negative, constraints.size(), n.plane, id, 0});
      result = id;
      break;
    }
    if (f.parent < 0)
      out.root = result;
    else
      (f.side == 0 ? out.nodes[std::size_t(f.parent)].negative : out.nodes[std::size_t(f.parent)].positive) = result;
  }
  return out;
}

Solid build(const Recipe& r) {
  TreeBuilder b;
  std::vector<std::int32_t> index;
  for (std::size_t i = 0; i < r.planes.size(); ++i) index.push_back(b.add_plane(r.planes[i], r.auxiliary[i]));
  std::vector<TreeRef> ref(r.nodes.size(), kOut);
  auto child = [&](TreeRef c) { return is_leaf(c) ? c : ref[std::size_t(c)]; };
  for (std::size_t k = r.nodes.size(); k-- > 0;)  // children have larger indices
    ref[k] = b.add_node(index[std::size_t(r.nodes[k].plane)], child(r.nodes[k].negative), child(r.nodes[k].positive));
  return std::move(b).build(child(r.root));
}

// A built solid's tree as a recipe (children after parents).
Recipe recipe_of(const Solid& s) {
  Recipe r;
  for (std::int32_t i = 6; i < s.planes().size(); ++i) {
    r.planes.push_back(s.planes()[i]);
    r.auxiliary.push_back(s.planes().auxiliary(i));
  }
  std::vector<TreeRef> order;
  std::vector<TreeRef> id(s.nodes().size(), kOut);
  std::vector<TreeRef> stack{s.root()};
  while (!stack.empty()) {
    const TreeRef t = stack.back();
    stack.pop_back();
    if (is_leaf(t)) continue;
    id[std::size_t(t)] = TreeRef(order.size());
    order.push_back(t);
    stack.push_back(s.nodes()[std::size_t(t)].positive);
    stack.push_back(s.nodes()[std::size_t(t)].negative);
  }
  for (TreeRef t : order) {
    const BspNode& n = s.nodes()[std::size_t(t)];
    EXPECT_GE(n.plane, 6) << "world planes do not split solids";
    auto map = [&](TreeRef c) { return is_leaf(c) ? c : id[std::size_t(c)]; };
    r.nodes.push_back({n.plane - 6, map(n.negative), map(n.positive)});
  }
  r.root = is_leaf(s.root()) ? s.root() : 0;
  return r;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Walks both trees together; the reference's nodes whose two children are the same leaf
// collapse to that leaf (as compaction does). Returns the number of nodes compared.
// Pending sub-hyperplanes of `s` (BuildOptions::nodes_cut_cells) are computed first, from the
// nodes' paths, so the polygons compared are those every algorithm gets.
int expect_same_tree(const Built& ref, const Solid& solid) {
  const bsp::detail::Arena s = bsp::detail::with_node_polygons(solid);
  const TreeRef s_root = solid.root();
  std::vector<TreeRef> collapsed(ref.nodes.size(), kOut);
  // Children are created after parents: a reverse pass sees children first.
  for (std::size_t k = ref.nodes.size(); k-- > 0;) {
    auto c = [&](TreeRef t) { return is_leaf(t) ? t : collapsed[std::size_t(t)]; };
    const TreeRef neg = c(ref.nodes[k].negative), pos = c(ref.nodes[k].positive);
    collapsed[k] = is_leaf(neg) && neg == pos ? neg : TreeRef(k);
  }
  auto canon = [&](TreeRef t) { return is_leaf(t) ? t : collapsed[std::size_t(t)]; };
  int compared = 0;
  std::vector<std::pair<TreeRef, TreeRef>> stack{{canon(ref.root), s_root}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    EXPECT_EQ(is_leaf(a), is_leaf(b));
    if (is_leaf(a) || is_leaf(b)) {
      EXPECT_EQ(a, b);
      continue;
    }
    ++compared;
    const BspNode& na = ref.nodes[std::size_t(a)];
    const BspNode& nb = s.nodes[std::size_t(b)];
    EXPECT_EQ(ref.planes[na.plane], s.planes[nb.plane]);
    EXPECT_EQ(ref.planes.auxiliary(na.plane), s.planes.auxiliary(nb.plane));
    const ConvexPolygon& pa = ref.polygons[std::size_t(a)];
    const ConvexPolygon& pb = s.polygons[std::size_t(b)];
    EXPECT_EQ(ref.planes[pa.support], s.planes[pb.support]);
    EXPECT_EQ(pa.corners.size(), pb.corners.size());
    if (pa.corners.size() == pb.corners.size()) {
      for (std::size_t i = 0; i < pa.corners.size(); ++i) {
        const auto& ca = pa.corners[i];
        const auto& cb = pb.corners[i];
        EXPECT_EQ(ref.planes[ca.edge], s.planes[cb.edge]);
        EXPECT_EQ(ref.planes[ca.p], s.planes[cb.p]);
        EXPECT_EQ(ref.planes[ca.q], s.planes[cb.q]);
        EXPECT_TRUE(same_bits(ca.at().x, cb.at().x) && same_bits(ca.at().y, cb.at().y) &&
                    same_bits(ca.at().z, cb.at().z) && same_bits(ca.at().err, cb.at().err));
      }
    }
    if (::testing::Test::HasFailure()) return compared;  // one report, not thousands
    stack.push_back({canon(na.positive), nb.positive});
    stack.push_back({canon(na.negative), nb.negative});
  }
  return compared;
}

TEST(TreeBuilder, SphereTreesEqualTheReferenceBuilder) {
  for (int n : {3, 5, 8, 17, 32, 64}) {
    SCOPED_TRACE(n);
    const Solid s = sphere(1.0, {.segments = n});
    const Recipe r = recipe_of(s);
    const Built ref = reference_build(r);
    const Solid again = build(r);
    EXPECT_EQ(expect_same_tree(ref, again), tree_stats(s).nodes);
    EXPECT_EQ(expect_same_tree(ref, s), tree_stats(s).nodes);
  }
}

TEST(TreeBuilder, ConeAndCylinderTreesEqualTheReferenceBuilder) {
  for (const Solid& s : {cylinder(0.5, 2.0, {.segments = 48}), cone(1.0, 1.0, {.segments = 31, .top_radius = 0.25}),
                         cone(2.0, 0.5, {.segments = 9, .center = true})}) {
    const Built ref = reference_build(recipe_of(s));
    EXPECT_EQ(expect_same_tree(ref, s), tree_stats(s).nodes);
  }
}

// Ring primitives are built with BuildOptions::nodes_cut_cells (no clipping, nothing dropped)
// unless a chain was widened or the path is degenerate. The reference builder, which clips and
// drops, must then find every node cutting its cell: same tree, nothing dropped.
TEST(TreeBuilder, RingPrimitivesNeedNoDropping) {
  std::vector<Solid> solids;
  for (int n : {3, 4, 6, 9, 10, 12, 16, 20, 24, 33, 40, 48}) {
    for (double r : {1e-3, 0.37, 1.0, 250.0}) {
      solids.push_back(sphere(r, {.segments = n}));
      solids.push_back(cylinder(r, 0.5 * r + 1e-3, {.segments = n}));
      solids.push_back(cone(r, r, {.segments = n, .center = true, .top_radius = 0.0}));
      solids.push_back(cone(r, 2.0, {.segments = n, .top_radius = 0.3 * r}));
    }
  }
  // Fine tessellations near the limit of the direct boundary (primitives.cpp: edge length times
  // the sine of the exterior angle against the rounding of the face planes).
  solids.push_back(sphere(1.0, {.segments = 256}));
  solids.push_back(sphere(3.0, {.segments = 400}));
  solids.push_back(cylinder(0.01, 1.0, {.segments = 300}));
  // Random convex paths (sorted angles on an ellipse, origin inside) and random ring stacks.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 3 + int(rng() % 30);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) angles.push_back(2 * std::numbers::pi * (i + 0.8 * u(rng)) / n);
    const double ax = 0.2 + 2 * u(rng), ay = 0.2 + 2 * u(rng);
    std::vector<Eigen::Vector2d> path;
    for (double a : angles) path.emplace_back(ax * std::cos(a), ay * std::sin(a));
    std::vector<Ring> rings;
    double z = -u(rng);
    const int count = 2 + int(rng() % 6);
    for (int k = 0; k < count; ++k) {
      const bool end = k == 0 || k + 1 == count;
      rings.push_back({z, end && rng() % 3 == 0 ? 0.0 : 0.05 + u(rng)});
      z += 0.01 + u(rng);
    }
    solids.push_back(revolve_rings(path, rings));
  }
  int trusted = 0;
  for (std::size_t i = 0; i < solids.size(); ++i) {
    SCOPED_TRACE(i);
    const Solid& s = solids[i];
    trusted += std::all_of(s.polygons().begin(), s.polygons().end(), bsp::detail::pending);
    const Built ref = reference_build(recipe_of(s));
    EXPECT_EQ(expect_same_tree(ref, s), tree_stats(s).nodes);
    if (HasFailure()) return;
  }
  EXPECT_GT(trusted, int(solids.size()) / 2);  // most of them take the fast path
}

// Exact maps (translations, mirrors, integer scales, quarter turns) keep every node cutting its
// cell, so their images are built without clipping, from full builds and fast builds alike.
TEST(TreeBuilder, ExactImagesNeedNoDropping) {
  const Solid sources[] = {sphere(1.0, {.segments = 24}), cone(1.0, 2.0, {.segments = 9, .top_radius = 0.25}),
                           sphere(0.5, {.segments = 7}) | box({0, 0, 0}, {1, 1, 1})};
  for (const Solid& s : sources) {
    const std::pair<Solid, double> images[] = {{translate(s, {0.25, -3.0, 7.5}), 1.0},
                                               {scale(s, {-1, 1, 1}), 1.0},
                                               {scale(s, {2, 2, -2}), 8.0},
                                               {rotate(s, {0, 0, 1}, 90.0), 1.0},
                                               {rotate(s, {1, 0, 0}, -90.0), 1.0}};
    for (const auto& [image, det] : images) {
      const Built ref = reference_build(recipe_of(image));
      EXPECT_EQ(expect_same_tree(ref, image), tree_stats(image).nodes);
      EXPECT_NEAR(volume(image), det * volume(s), 1e-9 * det * volume(s));  // |det| times the volume
    }
  }
}

// Top-down construction (open_nodes / set_node): a tree laid out in pre-order is kept as it is,
// any other layout (breadth-first, a shared node, an unreachable node) is copied into pre-order.
// Either way the solid's storage must equal that of the same tree built bottom-up (add_node).
TEST(TreeBuilder, OpenedNodesGiveTheSameStorageInAnyLayout) {
  std::mt19937 rng(11);
  auto storage = [](const Solid& s) {
    std::vector<std::tuple<Plane, bool, TreeRef, TreeRef, Plane>> out;
    for (std::size_t i = 0; i < s.nodes().size(); ++i) {
      const BspNode& n = s.nodes()[i];
      out.emplace_back(s.planes()[n.plane], s.planes().auxiliary(n.plane), n.negative, n.positive,
                       s.planes()[s.polygons()[i].support]);
    }
    return out;
  };
  int layouts = 0, shares = 0;
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    // A random recipe whose nodes are numbered breadth-first (children after parents).
    Recipe r;
    const int planes = 2 + int(rng() % 6);
    for (int i = 0; i < planes; ++i) {
      r.planes.push_back(kernel::make_plane(int(rng() % 5) - 2, 1 + int(rng() % 3), int(rng() % 3), i));
      r.auxiliary.push_back(rng() % 2 == 0);
    }
    const int count = 1 + int(rng() % 40);
    for (int k = 0; k < count; ++k) r.nodes.push_back({std::int32_t(rng() % std::uint32_t(planes)), kOut, kIn});
    int next = 1;
    for (int k = 0; k < next; ++k)  // node k has a parent (or is the root)
      for (TreeRef* c : {&r.nodes[std::size_t(k)].negative, &r.nodes[std::size_t(k)].positive})
        *c = next < count && rng() % 3 != 0 ? TreeRef(next++) : (rng() % 2 ? kIn : kOut);
    r.nodes.resize(std::size_t(next));  // the nodes no parent took
    // Sometimes a node shared by two parents: the root's positive child X, also a child of node 1
    // (the root's negative child) in place of a leaf.
    const TreeRef x = r.nodes[0].positive;
    const bool shared = trial % 3 == 1 && r.nodes[0].negative == 1 && !is_leaf(x) &&
                        (is_leaf(r.nodes[1].negative) || is_leaf(r.nodes[1].positive));
    if (shared) (is_leaf(r.nodes[1].negative) ? r.nodes[1].negative : r.nodes[1].positive) = x;
    r.root = 0;
    // Pre-order of the recipe (negative subtree first), as TreeBuilder lays it out.
    std::vector<TreeRef> preorder;
    for (std::vector<TreeRef> stack{0}; !stack.empty();) {
      const TreeRef t = stack.back();
      stack.pop_back();
      preorder.push_back(t);
      for (const TreeRef c : {r.nodes[std::size_t(t)].positive, r.nodes[std::size_t(t)].negative})
        if (!is_leaf(c)) stack.push_back(c);
    }
    // Bottom-up reference, then top-down in three layouts: the recipe's breadth-first order, pre-order
    // (kept as laid out unless a node is shared), pre-order with one unreachable node at the end.
    const Solid reference = [&] {
      TreeBuilder b;
      for (std::size_t i = 0; i < r.planes.size(); ++i) b.add_plane(r.planes[i], r.auxiliary[i]);
      std::vector<TreeRef> ref(r.nodes.size(), kOut);
      auto child = [&](TreeRef c) { return is_leaf(c) ? c : ref[std::size_t(c)]; };
      for (std::size_t k = r.nodes.size(); k-- > 0;)
        ref[k] = b.add_node(kernel::kWorldPlanes + r.nodes[k].plane, child(r.nodes[k].negative), child(r.nodes[k].positive));
      return std::move(b).build(ref[0], BuildOptions{.nodes_cut_cells = true});
    }();
    for (int layout = 0; layout < 3; ++layout) {
      std::vector<TreeRef> order(r.nodes.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = TreeRef(i);
      if (layout > 0 && !shared) order = preorder;  // a shared node is visited twice: no single layout
      TreeBuilder b;
      for (std::size_t i = 0; i < r.planes.size(); ++i) b.add_plane(r.planes[i], r.auxiliary[i]);
      const TreeRef first = b.open_nodes(std::int32_t(order.size()) + (layout == 2 ? 1 : 0));
      std::vector<TreeRef> at(r.nodes.size(), kOut);
      for (std::size_t i = 0; i < order.size(); ++i) at[std::size_t(order[i])] = first + TreeRef(i);
      auto child = [&](TreeRef c) { return is_leaf(c) ? c : at[std::size_t(c)]; };
      for (std::size_t k = 0; k < r.nodes.size(); ++k)
        b.set_node(at[k], kernel::kWorldPlanes + r.nodes[k].plane, child(r.nodes[k].negative), child(r.nodes[k].positive));
      if (layout == 2) b.set_node(first + TreeRef(order.size()), kernel::kWorldPlanes, kIn, kOut);  // unreachable
      const Solid s = std::move(b).build(at[0], BuildOptions{.nodes_cut_cells = true});
      EXPECT_EQ(s.root(), 0);
      EXPECT_EQ(storage(s), storage(reference)) << "layout " << layout;
      ++layouts;
    }
    EXPECT_EQ(reference.nodes().size(), preorder.size());  // a shared node is copied for each parent
    if (!shared) {
      EXPECT_EQ(preorder.size(), r.nodes.size());
    }
    shares += shared ? 1 : 0;
  }
  EXPECT_EQ(layouts, 600);
  EXPECT_GT(shares, 10);
}

TEST(TreeBuilder, OpenedNodesAreChecked) {
  TreeBuilder b;
  const std::int32_t p = b.add_plane(kernel::make_plane(0, 0, 1, 0));
  EXPECT_THROW(b.open_nodes(-1), std::out_of_range);
  const TreeRef n = b.open_nodes(2);
  EXPECT_THROW(b.set_node(n + 2, p, kIn, kOut), std::out_of_range);  // unknown node
  EXPECT_THROW(b.set_node(n, p + 1, kIn, kOut), std::out_of_range);  // unknown plane
  EXPECT_THROW(b.set_node(n, p, n + 2, kOut), std::out_of_range);    // unknown child
  b.set_node(n, p, n + 1, kOut);
  {
    TreeBuilder copy = b;  // node n + 1 never set
    EXPECT_THROW((void)std::move(copy).build(n), std::logic_error);
  }
  b.set_node(n + 1, p, kIn, kOut);
  EXPECT_NO_THROW((void)std::move(b).build(n));
}

// Random trees over a few planes with many coincident, opposite and parallel ones: most nodes
// do not cut their cells (empty polygons and planes equal to an ancestor's), which exercises
// dropping, the choice of the surviving child and the auxiliary marks.
TEST(TreeBuilder, RandomRedundantTreesEqualTheReferenceBuilder) {
  std::mt19937 rng(7);
  std::vector<Plane> pool;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c)
        if (a != 0 || b != 0 || c != 0)
          for (int d : {-3, 0, 2}) pool.push_back(kernel::make_plane(a, b, c, kernel::Int128(d) << 15));
  int total = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Recipe r;
    const int planes = 3 + int(rng() % 10);
    for (int i = 0; i < planes; ++i) {
      r.planes.push_back(pool[rng() % pool.size()]);
      r.auxiliary.push_back(rng() % 3 == 0);
    }
    // Breadth-first random tree: each node's children are leaves or later nodes.
    const int count = 1 + int(rng() % 60);
    for (int k = 0; k < count; ++k) r.nodes.push_back({std::int32_t(rng() % std::uint32_t(planes)), kOut, kIn});
    int next = 1;
    for (int k = 0; k < count; ++k)
      for (TreeRef* c : {&r.nodes[std::size_t(k)].negative, &r.nodes[std::size_t(k)].positive})
        *c = next < count && rng() % 4 != 0 ? TreeRef(next++) : (rng() % 2 ? kIn : kOut);
    r.root = 0;
    SCOPED_TRACE(trial);
    const Built ref = reference_build(r);
    const Solid s = build(r);
    total += expect_same_tree(ref, s);
    if (HasFailure()) return;
  }
  EXPECT_GT(total, 300);  // the trees are not all trivial
}

}  // namespace
}  // namespace sculpt
