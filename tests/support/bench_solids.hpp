#pragma once
/// \file bench_solids.hpp
/// The solids of tests/bench/bsp/CASES.md, shared by the tests and the benchmarks.
///
/// menger_sponge: differences of bars from a cube (273 at level 3). 1/27 is not on the kernel grid, so the
/// sponge is built in units of 1/3^level (integer coordinates, exact): the cube [0, 3^level]^3,
/// bars reaching half the cube beyond it on both sides. Volume 20^level in those units.

#include <vector>
#include <cmath>
#include <cstdint>

#include <Eigen/Core>

#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"

namespace sculpt::checks {

inline Solid menger_sponge(int level) {
  const double u = std::pow(3.0, level);
  Solid s = box({0, 0, 0}, {u, u, u});
  for (int l = 1; l <= level; ++l) {
    const int m = int(std::pow(3, l));
    const double w = u / m;
    for (int axis = 0; axis < 3; ++axis)
      for (int i = 1; i < m; i += 3)
        for (int j = 1; j < m; j += 3) {
          Eigen::Vector3d lo, hi;
          const int a = (axis + 1) % 3, b = (axis + 2) % 3;
          lo[axis] = -0.5 * u, hi[axis] = 1.5 * u;
          lo[a] = i * w, hi[a] = (i + 1) * w;
          lo[b] = j * w, hi[b] = (j + 1) * w;
          s = std::move(s) - box(lo, hi);
        }
  }
  return s;
}

/// The `count` boxes of the 32-bit LCG of CASES.md, in order.
inline std::vector<Solid> lcg_box_list(int count) {
  std::uint32_t state = 1;
  auto next = [&] { return state = 1664525u * state + 1013904223u; };
  std::vector<Solid> boxes;
  boxes.reserve(std::size_t(std::max(0, count)));
  for (int k = 0; k < count; ++k) {
    Eigen::Vector3d lo, size;
    for (int i = 0; i < 3; ++i) lo[i] = (next() >> 16) / 4096.0;
    for (int i = 0; i < 3; ++i) size[i] = 0.5 + ((next() >> 16) >> 5) / 1024.0;
    boxes.push_back(box(lo, lo + size));
  }
  return boxes;
}

/// Union of `count` boxes from the 32-bit LCG of CASES.md, accumulated in place one at a time.
inline Solid lcg_boxes(int count) {
  Solid s;
  for (const Solid& b : lcg_box_list(count)) s = std::move(s) | b;
  return s;
}

}  // namespace sculpt::checks
