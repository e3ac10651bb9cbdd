#include "bsp/local/cell_merge.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <memory>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "base/assert.hpp"
#include "base/cancel.hpp"
#include "base/dispose.hpp"
#include "base/parallel.hpp"
#include "bsp/local/cell_reach.hpp"
#include "bsp/local/deferred_build.hpp"
#include "bsp/partition/autopartition.hpp"
#include "bsp/tree/boundary_clipper.hpp"
#include "bsp/tree/result_planes.hpp"

namespace sculpt::bsp::detail {

using kernel::ConvexPolygon;
using kernel::CornerBox;
using kernel::Side;

namespace {

constexpr TreeRef kUnbuilt = -100;      // a leaf's local tree not built yet
constexpr std::size_t kLeafChunk = 16;  // leaves per parallel chunk (fixed: results never depend on threads)

// Keeps a piece whose two sides get `in_behind` / `in_front` in the result: drop, keep, reverse.
int verdict(bool in_behind, bool in_front) { return in_behind == in_front ? kDrop : (in_behind ? kKeep : kReverse); }

struct Operand {
  const FragmentList* list = nullptr;  // the solid's own fragments (read only, never copied whole)
  std::int32_t shift = 0;              // its planes' offset in the arena (the smaller operand's follow the larger's)
  [[nodiscard]] const FragmentList& faces() const { return *list; }
  // Fragment i on the arena's planes: the solid's own when its planes were not moved, else a copy
  // renumbered in `buf`.
  FragmentRef fragment(std::size_t i, BoundaryFragment& buf) const {
    const FragmentRef f = (*list)[i];
    if (shift == 0) return f;
    buf.polygon.assign(f.polygon);  // reuses buf's room
    buf.flip = f.flip;
    auto map = [this](std::int32_t p) { return p < kernel::kWorldPlanes ? p : p + shift; };
    buf.polygon.support = map(buf.polygon.support);
    for (auto& c : buf.polygon.corners) c.edge = map(c.edge), c.p = map(c.p), c.q = map(c.q);
    return {buf.polygon, buf.flip};
  }
  // Fragment i's support plane on the arena's planes (without copying the fragment).
  [[nodiscard]] std::int32_t support(std::size_t i) const {
    const std::int32_t p = (*list)[i].polygon.support;
    return p < kernel::kWorldPlanes ? p : p + shift;
  }
  std::vector<FragmentBox> boxes;
  CornerBox box;            // around the boundary; invalid when it reaches the world box
  std::optional<bool> far;  // status outside `box`
};

// One operand's pieces in a leaf: fragments clipped to the leaf, and the fragment each came from.
struct Pieces {
  FragmentList faces;
  std::vector<std::uint32_t> origin;
};

enum class CellClip { Outside, Inside, Cut };
// `poly` clipped to the closed cell whose walls are `walls` (the cell on their negative sides):
// Outside when nothing of positive area is left, Inside when all of it is in the cell (`out` is
// then not written), Cut with the part in the cell in `out`.
CellClip clip_to_cell(const kernel::PlaneTable& planes, kernel::PolygonView poly,
                      const std::array<std::int32_t, 6>& walls, ConvexPolygon& out, ConvexPolygon& scratch) {
  CornerBox box = kernel::corner_box(poly);
  bool inside = true;
  for (const std::int32_t w : walls) inside = inside && kernel::box_side(box, planes[w]) == Side::Negative;
  if (inside) return CellClip::Inside;
  out.assign(poly);
  for (const std::int32_t w : walls) {
    const Side s = kernel::clip_to_negative(planes, out, scratch, box, w);
    SCULPT_ASSERT(s != Side::On, "cell_merge: a fragment lies on a cell wall");
    if (s == Side::Positive || s == Side::On) return CellClip::Outside;
    if (s == Side::Both) std::swap(out, scratch);
  }
  return out.empty() ? CellClip::Outside : CellClip::Cut;
}

class CellMerge {
 public:
  CellMerge(Arena& arena, std::array<Operand, 2>& ops, const bool op[2][2], const KdOptions& options)
      : arena_(arena), ops_(ops) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) op_[i][j] = op[i][j];
    cells_ =
        subdivide({std::span<const FragmentBox>(ops[0].boxes), std::span<const FragmentBox>(ops[1].boxes)}, options);
  }

  // The result's fragments; `uniform` is set to the result's status when none is kept.
  FragmentList run(std::optional<bool>& uniform) {
    // Ctrl-C (base/cancel.hpp) between the steps and per leaf inside them: the operands are
    // never written, so a stopped operation leaves nothing behind.
    make_walls();
    check_cancel();
    clip_leaves();
    check_cancel();
    count_pieces();
    make_mixed_opposites();
    build_status_trees();
    check_cancel();
    for (std::size_t l = 0; l < leaf_count(); ++l)
      for (int x = 0; x < 2; ++x)
        if (needs_status(l, x)) status(node_of(l), x);
    check_cancel();
    for (const BspNode& n : arena_.nodes) arena_.opposite(n.plane);  // the pushes then only read the arena
    return emit(uniform);
  }

 private:
  [[nodiscard]] std::size_t leaf_count() const { return cells_.leaves.size(); }
  [[nodiscard]] std::int32_t node_of(std::size_t leaf) const { return cells_.leaves[leaf]; }
  [[nodiscard]] bool mixed(std::size_t l) const {
    return !pieces_[l][0].origin.empty() && !pieces_[l][1].origin.empty();
  }
  // Leaf l holds pieces of the other operand but none of x: x's status there is needed (step 4).
  [[nodiscard]] bool needs_status(std::size_t l, int x) const {
    return pieces_[l][x].origin.empty() && !pieces_[l][1 - x].origin.empty();
  }

  // The walls of every kd node as arena planes (upper then lower per axis), each plane made once;
  // each node's range of leaves (leaves are in depth-first order).
  void make_walls() {
    std::unordered_map<std::int64_t, std::int32_t> made[3][2];  // per axis and orientation
    auto wall = [&](int axis, std::int64_t at, bool upper) {
      auto [it, fresh] = made[axis][upper].try_emplace(at, -1);
      if (fresh) {
        std::int64_t n[3] = {0, 0, 0};
        n[axis] = upper ? 2 : -2;  // upper: 2x - at <= 0; lower: -2x + at <= 0
        it->second =
            arena_.planes.add(kernel::Plane(n[0], n[1], n[2], upper ? -kernel::Int128(at) : kernel::Int128(at)));
      }
      return it->second;
    };
    walls_.resize(cells_.nodes.size());
    for (std::size_t i = 0; i < cells_.nodes.size(); ++i) {
      const CellBounds& b = cells_.nodes[i].bounds;
      for (int k = 0; k < 3; ++k) {
        walls_[i][std::size_t(2 * k)] = wall(k, b.hi[k], true);
        walls_[i][std::size_t(2 * k + 1)] = wall(k, b.lo[k], false);
      }
    }
    leaf_index_.assign(cells_.nodes.size(), -1);
    leaf_range_.assign(cells_.nodes.size(), {0, 0});
    for (std::size_t l = 0; l < leaf_count(); ++l) leaf_index_[std::size_t(node_of(l))] = std::int32_t(l);
    for (std::size_t i = cells_.nodes.size(); i-- > 0;) {
      const KdNode& n = cells_.nodes[i];
      if (n.axis < 0) {
        const auto l = std::uint32_t(leaf_index_[i]);
        leaf_range_[i] = {l, l + 1};
      } else {
        leaf_range_[i] = {leaf_range_[std::size_t(n.child[0])][0], leaf_range_[std::size_t(n.child[1])][1]};
      }
    }
  }

  // Step 2: every fragment clipped to each leaf its box meets (reads the arena only). Only which
  // fragments reach the leaf is kept: the pieces' polygons are made again where they are used
  // (a mixed leaf's in emit, a status leaf's in pieces_of), one leaf at a time, so they are never
  // all held at once (a fifth of a real-mesh union's peak memory).
  void clip_leaves() {
    pieces_.resize(leaf_count());
    parallel_chunks(leaf_count(), kLeafChunk, [&](std::size_t begin, std::size_t end) {
      ConvexPolygon piece, scratch;
      BoundaryFragment renumbered;
      check_cancel();
      for (std::size_t l = begin; l < end; ++l) {
        const KdNode& n = cells_.nodes[std::size_t(node_of(l))];
        for (int x = 0; x < 2; ++x) {
          Pieces& p = pieces_[l][x];
          for (const std::uint32_t i : n.items[x]) {
            // Reading the approximations first decides most fragments: the exact clip is for
            // the rest (those that miss the leaf, and slivers along its walls).
            const FragmentRef f = ops_[x].fragment(i, renumbered);
            if (certainly_reaches(f.polygon, n.bounds) ||
                clip_to_cell(arena_.planes, f.polygon, walls_[std::size_t(node_of(l))], piece, scratch) !=
                    CellClip::Outside)
              p.origin.push_back(i);
          }
        }
      }
    });
    for (KdNode& n : cells_.nodes) n.items = {};
  }

  // Operand x's pieces in leaf l (its fragments that reach the leaf, clipped to it), appended to
  // `out` in the order of their origins.
  void make_pieces(std::size_t l, int x, FragmentList& out) const {
    ConvexPolygon piece, scratch;
    BoundaryFragment renumbered;
    for (const std::uint32_t i : pieces_[l][x].origin) {
      const FragmentRef f = ops_[x].fragment(i, renumbered);
      const CellClip c = clip_to_cell(arena_.planes, f.polygon, walls_[std::size_t(node_of(l))], piece, scratch);
      out.push_back(c == CellClip::Inside ? f.polygon : kernel::PolygonView(piece), f.flip);
    }
  }
  // Operand x's pieces in leaf l, kept for the status trees (step 4).
  const FragmentList& pieces_of(std::size_t l, int x) {
    Pieces& p = pieces_[l][x];
    if (p.faces.size() != p.origin.size()) make_pieces(l, x, p.faces);
    return p.faces;
  }

  // Pieces per kd node and operand (bottom-up).
  void count_pieces() {
    count_.assign(cells_.nodes.size(), {0, 0});
    for (std::size_t l = 0; l < leaf_count(); ++l)
      for (int x = 0; x < 2; ++x) count_[std::size_t(node_of(l))][x] = pieces_[l][x].origin.size();
    for (std::size_t i = cells_.nodes.size(); i-- > 1;) {
      const std::int32_t up = cells_.nodes[i].parent;
      for (int x = 0; x < 2; ++x) count_[std::size_t(up)][x] += count_[i][x];
    }
    status_.assign(cells_.nodes.size(), {-1, -1});
  }

  // Step 3: local trees (Thibault & Naylor's autopartition over one leaf's pieces), with face
  // planes only: an auxiliary plane (half a grid step off the grid) would cut the other operand's
  // pieces next to its edges into slivers, and a leaf's few pieces need no balancing. A mixed
  // leaf's trees are built in emit by the task that pushes its pieces (face planes only, so the
  // builds only read the arena); those status() reads go to the arena's nodes (no node polygons:
  // nothing here reads them).
  // Local trees score 3 candidate planes against 24 sampled pieces per node instead of the
  // default 5 and 48: scoring was most of their build (a leaf's few pieces need no finer choice),
  // and the outputs were the same (session 45: sphere minus sphere 128 10-12 % faster, the
  // armadillo job 7-8 %; docs/benchmarks.md).
  static constexpr AutopartitionOptions kLocal{.candidates = 3, .sample = 24, .auxiliary_splits = false};
  // A leaf holding one operand's pieces only needs its tree for statuses (step 4): nothing is
  // pushed down it, so it may take the balancing auxiliary planes. A convex piece of surface on
  // face planes alone is a chain, one node per piece, quadratic to build: at 2048 segments a
  // sphere's leaves held enough pieces for 85 s. Auxiliary planes are added to the arena, only
  // where a node holds at least kAuxiliarySplitFrom pieces (autopartition.hpp): those trees are built
  // on branches of the arena (build_status_trees).
  static constexpr AutopartitionOptions kStatusOnly{.candidates = 3, .sample = 24};
  TreeRef append_tree(const PartitionTree& tree) {
    if (is_leaf(tree.root)) return tree.root;
    const auto first = TreeRef(arena_.nodes.size());
    auto slot = [first](TreeRef c) { return is_leaf(c) ? c : first + c; };
    for (const PartitionNode& n : tree.nodes) arena_.nodes.push_back({n.plane, slot(n.negative), slot(n.positive)});
    return slot(tree.root);
  }
  // Operand x's local tree in leaf l, built on first use (serial: it may add arena planes).
  // A mixed leaf's trees are also read by emit (pieces pushed down them), so they take face
  // planes only (kLocal) wherever they are built.
  TreeRef local_tree(std::size_t l, int x) {
    TreeRef& t = trees_[l][x];
    if (t == kUnbuilt)
      t = append_tree(partition_fragments(arena_, pieces_of(l, x), mixed(l) ? kLocal : kStatusOnly,
                                          walls_[std::size_t(node_of(l))]));
    return t;
  }
  // The opposites of the planes of the mixed leaves' pieces, in leaf order: their local trees
  // (face planes only) are built in emit on every core, and then only read the arena.
  void make_mixed_opposites() {
    trees_.assign(leaf_count(), {kUnbuilt, kUnbuilt});
    for (std::size_t l = 0; l < leaf_count(); ++l)
      if (mixed(l))
        for (int x = 0; x < 2; ++x)
          for (const std::uint32_t i : pieces_[l][x].origin) arena_.opposite(ops_[x].support(i));
  }

  // The local trees step 4 reads, made ahead on every core: the leaves status() will read are
  // found by its walk on the kd-tree alone (across()), then their trees are built in parallel and
  // appended in leaf order. Building them one by one as status() first asked took 2.3 s of
  // `sphere(1, 1024) - moved copy`'s 4 on one core.
  void build_status_trees() {
    std::vector<std::array<char, 2>> seen(cells_.nodes.size(), {0, 0});
    std::vector<std::array<char, 2>> wanted(leaf_count(), {0, 0});
    for (std::size_t l = 0; l < leaf_count(); ++l)
      for (int x = 0; x < 2; ++x) {
        if (!needs_status(l, x)) continue;
        // status()'s recursion as a loop: it goes on where the leaf found holds none of x either.
        for (std::int32_t id = node_of(l); !seen[std::size_t(id)][x] && !outside_box(id, x);) {
          seen[std::size_t(id)][x] = 1;
          const Across a = across(id, x);
          seen[std::size_t(a.top)][x] = 1;
          if (count_[std::size_t(a.m)][x] > 0) {
            wanted[std::size_t(leaf_index_[std::size_t(a.m)])][x] = 1;
            break;
          }
          id = a.m;
        }
      }
    std::vector<std::pair<std::size_t, int>> todo;
    for (std::size_t l = 0; l < leaf_count(); ++l)
      for (int x = 0; x < 2; ++x)
        if (wanted[l][x] && trees_[l][x] == kUnbuilt) todo.emplace_back(l, x);
    // The pieces' polygons (each task writes its own leaf's), then their planes' opposites.
    parallel_chunks(todo.size(), kLeafChunk, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) pieces_of(todo[k].first, todo[k].second);
    });
    for (const auto& [l, x] : todo)
      for (const FragmentRef f : pieces_[l][x].faces) arena_.opposite(f.polygon.support);
    // A tree of kAuxiliarySplitFrom pieces or more may add auxiliary planes: it is built on a
    // branch of the arena, whose planes are then added in order, as a build on the arena itself
    // would have added them (the same planes, the same indices, for any thread count).
    std::vector<PartitionTree> built(todo.size());
    std::vector<std::optional<Arena::BranchPlanes>> added(todo.size());
    arena_.opposite_of.resize(std::size_t(arena_.planes.size()), -1);  // read from every core below
    auto large = [&](std::size_t k) {
      const auto [l, x] = todo[k];
      return !mixed(l) && pieces_[l][x].faces.size() >= kAuxiliarySplitFrom;
    };
    parallel_chunks(todo.size(), 1, [&](std::size_t k, std::size_t) {
      check_cancel();
      const auto [l, x] = todo[k];
      const AutopartitionOptions& options = mixed(l) ? kLocal : kStatusOnly;
      const std::span<const std::int32_t> cell = walls_[std::size_t(node_of(l))];
      if (!large(k)) {
        built[k] = partition_fragments(arena_, pieces_[l][x].faces, options, cell);
        return;
      }
      Arena branch = arena_.branch();
      built[k] = partition_fragments(branch, pieces_[l][x].faces, options, cell);
      added[k] = branch.added_planes();
    });
    for (std::size_t k = 0; k < todo.size(); ++k) {
      if (added[k]) {
        const Arena::PlaneMap map = arena_.take_planes(*added[k]);
        added[k].reset();
        for (PartitionNode& n : built[k].nodes) n.plane = map(n.plane);
      }
      trees_[todo[k].first][todo[k].second] = append_tree(built[k]);
    }
  }

  // Where status(id, x) reads operand x's status, on the kd-tree alone: the largest node `top`
  // around `id` that holds none of x's pieces shares a wall with its sibling; `m` is a leaf of
  // the sibling on that wall (where the sibling splits across the wall, the side with fewer of
  // x's pieces, but some: a small local tree to build).
  struct Across {
    std::int32_t top, m;
    int axis;
    std::int64_t split;
    bool above;  // m lies above the wall
  };
  [[nodiscard]] Across across(std::int32_t id, int x) const {
    std::int32_t top = id;
    while (cells_.nodes[std::size_t(top)].parent >= 0 &&
           count_[std::size_t(cells_.nodes[std::size_t(top)].parent)][x] == 0)
      top = cells_.nodes[std::size_t(top)].parent;
    const KdNode& up = cells_.nodes[std::size_t(cells_.nodes[std::size_t(top)].parent)];
    const int side = up.child[0] == top ? 1 : 0;  // the sibling's side of the wall
    std::int32_t m = up.child[side];
    while (cells_.nodes[std::size_t(m)].axis >= 0) {
      const KdNode& n = cells_.nodes[std::size_t(m)];
      if (n.axis == up.axis) {
        m = n.child[1 - side];  // towards the wall
      } else {
        const std::size_t c0 = count_[std::size_t(n.child[0])][x], c1 = count_[std::size_t(n.child[1])][x];
        m = c0 > 0 && (c1 == 0 || c0 <= c1) ? n.child[0] : n.child[1];
      }
    }
    return {top, m, up.axis, up.split, side == 1};
  }

  // Step 4: operand x's status in kd node `id`, which holds none of x's pieces. The largest such
  // node around it shares a wall with its sibling, where x's pieces are; a leaf of the sibling on
  // that wall tells the status by the wall's polygon pushed down its local tree of x (or, if that
  // leaf has no piece of x either, by its own status, found deeper in the kd-tree: the recursion
  // is at most the kd-tree's depth).
  bool status(std::int32_t id, int x) {
    if (status_[std::size_t(id)][x] >= 0) return status_[std::size_t(id)][x] == 1;
    SCULPT_ASSERT(count_[std::size_t(id)][x] == 0, "cell_merge: status asked where the operand has boundary");
    bool s;
    if (outside_box(id, x)) {
      s = *ops_[x].far;
    } else {
      const Across a = across(id, x);
      s = count_[std::size_t(a.m)][x] == 0 ? status(a.m, x) : status_across(a.m, a.axis, a.split, a.above, x);
      status_[std::size_t(a.top)][x] = s ? 1 : 0;
    }
    status_[std::size_t(id)][x] = s ? 1 : 0;
    return s;
  }

  // True if kd node `id` reaches outside operand x's box (then part of it is far from x's
  // boundary, and all of it, holding none, has x's far status).
  bool outside_box(std::int32_t id, int x) const {
    const Operand& o = ops_[x];
    if (!o.box.valid || !o.far) return false;
    const CellBounds& b = cells_.nodes[std::size_t(id)].bounds;
    for (int k = 0; k < 3; ++k)
      if (0.5 * double(b.lo[k]) < o.box.lo[k] || 0.5 * double(b.hi[k]) > o.box.hi[k]) return true;
    return false;
  }

  // Operand x's status just across the wall `split` (axis `axis`) from kd leaf `m`, which lies
  // above the wall when `above`. The wall crosses no boundary of x there. First a few points of
  // m's face on the wall, walked down m's local tree of x: a point on none of its planes is on no
  // piece of x (each piece lies on a plane its region reaches), so its leaf's status is the
  // status across the wall. Failing that (every point tried lies on a plane), the face's polygon
  // pushed down the tree: every piece reaches the same status; the side behind the polygon (its
  // support has m on the negative side) is m's.
  bool status_across(std::int32_t m, int axis, std::int64_t split, bool above, int x) {
    const std::size_t l = std::size_t(leaf_index_[std::size_t(m)]);
    const TreeRef t = local_tree(l, x);
    const CellBounds& b = cells_.nodes[std::size_t(m)].bounds;
    for (int attempt = 0; attempt < 8; ++attempt) {
      // Doubled coordinates: the wall's (odd) on its axis, even values strictly inside on the others.
      std::int64_t p[3];
      for (int k = 0; k < 3; ++k) {
        if (k == axis) {
          p[k] = split;
          continue;
        }
        const std::int64_t first = (b.lo[k] + 1) / 2, last = (b.hi[k] - 1) / 2;  // integers inside
        const std::int64_t span = last - first + 1;
        const std::int64_t pick = attempt == 0 ? span / 2 : (attempt * 40503 + k * 9973) % span;
        p[k] = 2 * (first + pick);
      }
      if (const std::optional<bool> s = status_at(t, p)) return *s;
    }
    const std::array<std::int32_t, 6>& walls = walls_[std::size_t(m)];
    // m's wall on the split: its lower wall when it lies above the split, else its upper one.
    const std::int32_t support = walls[std::size_t(2 * axis + (above ? 1 : 0))];
    SCULPT_ASSERT(
        (above ? cells_.nodes[std::size_t(m)].bounds.lo : cells_.nodes[std::size_t(m)].bounds.hi)[axis] == split,
        "cell_merge: the leaf found does not touch the wall");
    ConvexPolygon face = kernel::world_polygon(arena_.planes, support), scratch;
    CornerBox box = kernel::corner_box(face);
    for (int k = 0; k < 6; ++k) {
      if (k / 2 == axis) continue;
      if (kernel::clip_to_negative(arena_.planes, face, scratch, box, walls[std::size_t(k)]) == Side::Both)
        std::swap(face, scratch);
    }
    Clipper clip(arena_);
    int behind = -1;
    clip.push(
        t, FragmentRef{face, false},
        [&](bool, bool back_in, bool) {
          if (behind < 0) behind = back_in ? 1 : 0;
          return kDrop;
        },
        [](ConvexPolygon, int) {});
    SCULPT_ASSERT(behind >= 0, "cell_merge: a wall polygon reached no cell");
    return behind == 1;
  }

  // The leaf of the arena tree `t` a point reaches (doubled grid coordinates), or nothing if it
  // lies on a plane on the way. Exact: 2 f(p) = a X + b Y + c Z + 2 d fits in 128 bits.
  std::optional<bool> status_at(TreeRef t, const std::int64_t (&p)[3]) const {
    while (!is_leaf(t)) {
      const BspNode& n = arena_.nodes[std::size_t(t)];
      const kernel::Plane& q = arena_.planes[n.plane];
      const kernel::Int128 v =
          kernel::Int128(q.a) * p[0] + kernel::Int128(q.b) * p[1] + kernel::Int128(q.c) * p[2] + 2 * q.d;
      if (v == 0) return std::nullopt;
      t = v < 0 ? n.negative : n.positive;
    }
    return t == kIn;
  }

  // The fates of operand x's pieces (x = 0: A, 1: B) where the other operand's status is
  // `behind` / `front` on the piece's two sides; A's piece stands for a shared plane region.
  int fate(int x, bool front_in, bool back_in, bool on_plane) const {
    if (x == 0) return verdict(op_[1][back_in], op_[0][front_in]);
    return on_plane && front_in != back_in ? kDrop : verdict(op_[back_in][1], op_[front_in][0]);
  }
  // The result's status just behind a piece of operand x whose other operand has status `other`.
  bool behind_status(int x, bool other) const { return x == 0 ? op_[1][other] : op_[other][1]; }

  // Steps 3 and 4's decisions. Each piece's fate: a mixed leaf's pieces pushed down the other
  // operand's local tree, the others by status (in chunks of leaves, reading the arena only). A
  // mixed leaf's pieces and trees are made by its task and dropped after it (MixedLeaf), so the
  // merge holds one leaf's per thread, not every leaf's.
  // Then each fragment is put back together where the walls cut it needlessly: below the highest
  // kd nodes where all its pieces had one fate, it is emitted as one polygon (the fragment
  // clipped to that node's cell: the fragment itself at the root), so cell walls leave no seams
  // where nothing changes across them (in fragment order, in chunks).
  FragmentList emit(std::optional<bool>& uniform) {
    whole_.resize(leaf_count());
    parts_.resize(leaf_count());
    mixed_parts_.resize(leaf_count());
    std::vector<int> first_behind((leaf_count() + kLeafChunk - 1) / kLeafChunk, -1);
    parallel_chunks(leaf_count(), kLeafChunk, [&](std::size_t begin, std::size_t end) {
      int& fb = first_behind[begin / kLeafChunk];
      check_cancel();
      Clipper clip(arena_);
      MixedLeaf leaf;
      for (std::size_t l = begin; l < end; ++l) {
        const bool mix = mixed(l);
        if (mix) prepare(l, leaf);
        for (int x = 0; x < 2; ++x) {
          const Pieces& p = pieces_[l][x];
          std::vector<std::int8_t>& whole = whole_[l][x];
          whole.assign(p.origin.size(), std::int8_t(kDrop));
          if (p.origin.empty()) continue;
          if (!mix) {
            const bool s = status_[std::size_t(node_of(l))][1 - x] == 1;
            if (fb < 0) fb = behind_status(x, s) ? 1 : 0;
            whole.assign(p.origin.size(), std::int8_t(fate(x, s, s, false)));
            continue;
          }
          FragmentList& parts = parts_[l][x];
          const FragmentList& faces = *leaf.faces[x];
          clip.read_nodes(*leaf.nodes[1 - x]);
          for (std::size_t j = 0; j < faces.size(); ++j) {
            const FragmentRef f = faces[j];
            const std::size_t before = parts.size();
            const int w = clip.push(
                leaf.tree[1 - x], f,
                [&](bool front_in, bool back_in, bool on) {
                  if (fb < 0) fb = behind_status(x, back_in) ? 1 : 0;
                  return fate(x, front_in, back_in, on);
                },
                [&](ConvexPolygon piece, int v) {
                  parts.push_back({std::move(piece), v == kKeep ? f.flip : !f.flip});
                });
            whole[j] = std::int8_t(w);
            if (w != kMixed) parts.truncate(before);  // whole: emitted (or not) with its fragment below
            if (w == kMixed)
              mixed_parts_[l][x].push_back({std::uint32_t(j), std::uint32_t(before), std::uint32_t(parts.size())});
          }
        }
      }
    });
    // The pieces' polygons are not read again (rejoining reads the fragments, the fates and the
    // split parts): freed before the result is written, so the two are never held at once
    // (about 100 MB at sphere(1, 1024) - moved copy).
    for (auto& both : pieces_)
      for (Pieces& p : both) p.faces = FragmentList();
    // Nor the local trees: rejoining and the compaction read the arena's planes only.
    arena_.nodes = std::vector<BspNode>();
    arena_.polygons = PolygonStore();
    // Each fragment's pieces, by leaf (leaves ascending): fragment i's are [first[i], first[i + 1]).
    for (int x = 0; x < 2; ++x) {
      std::vector<std::uint32_t>& first = by_fragment_first_[x];
      first.assign(ops_[x].faces().size() + 1, 0);
      for (std::size_t l = 0; l < leaf_count(); ++l)
        for (const std::uint32_t i : pieces_[l][x].origin) ++first[i + 1];
      for (std::size_t i = 1; i < first.size(); ++i) first[i] += first[i - 1];
      std::vector<std::uint32_t> at(first.begin(), first.end() - 1);
      by_fragment_[x].resize(first.back());
      for (std::size_t l = 0; l < leaf_count(); ++l)
        for (std::size_t j = 0; j < pieces_[l][x].origin.size(); ++j)
          by_fragment_[x][at[pieces_[l][x].origin[j]]++] = {std::uint32_t(l), std::uint32_t(j)};
    }
    // Both operands' fragments in chunks, in waves (parallel_waves): the result is written once,
    // in fragment order, and the scratch lists hold one wave, not a second copy of the whole result.
    // Chunks of 256 fragments rather than 1024: a wave's lists are scratch beside the result (about
    // 1 MB less at small jobs' peaks, the same time).
    constexpr std::size_t kFragmentChunk = 256;
    const std::size_t na = ops_[0].faces().size(), n = na + ops_[1].faces().size();
    FragmentList result;
    parallel_waves<FragmentList>(
        n, kFragmentChunk,
        [&](std::size_t begin, std::size_t end, FragmentList& mine) {
          check_cancel();
          ConvexPolygon piece, scratch;
          BoundaryFragment renumbered;
          std::vector<RejoinFrame> stack;
          for (std::size_t i = begin; i < end; ++i)
            rejoin(i < na ? 0 : 1, i < na ? i : i - na, mine, piece, scratch, renumbered, stack);
        },
        [&](FragmentList& mine) { result.append(std::move(mine)); });
    for (const int fb : first_behind)
      if (fb >= 0) {
        uniform = fb == 1;
        break;
      }
    return result;
  }

  // A mixed leaf's pieces and local trees of both operands, made for emit by one task: the pieces
  // status() kept and the trees it built where it did, else the task's own.
  struct MixedLeaf {
    std::array<FragmentList, 2> own_faces;
    std::array<std::vector<BspNode>, 2> own_nodes;
    std::array<const FragmentList*, 2> faces{};
    std::array<const std::vector<BspNode>*, 2> nodes{};
    std::array<TreeRef, 2> tree{};
  };
  void prepare(std::size_t l, MixedLeaf& leaf) const {
    for (int x = 0; x < 2; ++x) {
      const Pieces& p = pieces_[l][x];
      leaf.own_faces[x].clear();
      if (p.faces.size() == p.origin.size()) {
        leaf.faces[x] = &p.faces;
      } else {
        make_pieces(l, x, leaf.own_faces[x]);
        leaf.faces[x] = &leaf.own_faces[x];
      }
      if (trees_[l][x] != kUnbuilt) {
        leaf.tree[x] = trees_[l][x];
        leaf.nodes[x] = &arena_.nodes;
        continue;
      }
      const PartitionTree t = partition_fragments(arena_, *leaf.faces[x], kLocal, walls_[std::size_t(node_of(l))]);
      leaf.own_nodes[x].clear();
      for (const PartitionNode& n : t.nodes) leaf.own_nodes[x].push_back({n.plane, n.negative, n.positive});
      leaf.tree[x] = t.root;
      leaf.nodes[x] = &leaf.own_nodes[x];
    }
  }

  // Fragment i of operand x put back together (see emit): an explicit stack over the kd nodes
  // its pieces lie under, from the root.
  using RejoinFrame = std::pair<std::int32_t, std::array<std::size_t, 2>>;  // kd node, pieces [a, b)
  void rejoin(int x, std::size_t i, FragmentList& out, ConvexPolygon& piece, ConvexPolygon& scratch,
              BoundaryFragment& renumbered, std::vector<RejoinFrame>& stack) {
    const std::span<const std::array<std::uint32_t, 2>> mine(by_fragment_[x].data() + by_fragment_first_[x][i],
                                                             by_fragment_first_[x][i + 1] - by_fragment_first_[x][i]);
    if (mine.empty()) return;
    const FragmentRef f = ops_[x].fragment(i, renumbered);
    stack.assign(1, {0, {0, mine.size()}});
    while (!stack.empty()) {
      const auto [id, range] = stack.back();
      stack.pop_back();
      if (range[0] == range[1]) continue;
      const int first = whole_[mine[range[0]][0]][x][mine[range[0]][1]];
      bool same = first != kMixed;
      for (std::size_t k = range[0] + 1; k < range[1] && same; ++k) same = whole_[mine[k][0]][x][mine[k][1]] == first;
      const KdNode& n = cells_.nodes[std::size_t(id)];
      if (same) {
        if (first == kDrop) continue;
        const bool flip = first == kKeep ? f.flip : !f.flip;
        const CellClip c = id == 0 ? CellClip::Inside
                                   : clip_to_cell(arena_.planes, f.polygon, walls_[std::size_t(id)], piece, scratch);
        if (c != CellClip::Outside) out.push_back(c == CellClip::Inside ? f.polygon : kernel::PolygonView(piece), flip);
        continue;
      }
      if (n.axis < 0) {  // a leaf: its one piece, split by the other operand's local tree
        const std::size_t l = mine[range[0]][0], j = mine[range[0]][1];
        for (const auto& [index, begin, end] : mixed_parts_[l][x])
          if (index == j)
            for (std::size_t k = begin; k < end; ++k) {
              const FragmentRef g = parts_[l][x][k];
              out.push_back(g.polygon, g.flip);
            }
        continue;
      }
      // Split the pieces between the children by their leaves' ranges (children pushed upper first).
      const std::uint32_t mid = leaf_range_[std::size_t(n.child[1])][0];
      std::size_t k = range[0];
      while (k < range[1] && mine[k][0] < mid) ++k;
      stack.push_back({n.child[1], {k, range[1]}});
      stack.push_back({n.child[0], {range[0], k}});
    }
  }

  Arena& arena_;
  std::array<Operand, 2>& ops_;
  bool op_[2][2];
  KdCells cells_;
  std::vector<std::array<std::int32_t, 6>> walls_;        // per kd node
  std::vector<std::int32_t> leaf_index_;                  // per kd node: its leaf index, or -1
  std::vector<std::array<std::uint32_t, 2>> leaf_range_;  // per kd node: its leaves [first, end)
  std::vector<std::array<Pieces, 2>> pieces_;             // per leaf and operand
  std::vector<std::array<std::size_t, 2>> count_;         // per kd node and operand
  std::vector<std::array<TreeRef, 2>> trees_;             // per leaf and operand
  std::vector<std::array<std::int8_t, 2>> status_;        // per kd node and operand: -1 unknown
  // emit(): per leaf and operand, each piece's fate as a whole (kMixed: split), the parts of the
  // split ones and where each one's parts are (piece, first part, end); per fragment its pieces.
  std::vector<std::array<std::vector<std::int8_t>, 2>> whole_;
  std::vector<std::array<FragmentList, 2>> parts_;
  struct PartRange {
    std::uint32_t piece, begin, end;
  };
  std::vector<std::array<std::vector<PartRange>, 2>> mixed_parts_;
  std::array<std::vector<std::array<std::uint32_t, 2>>, 2> by_fragment_;  // (leaf, piece) per fragment, in order
  std::array<std::vector<std::uint32_t>, 2> by_fragment_first_;
};

// Operand s with its fragments' boxes, their bounds and its far status, on the arena's planes
// at `shift` (see merge_by_cells). The fragments stay where they are: a shifted operand's are
// renumbered as they are read (Operand::fragment), not copied whole.
Operand load(const Solid& s, std::int32_t shift) {
  const Solid::BoundaryView view = s.boundary_view();
  Operand o;
  o.shift = shift;
  o.list = view.fragments;
  // Boxes, and their union as the operand's box (invalid if a fragment reaches the world box:
  // the operand is unbounded there, or if a box is unknown).
  // In chunks on every core; each chunk's union of boxes, joined in order (min and max are exact).
  constexpr std::size_t kChunk = 4096;
  const std::size_t n = o.faces().size();
  o.boxes.resize(n);
  std::vector<CornerBox> chunk_box((n + kChunk - 1) / kChunk);
  parallel_chunks(n, kChunk, [&](std::size_t begin, std::size_t end) {
    check_cancel();  // Ctrl-C (base/cancel.hpp)
    CornerBox& box = chunk_box[begin / kChunk];
    box.valid = true;
    for (int k = 0; k < 3; ++k) box.lo[k] = 1e300, box.hi[k] = -1e300;
    for (std::size_t i = begin; i < end; ++i) {
      const FragmentRef f = o.faces()[i];
      const FragmentBox& b = o.boxes[i] = fragment_box(f.polygon);
      bool world = f.polygon.support < kernel::kWorldPlanes;
      for (const auto& c : f.polygon.corners)
        world |= c.edge < kernel::kWorldPlanes || c.p < kernel::kWorldPlanes || c.q < kernel::kWorldPlanes;
      box.valid = box.valid && b.valid && !world;
      for (int k = 0; k < 3; ++k)
        box.lo[k] = std::min(box.lo[k], double(b.lo[k])), box.hi[k] = std::max(box.hi[k], double(b.hi[k]));
    }
  });
  o.box.valid = true;
  for (int k = 0; k < 3; ++k) o.box.lo[k] = 1e300, o.box.hi[k] = -1e300;
  for (const CornerBox& box : chunk_box) {
    o.box.valid = o.box.valid && box.valid;
    for (int k = 0; k < 3; ++k)
      o.box.lo[k] = std::min(o.box.lo[k], box.lo[k]), o.box.hi[k] = std::max(o.box.hi[k], box.hi[k]);
  }
  o.far = far_status(s);
  return o;
}

// SCULPT_CELL_MERGE_MIN overrides the default (developers' A/B runs: 0 sends every operation with
// boundaries down the cell path); anything but a plain number is ignored.
std::size_t initial_threshold() {
  const char* v = std::getenv("SCULPT_CELL_MERGE_MIN");
  if (!v || !*v) return kDefaultCellMergeFragments;
  char* end = nullptr;
  const unsigned long long n = std::strtoull(v, &end, 10);
  return *end == '\0' ? std::size_t(n) : kDefaultCellMergeFragments;
}
std::atomic<std::size_t> g_threshold{initial_threshold()};

}  // namespace

std::size_t cell_merge_threshold() { return g_threshold.load(std::memory_order_relaxed); }
void set_cell_merge_threshold(std::size_t fragments) { g_threshold.store(fragments, std::memory_order_relaxed); }

std::optional<Solid> merge_by_cells(const Solid& a, const Solid& b, const bool op[2][2],
                                    const CellMergeOptions& options) {
  for (const Solid* s : {&a, &b}) {
    const Solid::BoundaryView v = s->boundary_view();
    if (!v.fragments || v.fragments->empty()) return std::nullopt;
  }
  // The planes of both, the walls and the opposites the local trees need, in one table: the
  // larger operand's table shared (no plane copied), the other's after it, its blocks shared too
  // when it fills one at least (kernel/plane_table.hpp), else copied (the world box planes are
  // common).
  auto owned_arena = std::make_unique<Arena>();
  Arena& arena = *owned_arena;
  const kernel::PlaneTable &pa = *a.boundary_view().planes, &pb = *b.boundary_view().planes;
  const bool a_base = pa.size() >= pb.size();
  const kernel::PlaneTable& other = a_base ? pb : pa;
  arena.planes = a_base ? pa : pb;
  const std::int32_t shift = other.size() >= kernel::PlaneTable::kBlock
                                 ? arena.planes.append_shared(other)
                                 : arena.planes.append(other, kernel::kWorldPlanes) - kernel::kWorldPlanes;
  std::array<Operand, 2> ops{load(a, a_base ? 0 : shift), load(b, a_base ? shift : 0)};
  std::optional<bool> uniform;
  auto merge = std::make_unique<CellMerge>(arena, ops, op, options.cells);
  for (Operand& o : ops) o.boxes = std::vector<FragmentBox>();  // read by the subdivision only (freed)
  FragmentList result;
  try {
    result = merge->run(uniform);
  } catch (const Cancelled&) {
    // Stopped by Ctrl-C: gigabytes of pieces and local trees are freed on another thread
    // (base/dispose.hpp), so that the stop answers at once. Their destructors read nothing else.
    dispose_in_background(std::make_tuple(std::move(merge), std::move(owned_arena), std::move(ops)));
    throw;
  }
  merge.reset();
  std::optional<bool> far;
  if (ops[0].far && ops[1].far) far = op[*ops[0].far][*ops[1].far];
  if (result.empty()) far = uniform;
  kernel::PlaneTable planes = result_planes(std::move(arena.planes), result);
  return solid_from_boundary(std::move(planes), std::move(result), far);
}

}  // namespace sculpt::bsp::detail
