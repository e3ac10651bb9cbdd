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
#include <numbers>
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

/// 4x4 column-major matrix (cases.mjs rotationAbout, same formula and operation order) of the
/// rotation by `degrees` about the axis through `centre` with direction `axis`.
inline std::array<double, 16> rotation_about(std::array<double, 3> axis, double degrees,
                                             std::array<double, 3> centre = {0, 0, 0}) {
  const double len = std::hypot(axis[0], axis[1], axis[2]);
  const double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
  const double t = degrees * std::numbers::pi / 180, c = std::cos(t), s = std::sin(t), k = 1 - c;
  const double r[3][3] = {{c + x * x * k, x * y * k - z * s, x * z * k + y * s},
                          {y * x * k + z * s, c + y * y * k, y * z * k - x * s},
                          {z * x * k - y * s, z * y * k + x * s, c + z * z * k}};
  double tr[3];
  for (int i = 0; i < 3; ++i) tr[i] = centre[i] - (r[i][0] * centre[0] + r[i][1] * centre[1] + r[i][2] * centre[2]);
  return {r[0][0], r[1][0], r[2][0], 0, r[0][1], r[1][1], r[2][1], 0, r[0][2], r[1][2], r[2][2], 0, tr[0], tr[1], tr[2], 1};
}

/// sphere_minus_sphere: centre of the second sphere (cases.mjs SPHERE_OFFSET).
inline constexpr std::array<double, 3> sphere_offset = {0.5, 0.375, 0.25};

/// sphere_minus_tilted_cube: the unit cube turned by 30 degrees about (1, 2, 3) (cases.mjs TILTED_CUBE).
inline std::array<double, 16> tilted_cube() { return rotation_about({1, 2, 3}, 30); }

/// drilled_plate: hole axes (x, y) for `count` holes, row by row (cases.mjs drillCentres).
inline std::vector<std::array<double, 2>> drill_centres(int count) {
  const int side = int(std::ceil(std::sqrt(double(count))));
  std::vector<std::array<double, 2>> centres;
  for (int k = 0; k < count; ++k) centres.push_back({(k % side) + 0.5, (k / side) + 0.5});
  return centres;
}

struct RotatedBox {
  Box box;
  std::array<double, 16> matrix;  ///< column-major, rotation about the box's centre
};

/// rotated_boxes: `count` boxes from Lcg(seed), each with its rotation (cases.mjs rotatedBoxes).
inline std::vector<RotatedBox> rotated_boxes(int count, uint32_t seed = 1) {
  Lcg rng(seed);
  std::vector<RotatedBox> boxes;
  for (int k = 0; k < count; ++k) {
    RotatedBox b{};
    for (int i = 0; i < 3; ++i) b.box.lo[i] = (rng.next() >> 16) / 8192.0;
    for (int i = 0; i < 3; ++i) b.box.hi[i] = b.box.lo[i] + 0.5 + ((rng.next() >> 16) >> 5) / 1024.0;
    std::array<double, 3> axis{};
    for (int i = 0; i < 3; ++i) axis[i] = (rng.next() >> 16) / 32768.0 - 1;
    if (axis[0] == 0 && axis[1] == 0 && axis[2] == 0) axis = {0, 0, 1};
    const double degrees = (rng.next() >> 16) * 360.0 / 65536;
    std::array<double, 3> centre{};
    for (int i = 0; i < 3; ++i) centre[i] = (b.box.lo[i] + b.box.hi[i]) / 2;
    b.matrix = rotation_about(axis, degrees, centre);
    boxes.push_back(b);
  }
  return boxes;
}

}  // namespace sculpt::bench_cases
