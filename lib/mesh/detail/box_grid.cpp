#include "mesh/detail/box_grid.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include "base/cancel.hpp"

namespace sculpt::mesh::detail {

BoxGrid::BoxGrid(std::span<const Eigen::AlignedBox3d> boxes) {
  if (boxes.empty()) return;
  Eigen::AlignedBox3d all;
  std::vector<double> extents;
  extents.reserve(boxes.size());
  for (const Eigen::AlignedBox3d& b : boxes) {
    all.extend(b);
    extents.push_back(b.sizes().maxCoeff());
  }
  std::nth_element(extents.begin(), extents.begin() + std::ptrdiff_t(extents.size() / 2), extents.end());
  // Twice the median extent: fewer entries per box, more boxes per cell. Against cells of the
  // median extent, to_mesh of bench_bsp's spheres and drilled plate takes 5-9 % less time, its
  // boxes and Menger sponge within 2 % either way (docs/benchmarks.md, session 17).
  double cell = std::max(2 * extents[extents.size() / 2], all.sizes().maxCoeff() * 0x1p-20);
  if (!(cell > 0) || !std::isfinite(cell)) cell = 1;
  const Eigen::Vector3d origin = all.min();
  auto cell_of = [&](double x, int axis) { return static_cast<std::int64_t>(std::floor((x - origin[axis]) / cell)); };
  range_.resize(boxes.size());
  auto place = [&] {
    size_t entries = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
      size_t n = 1;
      for (int axis = 0; axis < 3; ++axis) {
        range_[i][size_t(axis)] = static_cast<std::int32_t>(cell_of(boxes[i].min()[axis], axis));
        range_[i][size_t(axis) + 3] = static_cast<std::int32_t>(cell_of(boxes[i].max()[axis], axis));
        n *= static_cast<size_t>(range_[i][size_t(axis) + 3] - range_[i][size_t(axis)] + 1);
      }
      entries += n;
    }
    return entries;
  };
  const size_t budget = 8 * boxes.size() + 1024;
  size_t count = place();
  while (count > budget) {
    cell *= 2;
    count = place();
  }
  // Cells in the order (x, y, z): numbered densely over the grid's extent when that is small (a
  // counting sort), else 21 bits per axis (at most 2^20 + 1 cells along the widest axis) and
  // sorted; either way the entries come in the order (cell, box).
  for (int axis = 0; axis < 3; ++axis) dims_[size_t(axis)] = cell_of(all.max()[axis], axis) + 1;
  const double dense_cells = double(dims_[0]) * double(dims_[1]) * double(dims_[2]);
  dense_ = dense_cells <= double(4 * count + 4096);
  auto list = [&](auto&& emit) {
    CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
    for (size_t i = 0; i < range_.size(); ++i) {
      poll.tick();
      const auto& r = range_[i];
      for (std::int64_t x = r[0]; x <= r[3]; ++x)
        for (std::int64_t y = r[1]; y <= r[4]; ++y)
          for (std::int64_t z = r[2]; z <= r[5]; ++z)
            emit(key(x, y, z), static_cast<int>(i), (x == r[0] ? 1 : 0) | (y == r[1] ? 2 : 0) | (z == r[2] ? 4 : 0));
    }
  };
  if (dense_) {
    // Counting sort straight into the member list; the non-empty cells read off the counts.
    std::vector<int> start(static_cast<size_t>(dense_cells) + 1, 0);
    list([&](std::int64_t k, int, int) { ++start[size_t(k) + 1]; });  // start[k + 1]: cell k's count
    for (size_t k = 0; k + 1 < start.size(); ++k)
      if (start[k + 1] != 0) keys_.push_back(std::int64_t(k));
    for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];  // start[k]: where cell k begins
    starts_.resize(keys_.size());
    for (size_t c = 0; c < keys_.size(); ++c) starts_[c] = size_t(start[size_t(keys_[c])]);
    members_.resize(count);
    masks_.resize(count);
    list([&](std::int64_t k, int i, int mask) {
      const size_t at = size_t(start[size_t(k)]++);
      members_[at] = i;
      masks_[at] = static_cast<unsigned char>(mask);
    });
  } else {
    struct Entry {
      std::int64_t key;
      int box, mask;
    };
    std::vector<Entry> entries;
    entries.reserve(count);
    list([&](std::int64_t k, int i, int mask) { entries.push_back({k, i, mask}); });
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return std::tie(a.key, a.box) < std::tie(b.key, b.box); });
    members_.reserve(entries.size());
    masks_.reserve(entries.size());
    for (size_t e = 0; e < entries.size(); ++e) {
      if (e == 0 || entries[e].key != entries[e - 1].key) {
        keys_.push_back(entries[e].key);
        starts_.push_back(members_.size());
      }
      members_.push_back(entries[e].box);
      masks_.push_back(static_cast<unsigned char>(entries[e].mask));
    }
  }
  starts_.push_back(members_.size());
}

}  // namespace sculpt::mesh::detail
