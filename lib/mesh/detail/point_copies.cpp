#include "mesh/detail/point_copies.hpp"

#include <bit>
#include <cstdint>

namespace sculpt::mesh::detail {
namespace {

/// The coordinate's bits with -0 taken as +0 (equal under ==, so they must hash alike).
std::uint64_t key_bits(double x) { return std::bit_cast<std::uint64_t>(x == 0 ? 0.0 : x); }

/// A 64-bit mix of the three coordinates (multiply-xorshift; only the table's spread matters).
std::uint64_t point_hash(const Eigen::Vector3d& p) {
  std::uint64_t h = key_bits(p.x()) * 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 29) ^ key_bits(p.y())) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 31) ^ key_bits(p.z())) * 0x94D049BB133111EBull;
  return h ^ (h >> 32);
}

}  // namespace

std::vector<int> first_copies(std::span<const Eigen::Vector3d> points, std::span<const char> take) {
  const size_t n = points.size();
  std::vector<int> first(n);
  // Open addressing with linear probing, at most half full; a slot holds the first index at its point.
  const size_t capacity = std::bit_ceil(2 * n + 2);
  const size_t mask = capacity - 1;
  std::vector<int> table(capacity, -1);
  for (size_t v = 0; v < n; ++v) {
    first[v] = int(v);
    const Eigen::Vector3d& p = points[v];
    if ((!take.empty() && take[v] == 0) || !p.allFinite()) continue;
    for (size_t slot = size_t(point_hash(p)) & mask;; slot = (slot + 1) & mask) {
      const int at = table[slot];
      if (at < 0) {
        table[slot] = int(v);
        break;
      }
      if (points[size_t(at)] == p) {
        first[v] = at;
        break;
      }
    }
  }
  return first;
}

}  // namespace sculpt::mesh::detail
