#include "bsp/tree/autopartition.hpp"
#include "base/cancel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <span>
#include <utility>

#include "bsp/tree/node_polygons.hpp"
#include "bsp/tree_builder.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

// A fragment's piece in the cell being partitioned, with its outward plane (its box is kept
// apart, in an array of its own: scoring reads boxes far more often than polygons).
struct PartitionPiece {
  ConvexPolygon polygon;
  std::int32_t outward;  // support, or its opposite for a flipped fragment
};

using Node = PartitionNode;

// An auxiliary plane with no fragment on one side (ExpectedDepth): that side's status is not
// known when the node is made. The cell has no boundary there, and the plane carries none, so
// the side has the status of the cells just across the plane: the node's polygon (plane ∩ cell),
// pushed down the other child's subtree, reaches a leaf with that status.
struct PendingSide {
  TreeRef node;
  int empty_side;
  ConvexPolygon polygon;
};

// Side of a piece with respect to a plane given by value, for scoring only: the box, else the
// signs of the plane at the corners' approximations (with a small relative tolerance).
Side approximate_side(const PartitionPiece& p, const CornerBox& box, const kernel::Plane& e) {
  const Side quick = kernel::box_side(box, e);
  if (quick != Side::Both) return quick;
  const double a = double(e.a), b = double(e.b), c = double(e.c), d = e.d_nearest;
  const double tolerance = 1e-9 * (std::fabs(a) + std::fabs(b) + std::fabs(c)) * (1.0 + std::fabs(box.lo[0]) + std::fabs(box.hi[0]));
  bool neg = false, pos = false;
  for (const kernel::Corner& k : p.polygon.corners) {
    const double v = a * k.at().x + b * k.at().y + c * k.at().z + d;
    neg |= v < -tolerance;
    pos |= v > tolerance;
  }
  return neg ? (pos ? Side::Both : Side::Negative) : (pos ? Side::Positive : Side::On);
}

// Side of a piece with respect to a plane, for scoring only (a heuristic: the split itself is
// exact): the box first, else exactly, or (`approximate`) as approximate_side.
Side side_of(const kernel::PlaneTable& planes, const PartitionPiece& p, const CornerBox& box, std::int32_t plane,
             bool approximate) {
  if (approximate) return approximate_side(p, box, planes[plane]);
  const Side quick = kernel::box_side(box, planes[plane]);
  if (quick != Side::Both) return quick;
  return kernel::classify(planes, p.polygon, plane);
}

// Deterministic sampling (splitmix64): the same input gives the same tree.
struct SplitMix {
  std::uint64_t state = 0x243f6a8885a308d3ull;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

using Point = std::array<double, 3>;  // grid units

double plane_value(const kernel::Plane& e, const Point& x) {
  return double(e.a) * x[0] + double(e.b) * x[1] + double(e.c) * x[2] + e.d_nearest;
}

// Axis-aligned plane 2 x_axis - (2 floor(c) + 1) = 0: half a grid step above floor(c), so it
// contains no grid point, hence no vertex of a face of from_mesh; false outside the world.
bool half_step_plane(int axis, double c, kernel::Plane& out) {
  const double f = std::floor(c);
  if (!(std::fabs(f) < double(kernel::PlaneTable::kWorld))) return false;
  kernel::Int128 normal[3] = {0, 0, 0};
  normal[axis] = 2;
  out = kernel::make_plane(normal[0], normal[1], normal[2], -(2 * kernel::Int128(f) + 1));
  return true;
}

}  // namespace

PartitionTree partition_fragments(Arena& arena, const FragmentList& fragments,
                                  const AutopartitionOptions& options, std::span<const std::int32_t> cell) {
  PartitionTree tree;
  if (fragments.empty()) return tree;
  const kernel::PlaneTable& planes = arena.planes;
  // Pieces live in one pool (split parts are appended); frames hold indices into it.
  std::vector<PartitionPiece> pool;
  std::vector<CornerBox> boxes;
  pool.reserve(2 * fragments.size());
  boxes.reserve(2 * fragments.size());
  for (const FragmentRef f : fragments) {
    const std::int32_t s = f.polygon.support;
    pool.push_back({kernel::ConvexPolygon::copy_of(f.polygon), f.flip ? arena.opposite(s) : s});
    boxes.push_back(kernel::corner_box(f.polygon));
  }

  struct Frame {
    std::vector<std::int32_t> pieces;
    std::int32_t parent;  // -1: the root
    int side;
    std::vector<std::int32_t> points;  // ExpectedDepth: the sample points in the cell
  };
  const bool by_depth = options.score == PartitionScore::ExpectedDepth;
  SplitMix rng;
  std::vector<Point> points;
  std::vector<std::int32_t> all_points;
  if (by_depth) {
    // Points uniform in the fragments' bounding box (Ihm & Naylor sec. 6: a cell is reached with
    // the probability of its volume share).
    Point lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const CornerBox& b : boxes)
      if (b.valid)
        for (int a = 0; a < 3; ++a) lo[std::size_t(a)] = std::min(lo[std::size_t(a)], b.lo[a]), hi[std::size_t(a)] = std::max(hi[std::size_t(a)], b.hi[a]);
    if (lo[0] <= hi[0]) {
      points.resize(std::min(std::size_t(std::max(0, options.volume_samples)), std::size_t(kVolumeSamplesPerFragment) * pool.size()));
      for (Point& x : points)
        for (std::size_t a = 0; a < 3; ++a) x[a] = lo[a] + rng.uniform() * (hi[a] - lo[a]);
    }
    all_points.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) all_points[i] = std::int32_t(i);
  }
  std::vector<Node>& nodes = tree.nodes;
  std::vector<Frame> stack;
  {
    std::vector<std::int32_t> all(pool.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::int32_t(i);
    stack.push_back({std::move(all), -1, 0, std::move(all_points)});
  }
  TreeRef& root = tree.root;
  std::vector<PendingSide> pending_sides;
  std::vector<std::int32_t> path;
  const std::size_t candidates = std::size_t(std::max(1, options.candidates));
  const std::size_t sample = std::size_t(std::max(1, options.sample));
  // ExpectedDepth (Naylor 1993): the position in `pieces` of the face candidate of least
  // estimated cost, and an auxiliary plane (arena index) if one costs less, else -1.
  std::vector<double> medians;
  std::vector<std::int32_t> tried;
  auto choose_by_depth = [&](const std::vector<std::int32_t>& pieces,
                             const std::vector<std::int32_t>& cell_points) -> std::pair<std::size_t, std::int32_t> {
    const std::size_t n = pieces.size();
    if (n <= 1) return {0, -1};
    const std::size_t s = std::min(n, sample);
    const std::size_t m = cell_points.size();
    const std::size_t q = std::min(m, std::size_t(std::max(0, options.point_sample)));
    const double prior = 2.0;  // points' worth of the fragment shares where few points are left
    auto subtree = [](double count) { return std::log2(1.0 + count); };
    auto cost = [&](const kernel::Plane& e, double extra) {
      int neg = 0, pos = 0, both = 0;
      for (std::size_t j = 0; j < s; ++j) {
        const auto id = std::size_t(pieces[j * n / s]);
        const Side side = approximate_side(pool[id], boxes[id], e);
        neg += side == Side::Negative;
        pos += side == Side::Positive;
        both += side == Side::Both;
      }
      double below = 0;
      for (std::size_t j = 0; j < q; ++j) {
        const double v = plane_value(e, points[std::size_t(cell_points[j * m / q])]);
        below += v < 0 ? 1.0 : (v == 0 ? 0.5 : 0.0);
      }
      const double scale = double(n) / double(s);
      const double n_neg = (neg + both) * scale, n_pos = (pos + both) * scale;
      const double share = n_neg + n_pos > 0 ? n_neg / (n_neg + n_pos) : 0.5;
      const double p_neg = (below + prior * share) / (double(q) + prior);
      return p_neg * subtree(n_neg) + (1 - p_neg) * subtree(n_pos) + options.split_weight * both / double(s) + extra;
    };
    std::size_t best = 0;
    double best_cost = 1e300;
    const std::size_t k = std::min(n, candidates);
    tried.clear();
    for (std::size_t c = 0; c < k; ++c) {
      const std::size_t i = k == n ? c : std::size_t(rng.next() % n);
      tried.push_back(pool[std::size_t(pieces[i])].outward);
      const double sc = cost(planes[tried.back()], 0.0);
      if (sc < best_cost) best_cost = sc, best = i;
    }
    // Auxiliary planes: x, y or z through the median of the pieces' box centres (balance in
    // fragments) or of the cell's points (balance in volume), half a grid step off the grid.
    std::int32_t aux = -1;
    if (!options.auxiliary_splits) return {best, aux};
    kernel::Plane aux_value{};
    // Only across the longest extent of the sampled pieces' centres, and of the points (kd-tree
    // style): the other axes rarely win and scoring is most of the build's time.
    for (int by_points = 0; by_points < 2; ++by_points) {
      const std::size_t count = by_points ? q : s;
      if (count < (by_points ? 16u : 2u)) continue;
      double lo_c[3] = {1e300, 1e300, 1e300}, hi_c[3] = {-1e300, -1e300, -1e300};
      for (std::size_t j = 0; j < count; ++j)
        for (int a = 0; a < 3; ++a) {
          double v = 0;
          if (by_points) {
            v = points[std::size_t(cell_points[j * m / q])][std::size_t(a)];
          } else {
            const CornerBox& b = boxes[std::size_t(pieces[j * n / s])];
            v = b.valid ? 0.5 * (b.lo[a] + b.hi[a]) : 0.0;
          }
          lo_c[a] = std::min(lo_c[a], v), hi_c[a] = std::max(hi_c[a], v);
        }
      int longest = 0;
      for (int a = 1; a < 3; ++a)
        if (hi_c[a] - lo_c[a] > hi_c[longest] - lo_c[longest]) longest = a;
      {
        const int axis = longest;
        medians.resize(count);
        for (std::size_t j = 0; j < count; ++j) {
          if (by_points) {
            medians[j] = points[std::size_t(cell_points[j * m / q])][std::size_t(axis)];
          } else {
            const CornerBox& b = boxes[std::size_t(pieces[j * n / s])];
            medians[j] = b.valid ? 0.5 * (b.lo[axis] + b.hi[axis]) : 0.0;
          }
        }
        std::nth_element(medians.begin(), medians.begin() + std::ptrdiff_t(count / 2), medians.end());
        kernel::Plane e{};
        if (!half_step_plane(axis, medians[count / 2], e)) continue;
        const double sc = cost(e, options.auxiliary_cost);
        if (sc < best_cost) best_cost = sc, aux_value = e, aux = 0;
      }
    }
    // Planes just beyond the cell's pieces (half a grid step past their boxes' extremes), which
    // cut off a region without boundary where the cell's points say it has volume.
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    bool boxed = q >= 16;
    for (std::size_t j = 0; j < n && boxed; ++j) {
      const CornerBox& b = boxes[std::size_t(pieces[j])];
      boxed = b.valid;
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], b.lo[a]), hi[a] = std::max(hi[a], b.hi[a]);
    }
    if (boxed) {
      for (int axis = 0; axis < 3; ++axis) {
        kernel::Plane e{};
        if (half_step_plane(axis, std::ceil(hi[axis]), e)) {
          const double sc = cost(e, options.auxiliary_cost);
          if (sc < best_cost) best_cost = sc, aux_value = e, aux = 0;
        }
        if (half_step_plane(axis, std::floor(lo[axis]) - 1.0, e)) {
          const double sc = cost(e, options.auxiliary_cost);
          if (sc < best_cost) best_cost = sc, aux_value = e, aux = 0;
        }
      }
    }
    // Separating planes (Naylor 1993): each scored face plane moved just past all of the cell's
    // pieces, behind them (inside a curved part) or in front; split_all finds the exact sides.
    if (boxed && options.separating_planes) {
      for (const std::int32_t t : tried) {
        const kernel::Plane& e = planes[t];
        const double a = double(e.a), b = double(e.b), c = double(e.c);
        double vmin = 1e300, vmax = -1e300, err = 0;
        for (const std::int32_t id : pieces)
          for (const kernel::Corner& corner : pool[std::size_t(id)].polygon.corners) {
            const double v = a * corner.at().x + b * corner.at().y + c * corner.at().z;
            vmin = std::min(vmin, v), vmax = std::max(vmax, v), err = std::max(err, corner.at().err);
          }
        const double margin = (std::fabs(a) + std::fabs(b) + std::fabs(c)) * (1.0 + err) + 1e-12 * std::max(std::fabs(vmin), std::fabs(vmax));
        for (const double offset : {std::floor(vmin - margin), std::ceil(vmax + margin)}) {
          if (!(std::fabs(offset) < 0x1p100)) continue;
          const kernel::Plane sep = kernel::make_plane(e.a, e.b, e.c, -kernel::Int128(offset));
          const double sc = cost(sep, options.auxiliary_cost);
          if (sc < best_cost) best_cost = sc, aux_value = sep, aux = 0;
        }
      }
    }
    if (aux == 0) aux = arena.planes.add(aux_value, true);
    return {best, aux};
  };
  ConvexPolygon neg_part, pos_part;
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  while (!stack.empty()) {
    poll.tick();
    Frame f = std::move(stack.back());
    stack.pop_back();
    const std::size_t n = f.pieces.size();
    // Score a few candidate planes against a sample of the cell's pieces.
    std::size_t best = 0;
    std::int32_t aux_plane = -1;
    if (by_depth) {
      const auto chosen = choose_by_depth(f.pieces, f.points);
      best = chosen.first;
      aux_plane = chosen.second;
    } else {
      double best_score = 1e300;
      int best_larger = 0;  // the larger side of the best candidate, in sampled pieces
      const std::size_t k = std::min(n, candidates), m = std::min(n, sample);
      auto score = [&](std::int32_t plane, int& larger) {
        int neg = 0, pos = 0, both = 0;
        for (std::size_t j = 0; j < m; ++j) {
          const auto q = std::size_t(f.pieces[j * n / m]);
          const Side s = side_of(planes, pool[q], boxes[q], plane, options.approximate_scores);
          neg += s == Side::Negative;
          pos += s == Side::Positive;
          both += s == Side::Both;
        }
        larger = std::max(neg, pos);
        return options.split_weight * both + std::abs(neg - pos);
      };
      for (std::size_t c = 0; c < k && n > 1; ++c) {
        const std::size_t i = c * n / k;
        int larger = 0;
        const double sc = score(pool[std::size_t(f.pieces[i])].outward, larger);
        if (sc < best_score) best_score = sc, best = i, best_larger = larger;
      }
      // Where every candidate leaves nearly all pieces on one side (a convex part: its faces see
      // each other from behind), a plane x, y or z = median of the pieces' box centres + 1/2 grid
      // step, which carries no piece, may balance better (kd-tree style; Naylor 1990's balance).
      if (options.auxiliary_splits && n >= kAuxiliarySplitFrom && best_larger * 10 > int(m) * 9) {
        std::vector<double> centre(m);
        for (int axis = 0; axis < 3; ++axis) {
          for (std::size_t j = 0; j < m; ++j) {
            const CornerBox& b = boxes[std::size_t(f.pieces[j * n / m])];
            centre[j] = b.valid ? 0.5 * (b.lo[axis] + b.hi[axis]) : 0.0;
          }
          std::nth_element(centre.begin(), centre.begin() + std::ptrdiff_t(m / 2), centre.end());
          const double c = std::floor(centre[m / 2]);
          if (!(std::fabs(c) < double(kernel::PlaneTable::kWorld))) continue;
          kernel::Int128 normal[3] = {0, 0, 0};
          normal[axis] = 2;
          const std::int32_t candidate =
              arena.planes.add(kernel::make_plane(normal[0], normal[1], normal[2], -(2 * kernel::Int128(c) + 1)), true);
          int larger = 0;
          const double sc = score(candidate, larger);
          if (sc < best_score) best_score = sc, aux_plane = candidate;
        }
      }
    }
    // Splits the cell's pieces by `plane`; pieces on it are used up (false if that happens for an
    // auxiliary plane, which must carry none).
    std::vector<std::int32_t> negative, positive;
    auto split_all = [&](std::int32_t plane, std::int32_t opposite, bool auxiliary) {
      negative.clear();
      positive.clear();
      const kernel::Plane pv = planes[plane], po = planes[opposite];
      for (const std::int32_t id : f.pieces) {
        const std::int32_t s = pool[std::size_t(id)].polygon.support;
        if (s == plane || s == opposite || planes[s] == pv || planes[s] == po) {
          if (auxiliary) return false;
          continue;  // used up
        }
        Side side = kernel::box_side(boxes[std::size_t(id)], pv);
        if (side == Side::Both)
          side = kernel::split(planes, pool[std::size_t(id)].polygon, plane, opposite, neg_part, pos_part);
        switch (side) {
          case Side::Negative: negative.push_back(id); break;
          case Side::Positive: positive.push_back(id); break;
          case Side::Both: {
            const std::int32_t outward = pool[std::size_t(id)].outward;  // the pool may grow
            negative.push_back(std::int32_t(pool.size()));
            pool.push_back({neg_part, outward});
            boxes.push_back(kernel::corner_box(neg_part));
            positive.push_back(std::int32_t(pool.size()));
            pool.push_back({pos_part, outward});
            boxes.push_back(kernel::corner_box(pos_part));
            break;
          }
          case Side::On: break;  // cannot happen: a piece on the plane has that support
        }
      }
      return true;
    };
    // An auxiliary plane must have pieces on both sides (an empty side's status would be unknown),
    // or (ExpectedDepth) cut the cell, the empty side's status found later (PendingSide).
    bool auxiliary = aux_plane >= 0 && split_all(aux_plane, arena.opposite(aux_plane), true);
    bool pending = false;
    if (auxiliary && (negative.empty() || positive.empty())) {
      auxiliary = false;
      if (by_depth && !(negative.empty() && positive.empty())) {
        path.clear();
        for (std::int32_t up = f.parent, side = f.side; up >= 0;) {
          const Node& a = nodes[std::size_t(up)];
          path.push_back(side == 0 ? a.plane : arena.opposite(a.plane));
          side = a.side;
          up = a.parent;
        }
        path.insert(path.end(), cell.rbegin(), cell.rend());
        std::reverse(path.begin(), path.end());
        ConvexPolygon cut;
        std::int32_t on = -1;
        if (clip_to_cell(arena.planes, aux_plane, path, cut, on) == CellCut::Cuts) {
          auxiliary = pending = true;
          pending_sides.push_back({TreeRef(nodes.size()), negative.empty() ? 0 : 1, std::move(cut)});
        }
      }
    }
    std::int32_t plane = aux_plane;
    if (!auxiliary) {
      plane = pool[std::size_t(f.pieces[best])].outward;
      split_all(plane, arena.opposite(plane), false);
    }
    const auto id = TreeRef(nodes.size());
    nodes.push_back({plane, negative.empty() && !pending ? kIn : kOut, kOut, auxiliary, f.parent, f.side});
    if (f.parent < 0)
      root = id;
    else
      (f.side == 0 ? nodes[std::size_t(f.parent)].negative : nodes[std::size_t(f.parent)].positive) = id;
    // The cell's points go with their sides (those of a leaf side are done with).
    std::vector<std::int32_t> neg_points, pos_points;
    if (by_depth) {
      const kernel::Plane e = planes[plane];
      for (const std::int32_t x : f.points) {
        const bool below = plane_value(e, points[std::size_t(x)]) < 0;
        if (below ? !negative.empty() : !positive.empty()) (below ? neg_points : pos_points).push_back(x);
      }
    }
    if (!negative.empty()) stack.push_back({std::move(negative), id, 0, std::move(neg_points)});
    if (!positive.empty()) stack.push_back({std::move(positive), id, 1, std::move(pos_points)});
  }

  // Pending sides, children first (they have larger indices, and a walk may reach them).
  for (auto it = pending_sides.rbegin(); it != pending_sides.rend(); ++it) {
    Node& nd = nodes[std::size_t(it->node)];
    TreeRef t = it->empty_side == 0 ? nd.positive : nd.negative;
    ConvexPolygon& poly = it->polygon;
    while (!is_leaf(t)) {
      const Node& below = nodes[std::size_t(t)];
      const Side s = kernel::split(planes, poly, below.plane, arena.opposite(below.plane), neg_part, pos_part);
      if (s == Side::Both) poly = neg_part;
      t = s == Side::Positive ? below.positive : below.negative;
    }
    (it->empty_side == 0 ? nd.negative : nd.positive) = t;
  }
  return tree;
}

Solid autopartition(Arena& arena, FragmentList fragments, const AutopartitionOptions& options) {
  if (fragments.empty()) return Solid();
  const kernel::PlaneTable& planes = arena.planes;
  const PartitionTree tree = partition_fragments(arena, fragments, options, {});
  const std::vector<Node>& nodes = tree.nodes;
  const TreeRef root = tree.root;

  // Bottom-up into the builder (children have larger indices), with the planes in use.
  TreeBuilder b;
  std::vector<std::int32_t> plane_map(std::size_t(planes.size()), -1);
  for (std::int32_t i = 0; i < kernel::kWorldPlanes; ++i) plane_map[std::size_t(i)] = i;  // shared world box
  auto use = [&](std::int32_t p, bool auxiliary = false) {
    if (plane_map[std::size_t(p)] < 0) plane_map[std::size_t(p)] = b.add_plane(planes[p], auxiliary);
    return plane_map[std::size_t(p)];
  };
  std::vector<TreeRef> made(nodes.size(), kOut);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& nd = nodes[i];
    auto child = [&](TreeRef c) { return is_leaf(c) ? c : made[std::size_t(c)]; };
    made[i] = b.add_node(use(nd.plane, nd.auxiliary), child(nd.negative), child(nd.positive));
  }
  if (!options.carry_boundary) return std::move(b).build(made[std::size_t(root)], BuildOptions{.nodes_cut_cells = true});
  fragments.renumber_planes([&](std::int32_t p) { return use(p); });
  return std::move(b).build(made[std::size_t(root)], std::move(fragments), {.nodes_cut_cells = true});
}

TreeRef autopartition_into(Arena& arena, const FragmentList& fragments, std::span<const std::int32_t> cell,
                           const AutopartitionOptions& options) {
  const PartitionTree tree = partition_fragments(arena, fragments, options, cell);
  if (is_leaf(tree.root)) return tree.root;
  const auto first = TreeRef(arena.nodes.size());
  auto slot = [first](TreeRef c) { return is_leaf(c) ? c : first + c; };
  for (const Node& nd : tree.nodes) {
    arena.nodes.push_back({nd.plane, slot(nd.negative), slot(nd.positive)});
    arena.polygons.emplace_back();  // pending: the node cuts its cell
    arena.polygons.back().support = nd.plane;
  }
  return slot(tree.root);
}

}  // namespace sculpt::bsp::detail
