#include "mesh/detail/box_hash.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::mesh::detail {
namespace {

std::int64_t cell_key(int k, int x, int y, int z) {
  return (static_cast<std::int64_t>(x) * 73856093) ^ (static_cast<std::int64_t>(y) * 19349663) ^
         (static_cast<std::int64_t>(z) * 83492791) ^ (static_cast<std::int64_t>(k) * 2654435761);
}

}  // namespace

/// Cell range of a box at level k, or false if the coordinates are out of range. (Inline, as
/// every insert, erase and query computes ranges level by level.)
inline bool BoxHash::cell_range(const Eigen::AlignedBox3d& box, int k, Eigen::Array3i& lo, Eigen::Array3i& hi) const {
  const double size = std::ldexp(cell_, 2 * k);
  const Eigen::Array3d a = (box.min().array() / size).floor(), b = (box.max().array() / size).floor();
  if (!a.allFinite() || !b.allFinite() || a.abs().maxCoeff() > 1e9 || b.abs().maxCoeff() > 1e9) return false;
  lo = a.cast<int>();
  hi = b.cast<int>();
  return true;
}

/// The level a box is kept at, or kBig.
inline int BoxHash::level_of(const Eigen::AlignedBox3d& box) const {
  Eigen::Array3i lo, hi;
  for (int k = 0; k < kLevels; ++k)
    if (cell_range(box, k, lo, hi) && (hi - lo).maxCoeff() <= 3) return k;
  return kBig;
}

void BoxHash::update_cells(int id, const Eigen::AlignedBox3d& box, int k, int sign) {
  per_level_[size_t(k)] += sign;
  Eigen::Array3i lo, hi;
  cell_range(box, k, lo, hi);
  for (int x = lo.x(); x <= hi.x(); ++x)
    for (int y = lo.y(); y <= hi.y(); ++y)
      for (int z = lo.z(); z <= hi.z(); ++z) {
        auto& list = cells_[cell_key(k, x, y, z)];
        if (sign > 0)
          list.push_back(id);
        else
          std::erase(list, id);
      }
}

void BoxHash::insert(int id, const Eigen::AlignedBox3d& box) {
  if (level_.size() <= size_t(id)) level_.resize(size_t(id) + 1, kAbsent);
  const int k = level_of(box);
  level_[size_t(id)] = k;
  if (k == kBig)
    big_.push_back(id);
  else
    update_cells(id, box, k, +1);
}

void BoxHash::erase(int id, const Eigen::AlignedBox3d& box) {
  const int k = level_[size_t(id)];
  level_[size_t(id)] = kAbsent;
  if (k == kBig)
    std::erase(big_, id);
  else
    update_cells(id, box, k, -1);
}

std::vector<int> BoxHash::near(const Eigen::AlignedBox3d& box) const {
  // Each id once (it may sit in several cells): marked with this query's stamp.
  if (seen_.size() < level_.size()) seen_.resize(level_.size(), 0);
  if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0), stamp_ = 1;
  std::vector<int> out = big_;
  for (int k = 0; k < kLevels; ++k) {
    if (per_level_[size_t(k)] == 0) continue;
    Eigen::Array3i lo, hi;
    if (!cell_range(box, k, lo, hi) || (hi - lo + 1).cast<double>().prod() > 4096) {
      for (size_t t = 0; t < level_.size(); ++t)  // a query far larger than this level's cells
        if (level_[t] == k) out.push_back(static_cast<int>(t));
      continue;
    }
    for (int x = lo.x(); x <= hi.x(); ++x)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int z = lo.z(); z <= hi.z(); ++z) {
          const auto it = cells_.find(cell_key(k, x, y, z));
          if (it == cells_.end()) continue;
          for (int t : it->second)
            if (seen_[size_t(t)] != stamp_) {
              seen_[size_t(t)] = stamp_;
              out.push_back(t);
            }
        }
  }
  return out;
}

}  // namespace sculpt::mesh::detail
