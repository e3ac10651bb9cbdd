#include "bsp/extent_pruning.hpp"

#include "bsp/boundary_clipper.hpp"
#include "bsp/node_polygons.hpp"

namespace sculpt::detail {

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

// The closed side of plane `h` that holds every corner of A's boundary (Both if none does).
// A bounded solid lies in the convex hull of its boundary's vertices, so that side holds A.
Side side_of_corners(const kernel::PlaneTable& planes, const std::vector<BoundaryFragment>& faces,
                     const FragmentBoxes& boxes, const kernel::Plane& h) {
  Seen seen;
  const std::size_t w = FragmentBoxes::kBlock;
  for (std::size_t j = 0; j < boxes.blocks.size() && !seen.both(); ++j) {
    const Side s = kernel::box_side(widen(boxes.blocks[j]), h);
    if (s != Side::Both) {
      seen.add(s);
      continue;
    }
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
  for (const std::int32_t p : planes) {
    sides.side_.push_back(side_of_corners(arena.planes, a_faces, a_boxes, arena.planes[p]));
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

}  // namespace sculpt::detail
