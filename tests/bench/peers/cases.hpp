#pragma once
/// \file cases.hpp
/// C++ mirror of cases.mjs (definitions in tests/bench/bsp/CASES.md), header-only, so that our
/// bench builds exactly the inputs the peers build:
///   #include "../peers/cases.hpp"   (from tests/bench/bsp/)
/// Reference values (also printed by the peers as expected=): randomBoxes(1000)[0] is
/// [3.783203125, 5.908203125, 8.06787109375] - [5.6923828125, 6.5087890625, 9.30615234375], and the
/// union of the 1000 boxes has volume 2376.1997691816941 exactly (union_volume below).
/// menger_bars(3) has 273 bars, the last [0.9259259259259259, 0.9259259259259259, -0.5] -
/// [0.9629629629629629, 0.9629629629629629, 1.5].

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace sculpt::bench_cases {

struct Box {
  std::array<double, 3> lo;
  std::array<double, 3> hi;
};

/// 32-bit LCG (Numerical Recipes): state' = 1664525 * state + 1013904223 mod 2^32.
class Lcg {
 public:
  explicit Lcg(uint32_t seed) : state_(seed) {}
  uint32_t next() { return state_ = 1664525u * state_ + 1013904223u; }

 private:
  uint32_t state_;
};

/// Unit-cube Menger sponge bars, in the order level, axis, i, j (CASES.md).
inline std::vector<Box> menger_bars(int level) {
  std::vector<Box> bars;
  double m = 1;
  for (int l = 1; l <= level; ++l) {
    m *= 3;
    for (int axis = 0; axis < 3; ++axis)
      for (int i = 1; i < m; i += 3)
        for (int j = 1; j < m; j += 3) {
          Box b{};
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          b.lo[axis] = -0.5;
          b.hi[axis] = 1.5;
          b.lo[u] = i / m;
          b.hi[u] = (i + 1) / m;
          b.lo[v] = j / m;
          b.hi[v] = (j + 1) / m;
          bars.push_back(b);
        }
  }
  return bars;
}

/// `count` random boxes from Lcg(seed): corner (h / 4096), size 0.5 + (h >> 5) / 1024, h = draw >> 16.
inline std::vector<Box> random_boxes(int count, uint32_t seed = 1) {
  Lcg rng(seed);
  std::vector<Box> boxes;
  for (int k = 0; k < count; ++k) {
    Box b{};
    for (int i = 0; i < 3; ++i) b.lo[i] = (rng.next() >> 16) / 4096.0;
    for (int i = 0; i < 3; ++i) b.hi[i] = b.lo[i] + 0.5 + ((rng.next() >> 16) >> 5) / 1024.0;
    boxes.push_back(b);
  }
  return boxes;
}

/// Exact volume of a union of boxes with dyadic coordinates (coordinate compression in x and y,
/// interval merge in z), as in cases.mjs.
inline double union_volume(const std::vector<Box>& boxes) {
  std::set<double> xs;
  for (const Box& b : boxes) xs.insert({b.lo[0], b.hi[0]});
  const std::vector<double> x(xs.begin(), xs.end());
  double volume = 0;
  for (size_t i = 0; i + 1 < x.size(); ++i) {
    std::vector<const Box*> slab;
    for (const Box& b : boxes)
      if (b.lo[0] <= x[i] && b.hi[0] >= x[i + 1]) slab.push_back(&b);
    if (slab.empty()) continue;
    std::set<double> ys;
    for (const Box* b : slab) ys.insert({b->lo[1], b->hi[1]});
    const std::vector<double> y(ys.begin(), ys.end());
    double area = 0;
    for (size_t j = 0; j + 1 < y.size(); ++j) {
      std::vector<std::pair<double, double>> zs;
      for (const Box* b : slab)
        if (b->lo[1] <= y[j] && b->hi[1] >= y[j + 1]) zs.emplace_back(b->lo[2], b->hi[2]);
      std::sort(zs.begin(), zs.end());
      double length = 0, start = 0, end = 0;
      bool open = false;
      for (auto [z0, z1] : zs) {
        if (!open || z0 > end) {
          if (open) length += end - start;
          start = z0;
          end = z1;
          open = true;
        } else if (z1 > end) {
          end = z1;
        }
      }
      if (open) length += end - start;
      area += (y[j + 1] - y[j]) * length;
    }
    volume += (x[i + 1] - x[i]) * area;
  }
  return volume;
}

}  // namespace sculpt::bench_cases
