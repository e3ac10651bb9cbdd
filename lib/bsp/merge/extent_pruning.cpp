#include "bsp/merge/extent_pruning.hpp"

#include <boost/container/small_vector.hpp>

#include "bsp/tree/boundary_clipper.hpp"
#include "bsp/tree/node_polygons.hpp"

namespace sculpt::bsp::detail {

using kernel::Side;
using kernel::Sign;

namespace {

kernel::CornerBox widen(const FragmentBox& f) {  // float boxes are rounded outwards: exact in double
  kernel::CornerBox b;
  b.valid = f.valid;
  for (int k = 0; k < 3; ++k) b.lo[k] = f.lo[k], b.hi[k] = f.hi[k];
  return b;
}

// Signs seen so far of the plane over A's boundary corners.
struct Seen {
  bool neg = false, pos = false;
  void add(Side s) {
    neg |= s == Side::Negative;
    pos |= s == Side::Positive;
  }
  [[nodiscard]] bool both() const { return neg && pos; }
};

// The block boxes of A's boundary as a binary hierarchy: level 0 the blocks (widened to double),
// each level above the unions of pairs of the one below, up to one box. A plane meets few boxes
// of each level, so deciding its side costs about the fragments near it instead of a scan of every
// block (which made extent_sides grow with the product of b's planes and A's fragments).
struct BlockHierarchy {
  std::vector<std::vector<kernel::CornerBox>> levels;
};

kernel::CornerBox unite(const kernel::CornerBox& a, const kernel::CornerBox& b) {
  kernel::CornerBox u;
  u.valid = a.valid && b.valid;
  for (int k = 0; k < 3; ++k) u.lo[k] = std::min(a.lo[k], b.lo[k]), u.hi[k] = std::max(a.hi[k], b.hi[k]);
  return u;
}

BlockHierarchy block_hierarchy(const FragmentBoxes& boxes) {
  BlockHierarchy h;
  std::vector<kernel::CornerBox> level;
  level.reserve(boxes.blocks.size());
  for (const FragmentBox& b : boxes.blocks) level.push_back(widen(b));
  h.levels.push_back(std::move(level));
  while (h.levels.back().size() > 1) {
    const std::vector<kernel::CornerBox>& below = h.levels.back();
    std::vector<kernel::CornerBox> above((below.size() + 1) / 2);
    for (std::size_t j = 0; j < above.size(); ++j)
      above[j] = 2 * j + 1 < below.size() ? unite(below[2 * j], below[2 * j + 1]) : below[2 * j];
    h.levels.push_back(std::move(above));
  }
  return h;
}

// The closed side of plane `h` that holds every corner of A's boundary (Both if none does).
// A bounded solid lies in the convex hull of its boundary's vertices, so that side holds A.
// Boxes (exact-safe, box_side) decide whole groups of fragments; the corners of fragments whose
// boxes the plane meets are decided by the exact predicates.
Side side_of_corners(const kernel::PlaneTable& planes, const std::vector<BoundaryFragment>& faces,
                     const FragmentBoxes& boxes, const BlockHierarchy& hierarchy, const kernel::Plane& h) {
  Seen seen;
  const std::size_t w = FragmentBoxes::kBlock;
  struct Item {
    std::size_t level, index;
  };
  boost::container::small_vector<Item, 64> stack;
  if (!hierarchy.levels.empty() && !hierarchy.levels.back().empty()) stack.push_back({hierarchy.levels.size() - 1, 0});
  while (!stack.empty() && !seen.both()) {
    const Item it = stack.back();
    stack.pop_back();
    const Side s = kernel::box_side(hierarchy.levels[it.level][it.index], h);
    if (s != Side::Both) {
      seen.add(s);
      continue;
    }
    if (it.level > 0) {
      const std::size_t below = hierarchy.levels[it.level - 1].size();
      if (2 * it.index + 1 < below) stack.push_back({it.level - 1, 2 * it.index + 1});
      stack.push_back({it.level - 1, 2 * it.index});
      continue;
    }
    const std::size_t j = it.index;
    for (std::size_t i = j * w; i < std::min(faces.size(), (j + 1) * w) && !seen.both(); ++i) {
      const Side t = kernel::box_side(widen(boxes.each[i]), h);
      if (t != Side::Both) {
        seen.add(t);
        continue;
      }
      const kernel::ConvexPolygon& poly = faces[i].polygon;
      const kernel::Plane& support = planes[poly.support];
      for (const kernel::Corner& c : poly.corners) {
        Sign g = kernel::filtered_orient(c.at, h);
        if (g == Sign::Zero) g = kernel::orient(support, planes[c.p], planes[c.q], c.at, h);
        seen.add(g == Sign::Negative ? Side::Negative : (g == Sign::Positive ? Side::Positive : Side::On));
        if (seen.both()) break;
      }
    }
  }
  if (seen.both()) return Side::Both;
  return seen.neg ? Side::Negative : (seen.pos ? Side::Positive : Side::Both);
}

// Corners of A's boundary near its extremes along the axes (a corner of each fragment whose box
// reaches furthest): a plane with witnesses strictly on both sides crosses A at once, without the
// scan of side_of_corners. Any boundary corners would be correct; extreme ones decide most planes.
std::vector<kernel::ApproxPoint> witnesses(const std::vector<BoundaryFragment>& faces, const FragmentBoxes& boxes) {
  std::size_t lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 1; i < boxes.each.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      if (boxes.each[i].lo[k] < boxes.each[lo[k]].lo[k]) lo[k] = i;
      if (boxes.each[i].hi[k] > boxes.each[hi[k]].hi[k]) hi[k] = i;
    }
  std::vector<kernel::ApproxPoint> w;
  for (int k = 0; k < 3; ++k)
    for (const std::size_t i : {lo[k], hi[k]}) {
      const kernel::Corner* best = nullptr;  // the fragment's corner furthest along the axis
      for (const kernel::Corner& c : faces[i].polygon.corners) {
        const double v = k == 0 ? c.at.x : (k == 1 ? c.at.y : c.at.z);
        const double b = best == nullptr ? 0 : (k == 0 ? best->at.x : (k == 1 ? best->at.y : best->at.z));
        if (best == nullptr || (i == hi[k] ? v > b : v < b)) best = &c;
      }
      if (best != nullptr && best->at.err >= 0) w.push_back(best->at);
    }
  return w;
}

// True if the witnesses show A on both sides of h (by the filter alone).
bool crosses(const std::vector<kernel::ApproxPoint>& witnesses, const kernel::Plane& h) {
  bool neg = false, pos = false;
  for (const kernel::ApproxPoint& a : witnesses) {
    const Sign g = kernel::filtered_orient(a, h);
    neg |= g == Sign::Negative;
    pos |= g == Sign::Positive;
  }
  return neg && pos;
}

}  // namespace

void complete_boxes(const std::vector<BoundaryFragment>& faces, FragmentBoxes& boxes) {
  if (boxes.each.size() != faces.size()) {
    boxes.each.clear();
    boxes.each.reserve(faces.size());
    for (const BoundaryFragment& f : faces) boxes.each.push_back(fragment_box(f.polygon));
    boxes.blocks.clear();
  }
  if (boxes.blocks.size() != FragmentBoxes::block_count(boxes.each.size())) {
    boxes.blocks.assign(FragmentBoxes::block_count(boxes.each.size()), FragmentBox{});
    for (std::size_t j = 0; j < boxes.blocks.size(); ++j) boxes.update_block(j);
  }
}

ExtentSides extent_sides(Arena& arena, TreeRef a, const std::vector<BoundaryFragment>& a_faces,
                         const FragmentBoxes& a_boxes, TreeRef b, const std::vector<BoundaryFragment>& b_faces) {
  ExtentSides sides;
  if (is_leaf(a) || is_leaf(b) || a_faces.empty() || a_boxes.each.size() != a_faces.size() ||
      a_boxes.blocks.size() != FragmentBoxes::block_count(a_faces.size()))
    return sides;
  // Bounded: every corner strictly inside the world box (a fragment on a world plane reaches
  // it), and the tree out near the world box (the region outside a closed boundary).
  const auto world = float(kernel::PlaneTable::kWorld);  // a power of two: exact
  for (const FragmentBox& x : a_boxes.blocks) {
    if (!x.valid) return sides;
    for (int k = 0; k < 3; ++k)
      if (!(x.lo[k] > -world && x.hi[k] < world)) return sides;
  }
  Clipper clip(arena);
  if (clip.far_status(a)) return sides;

  // b's planes: those of its nodes and its fragments' supports, each once.
  std::vector<std::int32_t>& planes = sides.planes_;
  std::vector<TreeRef> stack{b};
  while (!stack.empty()) {
    const TreeRef t = stack.back();
    stack.pop_back();
    const BspNode& n = arena.nodes[std::size_t(t)];
    planes.push_back(n.plane);
    if (!is_leaf(n.negative)) stack.push_back(n.negative);
    if (!is_leaf(n.positive)) stack.push_back(n.positive);
  }
  for (const BoundaryFragment& f : b_faces) planes.push_back(f.polygon.support);
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  sides.side_.reserve(planes.size());
  const std::vector<kernel::ApproxPoint> extreme = witnesses(a_faces, a_boxes);
  const BlockHierarchy hierarchy = block_hierarchy(a_boxes);
  for (const std::int32_t p : planes) {
    const kernel::Plane& h = arena.planes[p];
    sides.side_.push_back(crosses(extreme, h) ? Side::Both : side_of_corners(arena.planes, a_faces, a_boxes, hierarchy, h));
    if (sides.side_.back() != Side::Both) ++sides.one_sided_;
  }
  return sides;
}

TreeRef prune_to_extent(Arena& arena, TreeRef b, const ExtentSides& sides) {
  if (sides.none()) return b;
  struct Frame {
    TreeRef t;
    std::int32_t parent;  // -1: the root
    bool positive;        // which child of parent
    bool grown;           // an ancestor was replaced: the cell is larger than before
  };
  TreeRef root = b;
  std::vector<Frame> stack{{b, -1, false, false}};
  while (!stack.empty()) {
    Frame f = stack.back();
    stack.pop_back();
    while (!is_leaf(f.t)) {
      const BspNode& n = arena.nodes[std::size_t(f.t)];
      const Side s = sides.of(n.plane);
      if (s == Side::Both) break;
      f.t = s == Side::Negative ? n.negative : n.positive;  // A's side
      f.grown = true;
    }
    if (f.parent < 0)
      root = f.t;
    else if (f.positive)
      arena.nodes[std::size_t(f.parent)].positive = f.t;
    else
      arena.nodes[std::size_t(f.parent)].negative = f.t;
    if (is_leaf(f.t)) continue;
    if (f.grown) arena.polygons[std::size_t(f.t)].corners.clear();  // pending: recomputed on demand
    const BspNode& n = arena.nodes[std::size_t(f.t)];
    stack.push_back({n.negative, f.t, false, f.grown});
    stack.push_back({n.positive, f.t, true, f.grown});
  }
  return root;
}

}  // namespace sculpt::bsp::detail
