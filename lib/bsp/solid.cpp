#include "bsp/solid.hpp"

#include <cmath>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

namespace sculpt {

Solid::Solid(kernel::PlaneTable planes, std::vector<BspNode> nodes,
             std::vector<kernel::ConvexPolygon> polygons, TreeRef root, std::size_t compacted_size,
             std::optional<std::vector<BoundaryFragment>> boundary, FragmentBoxes boundary_boxes)
    : planes_(std::move(planes)), nodes_(std::move(nodes)), polygons_(std::move(polygons)), root_(root),
      compacted_size_(compacted_size ? compacted_size : nodes_.size()), boundary_(std::move(boundary)),
      boundary_boxes_(std::move(boundary_boxes)) {
  if (!boundary_ || boundary_boxes_.each.size() != boundary_->size()) boundary_boxes_.each.clear();
  if (boundary_boxes_.blocks.size() != FragmentBoxes::block_count(boundary_boxes_.each.size()))
    boundary_boxes_.blocks.clear();
  if (nodes_.size() != polygons_.size() || (!is_leaf(root_) && std::size_t(root_) >= nodes_.size()))
    throw std::logic_error("Solid: inconsistent tree storage");
}

Solid::Storage Solid::release() && {
  Storage s{std::move(planes_), std::move(nodes_), std::move(polygons_), root_, compacted_size_, std::move(boundary_),
            std::move(boundary_boxes_)};
  planes_ = kernel::PlaneTable();
  nodes_.clear();
  polygons_.clear();
  root_ = kOut;
  compacted_size_ = 0;
  boundary_ = std::vector<BoundaryFragment>{};
  boundary_boxes_ = {};
  return s;
}

FragmentBox fragment_box(const kernel::ConvexPolygon& polygon) {
  const kernel::CornerBox b = kernel::corner_box(polygon);
  FragmentBox f{};
  f.valid = b.valid;
  if (!b.valid) return f;
  // nextafter(v, -inf) and nextafter(v, +inf) on the bit pattern (libm's nextafterf is a call):
  // away from zero is one unit more in the magnitude bits, towards zero one less, and from a zero
  // of either sign the step goes to the smallest subnormal (inf - 1 is the largest float).
  auto step = [](float v, bool up) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    if ((bits & 0x7fffffffu) == 0) return std::bit_cast<float>(up ? 0x00000001u : 0x80000001u);
    const bool away = (bits >> 31 == 0) == up;  // positive and up, or negative and down
    return std::bit_cast<float>(away ? bits + 1 : bits - 1);
  };
  for (int k = 0; k < 3; ++k) {  // outwards: float(x) may round either way
    f.lo[k] = float(b.lo[k]);
    if (double(f.lo[k]) > b.lo[k]) f.lo[k] = step(f.lo[k], false);
    f.hi[k] = float(b.hi[k]);
    if (double(f.hi[k]) < b.hi[k]) f.hi[k] = step(f.hi[k], true);
  }
  return f;
}

void FragmentBoxes::update_block(std::size_t j) {
  FragmentBox b{};
  b.valid = true;
  for (int k = 0; k < 3; ++k) b.lo[k] = HUGE_VALF, b.hi[k] = -HUGE_VALF;
  const std::size_t end = std::min(each.size(), (j + 1) * kBlock);
  for (std::size_t i = j * kBlock; i < end; ++i) {
    const FragmentBox& x = each[i];
    b.valid &= x.valid;
    for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], x.lo[k]), b.hi[k] = std::max(b.hi[k], x.hi[k]);
  }
  blocks[j] = b;
}

const std::vector<BoundaryFragment>& Solid::boundary() const {
  static const std::vector<BoundaryFragment> none;
  return boundary_ ? *boundary_ : none;
}

Solid Solid::leaf(bool inside) {
  Solid s;
  s.root_ = inside ? kIn : kOut;
  return s;
}

TreeStats tree_stats(const Solid& solid) {
  TreeStats st;
  std::vector<std::pair<TreeRef, int>> stack{{solid.root(), 0}};
  double depth_sum = 0;
  while (!stack.empty()) {
    auto [r, depth] = stack.back();
    stack.pop_back();
    if (is_leaf(r)) {
      (r == kIn ? st.in_leaves : st.out_leaves)++;
      st.height = std::max(st.height, depth);
      depth_sum += depth;
      continue;
    }
    ++st.nodes;
    const BspNode& n = solid.nodes()[std::size_t(r)];
    stack.push_back({n.negative, depth + 1});
    stack.push_back({n.positive, depth + 1});
  }
  st.mean_leaf_depth = depth_sum / double(st.in_leaves + st.out_leaves);
  return st;
}

}  // namespace sculpt
