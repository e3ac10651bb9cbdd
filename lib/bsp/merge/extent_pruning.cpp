#include "bsp/merge/extent_pruning.hpp"
#include "base/cancel.hpp"

#include <boost/container/small_vector.hpp>
#include <optional>

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

kernel::CornerBox unite(const kernel::CornerBox& a, const kernel::CornerBox& b) {
  kernel::CornerBox u;
  u.valid = a.valid && b.valid;
  for (int k = 0; k < 3; ++k) u.lo[k] = std::min(a.lo[k], b.lo[k]), u.hi[k] = std::max(a.hi[k], b.hi[k]);
  return u;
}

// A bounding-volume hierarchy over the boxes of A's boundary fragments: split at the median of
// the box centres along the longest axis down to a few fragments per leaf. Deciding a plane's side
// visits the boxes the plane meets, about the fragments near it. (The blocks of FragmentBoxes are
// runs of consecutive fragments, often long thin bands across the solid that most planes near A
// meet: scanning them made extent_sides grow with the product of b's planes and A's fragments.)
struct FragmentHierarchy {
  struct Node {
    kernel::CornerBox box;
    std::uint32_t begin, end;  // range of `order`
    std::int32_t first_child;  // children first_child and first_child + 1, or -1 for a leaf
  };
  std::vector<Node> nodes;  // nodes[0] is the root (if any)
  std::vector<std::uint32_t> order;
};

constexpr std::uint32_t kLeafFragments = 4;

FragmentHierarchy fragment_hierarchy(const FragmentBoxes& boxes) {
  FragmentHierarchy h;
  const auto count = std::uint32_t(boxes.each.size());
  if (count == 0) return h;
  h.order.resize(count);
  std::vector<float> centre(3 * std::size_t(count));
  for (std::uint32_t i = 0; i < count; ++i) {
    h.order[i] = i;
    for (int k = 0; k < 3; ++k) centre[3 * std::size_t(i) + std::size_t(k)] = 0.5f * boxes.each[i].lo[k] + 0.5f * boxes.each[i].hi[k];
  }
  h.nodes.reserve(2 * std::size_t(count / kLeafFragments + 1));
  h.nodes.push_back({{}, 0, count, -1});
  std::vector<std::size_t> stack{0};
  while (!stack.empty()) {
    const std::size_t id = stack.back();
    stack.pop_back();
    const std::uint32_t begin = h.nodes[id].begin, end = h.nodes[id].end;
    kernel::CornerBox box = widen(boxes.each[h.order[begin]]);
    float clo[3], chi[3];
    for (int k = 0; k < 3; ++k) clo[k] = chi[k] = centre[3 * std::size_t(h.order[begin]) + std::size_t(k)];
    for (std::uint32_t i = begin + 1; i < end; ++i) {
      const std::uint32_t f = h.order[i];
      box = unite(box, widen(boxes.each[f]));
      for (int k = 0; k < 3; ++k) {
        clo[k] = std::min(clo[k], centre[3 * std::size_t(f) + std::size_t(k)]);
        chi[k] = std::max(chi[k], centre[3 * std::size_t(f) + std::size_t(k)]);
      }
    }
    h.nodes[id].box = box;
    if (end - begin <= kLeafFragments) continue;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(h.order.begin() + begin, h.order.begin() + mid, h.order.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y) {
                       return centre[3 * std::size_t(x) + std::size_t(axis)] < centre[3 * std::size_t(y) + std::size_t(axis)];
                     });
    const auto first = std::int32_t(h.nodes.size());
    h.nodes[id].first_child = first;
    h.nodes.push_back({{}, begin, mid, -1});
    h.nodes.push_back({{}, mid, end, -1});
    stack.push_back(std::size_t(first));
    stack.push_back(std::size_t(first) + 1);
  }
  return h;
}

// The signs of the corners of a fragment, added to `seen` (exact; stops once both are seen).
void add_corner_signs(const kernel::PlaneTable& planes, const FragmentRef& fragment, const kernel::Plane& h,
                      Seen& seen) {
  const kernel::PolygonView poly = fragment.polygon;
  const kernel::Plane& support = planes[poly.support];
  for (const kernel::Corner& c : poly.corners) {
    Sign g = kernel::filtered_orient(c.at(), h);
    if (g == Sign::Zero) g = kernel::orient(support, planes[c.p], planes[c.q], c.at(), h);
    seen.add(g == Sign::Negative ? Side::Negative : (g == Sign::Positive ? Side::Positive : Side::On));
    if (seen.both()) return;
  }
}

// side_of_corners through the block boxes alone (no hierarchy to build: for few planes).
Side side_by_blocks(const kernel::PlaneTable& planes, const FragmentList& faces, const FragmentBoxes& boxes,
                    const kernel::Plane& h, Seen seen) {
  const std::size_t w = FragmentBoxes::kBlock;
  for (std::size_t j = 0; j < boxes.blocks.size() && !seen.both(); ++j) {
    const Side s = kernel::box_side(widen(boxes.blocks[j]), h);
    if (s != Side::Both) {
      seen.add(s);
      continue;
    }
    for (std::size_t i = j * w; i < std::min(faces.size(), (j + 1) * w) && !seen.both(); ++i) {
      const Side t = kernel::box_side(widen(boxes.each[i]), h);
      if (t != Side::Both)
        seen.add(t);
      else
        add_corner_signs(planes, faces[i], h, seen);
    }
  }
  if (seen.both()) return Side::Both;
  return seen.neg ? Side::Negative : (seen.pos ? Side::Positive : Side::Both);
}

// The closed side of plane `h` that holds every corner of A's boundary (Both if none does).
// A bounded solid lies in the convex hull of its boundary's vertices, so that side holds A.
// Boxes (exact-safe, box_side) decide whole groups of fragments; the corners of fragments whose
// boxes the plane meets are decided by the exact predicates.
// Through `hierarchy_or_null` if given, else through the block boxes.
Side side_of_corners(const kernel::PlaneTable& planes, const FragmentList& faces,
                     const FragmentBoxes& boxes, const FragmentHierarchy* hierarchy_or_null, const kernel::Plane& h) {
  Seen seen;
  if (hierarchy_or_null == nullptr) return side_by_blocks(planes, faces, boxes, h, seen);
  const FragmentHierarchy& hierarchy = *hierarchy_or_null;
  boost::container::small_vector<std::int32_t, 64> stack;
  if (!hierarchy.nodes.empty()) stack.push_back(0);
  while (!stack.empty() && !seen.both()) {
    const FragmentHierarchy::Node& node = hierarchy.nodes[std::size_t(stack.back())];
    stack.pop_back();
    const Side s = kernel::box_side(node.box, h);
    if (s != Side::Both) {
      seen.add(s);
      continue;
    }
    if (node.first_child >= 0) {
      stack.push_back(node.first_child + 1);
      stack.push_back(node.first_child);
      continue;
    }
    for (std::uint32_t k = node.begin; k < node.end && !seen.both(); ++k) {
      const std::size_t i = hierarchy.order[k];
      const Side t = node.end - node.begin > 1 ? kernel::box_side(widen(boxes.each[i]), h) : Side::Both;
      if (t != Side::Both) {
        seen.add(t);
        continue;
      }
      add_corner_signs(planes, faces[i], h, seen);
    }
  }
  if (seen.both()) return Side::Both;
  return seen.neg ? Side::Negative : (seen.pos ? Side::Positive : Side::Both);
}

// Corners of A's boundary near its extremes along the axes (a corner of each fragment whose box
// reaches furthest): a plane with witnesses strictly on both sides crosses A at once, without the
// scan of side_of_corners. Any boundary corners would be correct; extreme ones decide most planes.
std::vector<kernel::ApproxPoint> witnesses(const FragmentList& faces, const FragmentBoxes& boxes) {
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
        const double v = k == 0 ? c.at().x : (k == 1 ? c.at().y : c.at().z);
        const double b = best == nullptr ? 0 : (k == 0 ? best->at().x : (k == 1 ? best->at().y : best->at().z));
        if (best == nullptr || (i == hi[k] ? v > b : v < b)) best = &c;
      }
      if (best != nullptr && best->at().err >= 0) w.push_back(best->at());
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

void complete_boxes(const FragmentList& faces, FragmentBoxes& boxes) {
  if (boxes.each.size() != faces.size()) {
    boxes.each.clear();
    boxes.each.reserve(faces.size());
    for (const FragmentRef f : faces) boxes.each.push_back(fragment_box(f.polygon));
    boxes.blocks.clear();
  }
  if (boxes.blocks.size() != FragmentBoxes::block_count(boxes.each.size())) {
    boxes.blocks.assign(FragmentBoxes::block_count(boxes.each.size()), FragmentBox{});
    for (std::size_t j = 0; j < boxes.blocks.size(); ++j) boxes.update_block(j);
  }
}

ExtentSides extent_sides(Arena& arena, TreeRef a, const FragmentList& a_faces,
                         const FragmentBoxes& a_boxes, TreeRef b, const FragmentList& b_faces) {
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
  for (const FragmentRef f : b_faces) planes.push_back(f.polygon.support);
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  const std::vector<kernel::ApproxPoint> extreme = witnesses(a_faces, a_boxes);
  // Planes the witnesses leave open are decided through the boxes. The hierarchy costs about a
  // sort of A's fragments, so it is built only when scanning every block for each such plane
  // would cost more (many planes: a curved B; an in-place sequence of small operands, like the
  // bars of a Menger sponge, keeps the blocks, which it updates instead of rebuilding).
  sides.side_.assign(planes.size(), Side::Both);
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < planes.size(); ++i)
    if (!crosses(extreme, arena.planes[planes[i]])) open.push_back(i);
  std::optional<FragmentHierarchy> hierarchy;
  if (open.size() * a_boxes.blocks.size() > 8 * a_faces.size()) hierarchy = fragment_hierarchy(a_boxes);
  for (const std::size_t i : open) {
    check_cancel();  // Ctrl-C (base/cancel.hpp): a plane's scan can visit many fragments
    sides.side_[i] = side_of_corners(arena.planes, a_faces, a_boxes, hierarchy ? &*hierarchy : nullptr, arena.planes[planes[i]]);
    if (sides.side_[i] != Side::Both) ++sides.one_sided_;
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
