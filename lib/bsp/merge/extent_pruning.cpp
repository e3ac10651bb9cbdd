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

// A bounding-volume hierarchy over boxes of A's fragments: of each fragment, or of each block of
// FragmentBoxes (a run of kBlock consecutive fragments), whichever costs less for the operation
// (extent_sides). The elements are put in Morton order of their centres, kLeafElements to a
// leaf, and each level above holds the boxes of pairs of the level below. Deciding a plane's side
// visits the elements whose boxes the plane meets, about the fragments near it. One sort and no
// median splits: over the 15,000 blocks of a stroke's workpiece (5 * 10^5 fragments) it takes
// about a millisecond (docs/benchmarks.md, "Session 44"). Runs of fragments are compact on the
// solids met so far (a ring primitive's bands, a merge's cells, a mesh's file order).
struct BoxHierarchy {
  std::size_t unit = 1;                                // fragments per element: 1 or kBlock
  std::vector<std::uint32_t> order;                    // element indices, in Morton order
  std::vector<std::vector<kernel::CornerBox>> levels;  // levels[0]: leaves; levels.back(): the root
};

constexpr std::size_t kLeafElements = 2;
constexpr std::size_t kOpenPlanesForBlockHierarchy = 16;  // about the cost of its sort in block scans

// Bits 3k + axis of the result are bit k of the three coordinates (each < 2^21).
std::uint64_t morton(const std::uint32_t c[3]) {
  std::uint64_t m = 0;
  for (int k = 0; k < 21; ++k)
    for (int axis = 0; axis < 3; ++axis) m |= std::uint64_t((c[axis] >> k) & 1u) << (3 * k + axis);
  return m;
}

BoxHierarchy box_hierarchy(const std::vector<FragmentBox>& elements, std::size_t unit) {
  BoxHierarchy h;
  h.unit = unit;
  const std::size_t count = elements.size();
  if (count == 0) return h;
  float lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = elements[0].lo[k], hi[k] = elements[0].hi[k];
  for (const FragmentBox& b : elements)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(count);
  for (std::size_t j = 0; j < count; ++j) {
    std::uint32_t c[3];
    for (int k = 0; k < 3; ++k) {
      const double centre = 0.5 * double(elements[j].lo[k]) + 0.5 * double(elements[j].hi[k]);
      const double t = hi[k] > lo[k] ? (centre - lo[k]) / (double(hi[k]) - lo[k]) : 0;
      c[k] = std::uint32_t(std::clamp(t, 0.0, 1.0) * double((1u << 21) - 1));
    }
    keyed[j] = {morton(c), std::uint32_t(j)};
  }
  std::sort(keyed.begin(), keyed.end());
  h.order.resize(count);
  for (std::size_t j = 0; j < count; ++j) h.order[j] = keyed[j].second;
  std::vector<kernel::CornerBox> level((count + kLeafElements - 1) / kLeafElements);
  for (std::size_t i = 0; i < level.size(); ++i) {
    level[i] = widen(elements[h.order[i * kLeafElements]]);
    for (std::size_t j = i * kLeafElements + 1; j < std::min(count, (i + 1) * kLeafElements); ++j)
      level[i] = unite(level[i], widen(elements[h.order[j]]));
  }
  h.levels.push_back(std::move(level));
  while (h.levels.back().size() > 1) {
    const std::vector<kernel::CornerBox>& below = h.levels.back();
    std::vector<kernel::CornerBox> above((below.size() + 1) / 2);
    for (std::size_t i = 0; i < above.size(); ++i)
      above[i] = 2 * i + 1 < below.size() ? unite(below[2 * i], below[2 * i + 1]) : below[2 * i];
    h.levels.push_back(std::move(above));
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

// The signs of the corners of fragments [first, last), added to `seen`: a fragment whose box lies
// on one side of h counts as that side, the others by their corners (exact).
void add_range_signs(const kernel::PlaneTable& planes, const FragmentList& faces, const FragmentBoxes& boxes,
                     std::size_t first, std::size_t last, const kernel::Plane& h, Seen& seen) {
  const std::size_t end = std::min(faces.size(), last);
  for (std::size_t i = first; i < end && !seen.both(); ++i) {
    const Side t = kernel::box_side(widen(boxes.each[i]), h);
    if (t != Side::Both)
      seen.add(t);
    else
      add_corner_signs(planes, faces[i], h, seen);
  }
}

Side side_seen(const Seen& seen) {
  if (seen.both()) return Side::Both;
  return seen.neg ? Side::Negative : (seen.pos ? Side::Positive : Side::Both);
}

// The closed side of plane `h` that holds every corner of A's boundary (Both if none does).
// A bounded solid lies in the convex hull of its boundary's vertices, so that side holds A.
// Boxes (exact-safe, box_side) decide whole groups of fragments; the corners of fragments whose
// boxes the plane meets are decided by the exact predicates.
// Through `hierarchy_or_null` if given, else through every block box in turn.
Side side_of_corners(const kernel::PlaneTable& planes, const FragmentList& faces, const FragmentBoxes& boxes,
                     const BoxHierarchy* hierarchy_or_null, const kernel::Plane& h) {
  Seen seen;
  if (hierarchy_or_null == nullptr) {
    for (std::size_t j = 0; j < boxes.blocks.size() && !seen.both(); ++j) {
      const Side s = kernel::box_side(widen(boxes.blocks[j]), h);
      if (s != Side::Both)
        seen.add(s);
      else
        add_range_signs(planes, faces, boxes, j * FragmentBoxes::kBlock, (j + 1) * FragmentBoxes::kBlock, h, seen);
    }
    return side_seen(seen);
  }
  const BoxHierarchy& hierarchy = *hierarchy_or_null;
  const std::vector<FragmentBox>& elements = hierarchy.unit == 1 ? boxes.each : boxes.blocks;
  const std::size_t count = hierarchy.order.size();
  boost::container::small_vector<std::pair<std::size_t, std::size_t>, 64> stack;  // (level, index)
  if (count > 0) stack.push_back({hierarchy.levels.size() - 1, 0});
  while (!stack.empty() && !seen.both()) {
    const auto [level, index] = stack.back();
    stack.pop_back();
    const Side s = kernel::box_side(hierarchy.levels[level][index], h);
    if (s != Side::Both) {
      seen.add(s);
      continue;
    }
    if (level > 0) {
      if (2 * index + 1 < hierarchy.levels[level - 1].size()) stack.push_back({level - 1, 2 * index + 1});
      stack.push_back({level - 1, 2 * index});
      continue;
    }
    const std::size_t first = index * kLeafElements, last = std::min(count, first + kLeafElements);
    for (std::size_t k = first; k < last && !seen.both(); ++k) {
      const std::size_t j = hierarchy.order[k];
      const Side t = last - first > 1 ? kernel::box_side(widen(elements[j]), h) : Side::Both;
      if (t != Side::Both)
        seen.add(t);
      else if (hierarchy.unit == 1)
        add_corner_signs(planes, faces[j], h, seen);
      else
        add_range_signs(planes, faces, boxes, j * hierarchy.unit, (j + 1) * hierarchy.unit, h, seen);
    }
  }
  return side_seen(seen);
}

// A corner of fragment i with a usable approximation, if any: the one furthest along `axis` in
// direction `sign` (axis < 0: the first).
std::optional<kernel::ApproxPoint> corner_of(const FragmentList& faces, std::size_t i, int axis, int sign) {
  std::optional<kernel::ApproxPoint> best;
  auto along = [axis](const kernel::ApproxPoint& p) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); };
  for (const kernel::Corner& c : faces[i].polygon.corners) {
    if (!(c.at().err >= 0)) continue;
    if (axis < 0) return c.at();
    if (!best || sign * along(c.at()) > sign * along(*best)) best = c.at();
  }
  return best;
}

// Corners of A's boundary that a plane crossing A likely has on both sides; a plane with
// witnesses strictly on both sides crosses A at once, without the scan of side_of_corners. Any
// boundary corners would be correct. Two kinds:
// - near A's extremes along the axes (a corner of the fragment whose box reaches furthest:
//   found in the block whose box does), which decide planes crossing A far and wide;
// - spread over the fragments whose boxes meet `near` (B's box), which decide the planes of B
//   that cut into A there (a stroke's tool: 74-120 of its 870 planes crossed the workpiece and
//   the extremes missed them). Every plane left open tests them all, so there are few when A
//   has few blocks (a plane's scan is short then): one per 32 blocks, at most kNearWitnesses.
constexpr std::size_t kNearWitnesses = 64;
std::vector<kernel::ApproxPoint> witnesses(const FragmentList& faces, const FragmentBoxes& boxes,
                                           const kernel::CornerBox& near) {
  std::vector<kernel::ApproxPoint> w;
  const std::size_t kBlock = FragmentBoxes::kBlock;
  for (int k = 0; k < 3; ++k)
    for (const int sign : {-1, 1}) {
      auto reach = [&](const FragmentBox& b) { return sign < 0 ? -b.lo[k] : b.hi[k]; };
      std::size_t block = 0;
      for (std::size_t j = 1; j < boxes.blocks.size(); ++j)
        if (reach(boxes.blocks[j]) > reach(boxes.blocks[block])) block = j;
      std::size_t best = block * kBlock;
      for (std::size_t i = best + 1; i < std::min(faces.size(), (block + 1) * kBlock); ++i)
        if (reach(boxes.each[i]) > reach(boxes.each[best])) best = i;
      if (const auto c = corner_of(faces, best, k, sign)) w.push_back(*c);
    }
  if (!near.valid) return w;
  auto meets = [&](const FragmentBox& b) {
    for (int k = 0; k < 3; ++k)
      if (double(b.hi[k]) < near.lo[k] || double(b.lo[k]) > near.hi[k]) return false;
    return true;
  };
  std::vector<std::size_t> close;
  for (std::size_t j = 0; j < boxes.blocks.size(); ++j) {
    if (!meets(boxes.blocks[j])) continue;
    for (std::size_t i = j * kBlock; i < std::min(faces.size(), (j + 1) * kBlock); ++i)
      if (meets(boxes.each[i])) close.push_back(i);
  }
  const std::size_t take = std::min({close.size(), kNearWitnesses, boxes.blocks.size() / 32});
  for (std::size_t t = 0; t < take; ++t)
    if (const auto c = corner_of(faces, close[t * close.size() / take], -1, 0)) w.push_back(*c);
  return w;
}

// True if the witnesses show A on both sides of h (by the filter alone).
bool crosses(const std::vector<kernel::ApproxPoint>& witnesses, const kernel::Plane& h) {
  bool neg = false, pos = false;
  for (const kernel::ApproxPoint& a : witnesses) {
    const Sign g = kernel::filtered_orient(a, h);
    neg |= g == Sign::Negative;
    pos |= g == Sign::Positive;
    if (neg && pos) return true;
  }
  return false;
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
  const std::vector<kernel::ApproxPoint> extreme =
      witnesses(a_faces, a_boxes, a_boxes.blocks.size() >= 32 ? bounds(b_faces) : kernel::CornerBox{});
  // Planes the witnesses leave open are decided through the boxes: for a few, by scanning every
  // block (an in-place sequence of small operands, like the bars of a Menger sponge, keeps the
  // blocks up to date); for more, through a hierarchy, which costs about a sort of its elements:
  // over fragments when scanning every block for each open plane would cost more than sorting
  // the fragments (a curved B against a small A), else over blocks (a stroke's tool against a
  // large workpiece).
  sides.side_.assign(planes.size(), Side::Both);
  std::vector<std::size_t> open;
  for (std::size_t i = 0; i < planes.size(); ++i)
    if (!crosses(extreme, arena.planes[planes[i]])) open.push_back(i);
  std::optional<BoxHierarchy> hierarchy;
  if (open.size() * a_boxes.blocks.size() > 8 * a_faces.size())
    hierarchy = box_hierarchy(a_boxes.each, 1);
  else if (open.size() > kOpenPlanesForBlockHierarchy)
    hierarchy = box_hierarchy(a_boxes.blocks, FragmentBoxes::kBlock);
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
