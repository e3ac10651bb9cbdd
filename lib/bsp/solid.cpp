#include "bsp/solid.hpp"

#include "base/assert.hpp"
#include "bsp/tree/deferred_tree.hpp"
#include "bsp/tree/tree_checks.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace sculpt {

Solid::Solid(kernel::PlaneTable planes, std::vector<BspNode> nodes,
             PolygonStore polygons, TreeRef root, FreeSlots free,
             std::optional<FragmentList> boundary, FragmentBoxes boundary_boxes)
    : planes_(std::move(planes)), nodes_(std::move(nodes)), polygons_(std::move(polygons)), root_(root),
      free_(std::move(free)),
      boundary_(std::move(boundary)),
      boundary_boxes_(std::move(boundary_boxes)) {
  if (!boundary_ || boundary_boxes_.each.size() != boundary_->size()) boundary_boxes_.each.clear();
  if (boundary_boxes_.blocks.size() != FragmentBoxes::block_count(boundary_boxes_.each.size()))
    boundary_boxes_.blocks.clear();
  if (nodes_.size() != polygons_.size() || (!is_leaf(root_) && std::size_t(root_) >= nodes_.size()))
    throw std::logic_error("Solid: inconsistent tree storage");
#ifndef NDEBUG
  const char* problem =
      bsp::detail::tree_storage_problem(planes_, nodes_, polygons_, root_, boundary_ ? &*boundary_ : nullptr);
  SCULPT_ASSERT(problem == nullptr, problem);
#endif
}

Solid::Solid() = default;
Solid::~Solid() = default;
// A moved-from solid is the empty solid (its root an out leaf over its emptied storage).
Solid::Solid(Solid&& other) noexcept
    : planes_(std::move(other.planes_)),
      nodes_(std::move(other.nodes_)),
      polygons_(std::move(other.polygons_)),
      root_(std::exchange(other.root_, kOut)),
      free_(std::move(other.free_)),
      boundary_(std::move(other.boundary_)),
      boundary_boxes_(std::move(other.boundary_boxes_)),
      grid_(other.grid_),
      deferred_(std::move(other.deferred_)) {
  other.boundary_ = FragmentList{};
}

Solid& Solid::operator=(Solid&& other) noexcept {
  if (this != &other) {
    planes_ = std::move(other.planes_);
    nodes_ = std::move(other.nodes_);
    polygons_ = std::move(other.polygons_);
    root_ = std::exchange(other.root_, kOut);
    free_ = std::move(other.free_);
    boundary_ = std::move(other.boundary_);
    boundary_boxes_ = std::move(other.boundary_boxes_);
    grid_ = other.grid_;
    deferred_ = std::move(other.deferred_);
    other.boundary_ = FragmentList{};
  }
  return *this;
}

void Solid::copy_from(const Solid& other) {
  other.settled();
  planes_ = other.planes_;
  nodes_ = other.nodes_;
  polygons_ = other.polygons_;
  root_ = other.root_;
  free_ = other.free_;
  boundary_ = other.boundary_;
  boundary_boxes_ = other.boundary_boxes_;
  grid_ = other.grid_;
  deferred_.reset();
}

Solid::Solid(const Solid& other) { copy_from(other); }

Solid& Solid::operator=(const Solid& other) {
  if (this != &other) copy_from(other);
  return *this;
}

Solid::Solid(std::unique_ptr<bsp::detail::DeferredTree> deferred) : deferred_(std::move(deferred)) {}

void Solid::build_deferred() const {
  // The built result replaces the (empty) storage; the grid stays (the operation labelled this
  // solid, the merge works at the default grid). deferred_ is released last: if build() throws
  // (Ctrl-C, out of memory), the solid stays deferred and whole, and a later use builds again.
  Solid built = deferred_->build();
  planes_ = std::move(built.planes_);
  nodes_ = std::move(built.nodes_);
  polygons_ = std::move(built.polygons_);
  root_ = built.root_;
  free_ = std::move(built.free_);
  boundary_ = std::move(built.boundary_);
  boundary_boxes_ = std::move(built.boundary_boxes_);
  deferred_.reset();
}

Solid::BoundaryView Solid::boundary_view() const {
  if (deferred_) return {&deferred_->planes(), &deferred_->boundary()};
  if (!boundary_) return {};
  return {&planes_, &*boundary_};
}

Solid::Storage Solid::release() && {
  settled();
  Storage s{std::move(planes_), std::move(nodes_), std::move(polygons_), root_, std::move(free_), std::move(boundary_),
            std::move(boundary_boxes_)};
  planes_ = kernel::PlaneTable();
  nodes_.clear();
  polygons_.clear();
  root_ = kOut;
  free_ = {};
  boundary_ = FragmentList{};
  boundary_boxes_ = {};
  return s;
}

const FragmentList& Solid::boundary() const {
  static const FragmentList none;
  settled();
  return boundary_ ? *boundary_ : none;
}

Solid Solid::leaf(bool inside, const kernel::Grid& grid) {
  Solid s;
  s.root_ = inside ? kIn : kOut;
  s.grid_ = grid;
  return s;
}

GridMismatch::GridMismatch(const kernel::Grid& a, const kernel::Grid& b)
    : InvalidInput("solids made at different grids (step " + a.name() + " and step " + b.name() +
                   ") cannot be combined: make every solid of a model at one grid") {}

kernel::Grid common_grid(const Solid& a, const Solid& b) {
  if (a.grid() == b.grid() || is_leaf(b.root())) return a.grid();
  if (is_leaf(a.root())) return b.grid();
  throw GridMismatch(a.grid(), b.grid());
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
