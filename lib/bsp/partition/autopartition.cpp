// The autopartition driver (autopartition.hpp): cells on an explicit stack, each split by the
// plane plane_choice.hpp picks; then the tree into a Solid or an arena.
#include "bsp/partition/autopartition.hpp"

#include <algorithm>
#include <utility>

#include "base/cancel.hpp"
#include "bsp/partition/pending_sides.hpp"
#include "bsp/partition/piece_pool.hpp"
#include "bsp/partition/plane_choice.hpp"
#include "bsp/tree/node_polygons.hpp"
#include "bsp/tree_builder.hpp"

namespace sculpt::bsp::detail {

namespace {

// A cell still to be partitioned: its pieces and sample points (ranges of the Partitioner's
// stacks; a frame's ranges lie below those of every frame pushed after it) and the node it
// hangs from.
struct Frame {
  std::size_t pieces_begin, pieces_end;
  std::size_t points_begin, points_end;
  std::int32_t parent;  // -1: the root
  int side;             // of the parent
};

// The plane a cell is split by, and how.
struct CellSplit {
  std::int32_t plane = -1;
  bool auxiliary = false;  // carries no piece
  bool pending = false;    // auxiliary with one side empty (PendingSide)
};

class Partitioner {
 public:
  Partitioner(Arena& arena, const FragmentList& fragments, const AutopartitionOptions& options,
              std::span<const std::int32_t> cell)
      : arena_(arena),
        options_(options),
        cell_(cell),
        by_depth_(options.score == PartitionScore::ExpectedDepth),
        pool_(PiecePool::of(fragments, [&arena](std::int32_t s) { return arena.opposite(s); })) {
    if (by_depth_) sample_ = volume_sample(pool_, options, rng_);
    piece_stack_.resize(pool_.size());
    for (std::size_t i = 0; i < pool_.size(); ++i) piece_stack_[i] = std::int32_t(i);
    point_stack_.resize(sample_.size());
    for (std::size_t i = 0; i < sample_.size(); ++i) point_stack_[i] = std::int32_t(i);
    frames_.push_back({0, piece_stack_.size(), 0, point_stack_.size(), -1, 0});
  }

  PartitionTree run() && {
    CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
    while (!frames_.empty()) {
      poll.tick();
      const Frame f = frames_.back();
      frames_.pop_back();
      partition(f);
    }
    resolve_pending_sides(arena_, tree_.nodes, pending_);
    return std::move(tree_);
  }

 private:
  // One node: the cell's plane, its pieces split onto the sides, the sides pushed as frames.
  void partition(const Frame& f) {
    const std::span<const std::int32_t> pieces{piece_stack_.data() + f.pieces_begin, f.pieces_end - f.pieces_begin};
    const std::span<const std::int32_t> points{point_stack_.data() + f.points_begin, f.points_end - f.points_begin};
    const PlaneChoice choice = by_depth_ ? choose_by_depth(arena_, pool_, pieces, points, sample_, options_, rng_)
                                         : choose_by_balance(arena_, pool_, pieces, options_);
    const CellSplit cut = split(f, pieces, choice);
    const auto id = TreeRef(tree_.nodes.size());
    tree_.nodes.push_back(
        {cut.plane, sides_.negative.empty() && !cut.pending ? kIn : kOut, kOut, cut.auxiliary, f.parent, f.side});
    if (f.parent < 0)
      tree_.root = id;
    else
      (f.side == 0 ? tree_.nodes[std::size_t(f.parent)].negative : tree_.nodes[std::size_t(f.parent)].positive) = id;
    sort_points(points, cut.plane);
    // The children's ranges replace the cell's at the top of the stacks.
    piece_stack_.resize(f.pieces_begin);
    point_stack_.resize(f.points_begin);
    push(sides_.negative, neg_points_, id, 0);
    push(sides_.positive, pos_points_, id, 1);
  }

  // Splits the cell's pieces into sides_ by the chosen auxiliary plane where that one carries
  // none and leaves pieces on both sides (or, ExpectedDepth, cuts the cell: the empty side's
  // status is found later, PendingSide), else by the chosen face plane.
  CellSplit split(const Frame& f, std::span<const std::int32_t> pieces, const PlaneChoice& choice) {
    CellSplit cut;
    if (choice.auxiliary >= 0 &&
        split_cell(arena_.planes, pool_, pieces, choice.auxiliary, arena_.opposite(choice.auxiliary), true, sides_)) {
      cut = {choice.auxiliary, true, false};
      if (sides_.negative.empty() || sides_.positive.empty()) cut = pend(f, choice.auxiliary);
    }
    if (!cut.auxiliary) {
      cut.plane = pool_.pieces[std::size_t(pieces[choice.face])].outward;
      split_cell(arena_.planes, pool_, pieces, cut.plane, arena_.opposite(cut.plane), false, sides_);
    }
    return cut;
  }

  // An auxiliary plane with one side of the cell empty of pieces: kept (ExpectedDepth) if it
  // cuts the cell, the empty side pending; otherwise not auxiliary (the face plane is used).
  CellSplit pend(const Frame& f, std::int32_t plane) {
    if (!by_depth_ || (sides_.negative.empty() && sides_.positive.empty())) return {};
    path_.clear();
    for (std::int32_t up = f.parent, side = f.side; up >= 0;) {
      const PartitionNode& a = tree_.nodes[std::size_t(up)];
      path_.push_back(side == 0 ? a.plane : arena_.opposite(a.plane));
      side = a.side;
      up = a.parent;
    }
    path_.insert(path_.end(), cell_.rbegin(), cell_.rend());
    std::reverse(path_.begin(), path_.end());  // the given cell's walls, then the root's side down
    kernel::ConvexPolygon polygon;
    std::int32_t on = -1;
    if (clip_to_cell(arena_.planes, plane, path_, polygon, on) != CellCut::Cuts) return {};
    pending_.push_back({TreeRef(tree_.nodes.size()), sides_.negative.empty() ? 0 : 1, std::move(polygon)});
    return {plane, true, true};
  }

  // ExpectedDepth: the cell's points by side of `plane` into neg_points_ and pos_points_ (those
  // of a side without pieces, a leaf, are done with).
  void sort_points(std::span<const std::int32_t> points, std::int32_t plane) {
    neg_points_.clear();
    pos_points_.clear();
    if (!by_depth_) return;
    const kernel::Plane e = arena_.planes[plane];
    for (const std::int32_t x : points) {
      const bool below = plane_value(e, sample_[std::size_t(x)]) < 0;
      if (below ? !sides_.negative.empty() : !sides_.positive.empty()) (below ? neg_points_ : pos_points_).push_back(x);
    }
  }

  void push(const std::vector<std::int32_t>& pieces, const std::vector<std::int32_t>& points, TreeRef parent,
            int side) {
    if (pieces.empty()) return;
    const Frame f{piece_stack_.size(),
                  piece_stack_.size() + pieces.size(),
                  point_stack_.size(),
                  point_stack_.size() + points.size(),
                  parent,
                  side};
    piece_stack_.insert(piece_stack_.end(), pieces.begin(), pieces.end());
    point_stack_.insert(point_stack_.end(), points.begin(), points.end());
    frames_.push_back(f);
  }

  Arena& arena_;
  const AutopartitionOptions& options_;
  std::span<const std::int32_t> cell_;
  bool by_depth_;
  SplitMix rng_;
  PiecePool pool_;
  std::vector<SamplePoint> sample_;
  std::vector<std::int32_t> piece_stack_, point_stack_;
  std::vector<Frame> frames_;
  PartitionTree tree_;
  std::vector<PendingSide> pending_;
  // Scratch, reused from cell to cell.
  CellSides sides_;
  std::vector<std::int32_t> neg_points_, pos_points_, path_;
};

}  // namespace

PartitionTree partition_fragments(Arena& arena, const FragmentList& fragments, const AutopartitionOptions& options,
                                  std::span<const std::int32_t> cell) {
  if (fragments.empty()) return {};
  return Partitioner(arena, fragments, options, cell).run();
}

Solid autopartition(Arena& arena, FragmentList fragments, const AutopartitionOptions& options) {
  if (fragments.empty()) return Solid();
  const kernel::PlaneTable& planes = arena.planes;
  const PartitionTree tree = partition_fragments(arena, fragments, options, {});
  const std::vector<PartitionNode>& nodes = tree.nodes;

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
    const PartitionNode& nd = nodes[i];
    auto child = [&](TreeRef c) { return is_leaf(c) ? c : made[std::size_t(c)]; };
    made[i] = b.add_node(use(nd.plane, nd.auxiliary), child(nd.negative), child(nd.positive));
  }
  if (!options.carry_boundary)
    return std::move(b).build(made[std::size_t(tree.root)], BuildOptions{.nodes_cut_cells = true});
  fragments.renumber_planes([&](std::int32_t p) { return use(p); });
  return std::move(b).build(made[std::size_t(tree.root)], std::move(fragments), {.nodes_cut_cells = true});
}

TreeRef autopartition_into(Arena& arena, const FragmentList& fragments, std::span<const std::int32_t> cell,
                           const AutopartitionOptions& options) {
  const PartitionTree tree = partition_fragments(arena, fragments, options, cell);
  if (is_leaf(tree.root)) return tree.root;
  const auto first = TreeRef(arena.nodes.size());
  auto slot = [first](TreeRef c) { return is_leaf(c) ? c : first + c; };
  for (const PartitionNode& nd : tree.nodes) {
    arena.nodes.push_back({nd.plane, slot(nd.negative), slot(nd.positive)});
    arena.polygons.emplace_back();  // pending: the node cuts its cell
    arena.polygons.back().support = nd.plane;
  }
  return slot(tree.root);
}

}  // namespace sculpt::bsp::detail
