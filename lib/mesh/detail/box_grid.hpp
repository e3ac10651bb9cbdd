#pragma once
/// \file box_grid.hpp
/// The broad phase of the self-intersection searches (search_self_intersections and the output
/// rounding's crossing search): a uniform grid of cubic cells over a set of boxes, each box listed
/// in every cell it overlaps. A pair of overlapping boxes is to be examined in one cell only, the
/// one holding the minimum corner of the boxes' intersection (owns()), so each pair once.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

namespace sculpt::mesh::detail {

class BoxGrid {
 public:
  /// Cells of twice the median box extent (at least 2^-20 of the boxes' whole extent), coarsened
  /// until the boxes' cell entries stay within 8 per box (plus 1024). Boxes must be finite.
  explicit BoxGrid(std::span<const Eigen::AlignedBox3d> boxes);

  /// The non-empty cells, in order.
  [[nodiscard]] size_t cells() const { return starts_.empty() ? 0 : starts_.size() - 1; }
  /// The boxes listed in cell k (indices into the boxes given, ascending).
  [[nodiscard]] std::span<const int> cell(size_t k) const {
    return {members_.data() + starts_[k], members_.data() + starts_[k + 1]};
  }
  /// Whether the pair (a, b) of overlapping boxes is examined in cell k (the cell of the minimum
  /// corner of their intersection; cell indices are monotone, so that is the larger first cell of
  /// the two along each axis).
  [[nodiscard]] bool owns(size_t k, int a, int b) const {
    const auto &x = range_[size_t(a)], &y = range_[size_t(b)];
    return key(std::max(x[0], y[0]), std::max(x[1], y[1]), std::max(x[2], y[2])) == keys_[k];
  }
  /// For each box listed in cell k (in cell(k)'s order): bit i set when the box's first cell along
  /// axis i is this one. Two boxes listed in one cell both reach it, so their intersection's
  /// minimum corner is in that cell (owns) exactly when their two masks together have all three
  /// bits.
  [[nodiscard]] std::span<const unsigned char> first_cell_masks(size_t k) const {
    return {masks_.data() + starts_[k], masks_.data() + starts_[k + 1]};
  }

 private:
  [[nodiscard]] std::int64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return dense_ ? (x * dims_[1] + y) * dims_[2] + z : (x << 42) | (y << 21) | z;
  }

  /// Per box: first cells (x, y, z), last cells (below 2^20 + 1 along every axis: 32 bits, half
  /// the memory of 64, which matters on millions of boxes).
  std::vector<std::array<std::int32_t, 6>> range_;
  std::array<std::int64_t, 3> dims_{};
  bool dense_ = false;  ///< keys number the cells densely (counting sort), else 21 bits per axis
  std::vector<std::int64_t> keys_;  ///< per non-empty cell
  std::vector<size_t> starts_;      ///< per non-empty cell, where its members begin (one more at the end)
  std::vector<int> members_;
  std::vector<unsigned char> masks_;  ///< per member: first_cell_masks
};

}  // namespace sculpt::mesh::detail
