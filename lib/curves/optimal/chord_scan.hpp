#pragma once
/// \file chord_scan.hpp
/// The inner loop of the optimal solvers: the largest distance of the points between two indices
/// to the chord line (Definition 2.3), over points stored as columns (x, y, z arrays) so that two
/// points are measured per instruction. Every value is computed with the same IEEE operations in
/// the same order as ChordDistance (Eigen's cross product and squaredNorm, -ffp-contract=off), so
/// the results are bit-identical to segment_error(); tests compare them with DYNAMIC by ==.

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace sculpt::curves::detail {

/// Points as three coordinate columns.
struct PointColumns {
  std::vector<double> x, y, z;
  explicit PointColumns(const std::vector<Eigen::Vector3d>& points) {
    x.reserve(points.size());
    y.reserve(points.size());
    z.reserve(points.size());
    for (const Eigen::Vector3d& p : points) {
      x.push_back(p.x());
      y.push_back(p.y());
      z.push_back(p.z());
    }
  }
};

/// |(p_k - p_i) x d|^2 for the chord direction d = (dx, dy, dz), as scan_chord computes it.
[[nodiscard]] inline double cross2_to(const PointColumns& c, int i, int k, double dx, double dy, double dz) {
  const double wx = c.x[k] - c.x[i], wy = c.y[k] - c.y[i], wz = c.z[k] - c.z[i];
  const double c0 = wy * dz - wz * dy, c1 = wz * dx - wx * dz, c2 = wx * dy - wy * dx;
  return (c0 * c0 + c1 * c1) + c2 * c2;
}

/// Result of scan_chord: `cross2` = |(p_k - p_i) x (p_j - p_i)|^2 of the farthest interior point
/// (0 if none), or, if some point has cross2 > bound, `beyond` = such an index (else -1) and
/// cross2 is not the maximum.
struct ChordScan {
  double cross2;
  int beyond;
};

/// Largest squared cross product over the points strictly between i and j, stopping at the
/// first pair of points with one above `bound`. The distance of that point to the chord line is
/// sqrt(cross2) / sqrt(|p_j - p_i|^2), exactly as ChordDistance computes it.
[[nodiscard]] inline ChordScan scan_chord(const PointColumns& c, int i, int j, double bound) {
  const double ax = c.x[i], ay = c.y[i], az = c.z[i];
  const double dx = c.x[j] - ax, dy = c.y[j] - ay, dz = c.z[j] - az;
#if defined(__GNUC__)
  // Two points per step with GCC/Clang vector extensions (each lane is plain IEEE arithmetic).
  typedef double Double2 __attribute__((vector_size(16)));
  const Double2 vax = {ax, ax}, vay = {ay, ay}, vaz = {az, az};
  const Double2 vdx = {dx, dx}, vdy = {dy, dy}, vdz = {dz, dz};
  Double2 best = {0.0, 0.0};
  int k = i + 1;
  for (; k + 1 < j; k += 2) {
    Double2 px, py, pz;
    std::memcpy(&px, &c.x[k], sizeof px);
    std::memcpy(&py, &c.y[k], sizeof py);
    std::memcpy(&pz, &c.z[k], sizeof pz);
    const Double2 wx = px - vax, wy = py - vay, wz = pz - vaz;
    const Double2 c0 = wy * vdz - wz * vdy, c1 = wz * vdx - wx * vdz, c2 = wx * vdy - wy * vdx;
    const Double2 s = (c0 * c0 + c1 * c1) + c2 * c2;
    if (s[0] > bound || s[1] > bound) return {s[0] > bound ? s[0] : s[1], s[0] > bound ? k : k + 1};
    best = s > best ? s : best;
  }
  double largest = best[0] > best[1] ? best[0] : best[1];
#else
  double largest = 0.0;
  int k = i + 1;
#endif
  for (; k < j; ++k) {
    const double wx = c.x[k] - ax, wy = c.y[k] - ay, wz = c.z[k] - az;
    const double c0 = wy * dz - wz * dy, c1 = wz * dx - wx * dz, c2 = wx * dy - wy * dx;
    const double s = (c0 * c0 + c1 * c1) + c2 * c2;
    if (s > bound) return {s, k};
    if (s > largest) largest = s;
  }
  return {largest, -1};
}

/// scan_chord for points with z = 0: the cross product has only its z component, (0 + 0) + c2^2
/// is c2^2 exactly (x 0 = +-0, and +-0 - +-0 = +-0), so the values are the same bits.
[[nodiscard]] inline ChordScan scan_chord_planar(const PointColumns& c, int i, int j, double bound) {
  const double ax = c.x[i], ay = c.y[i];
  const double dx = c.x[j] - ax, dy = c.y[j] - ay;
  double largest = 0.0;
  for (int k = i + 1; k < j; ++k) {
    const double c2 = (c.x[k] - ax) * dy - (c.y[k] - ay) * dx;
    const double s = c2 * c2;
    if (s > bound) return {s, k};
    if (s > largest) largest = s;
  }
  return {largest, -1};
}

/// sqrt(cross2[t]) / sqrt(length2[t]) for every t (the distance ChordDistance reports for a
/// point with that squared cross product), two at a time; markers pass through: cross2[t] = -1
/// gives `beyond`, -2 gives `below`. \pre cross2.size() == length2.size()
[[nodiscard]] inline std::vector<double> chord_distances(const std::vector<double>& cross2,
                                                         const std::vector<double>& length2, double beyond,
                                                         double below) {
  const auto marker = [&](double c) { return c == -1.0 ? beyond : below; };
  const std::size_t count = cross2.size();
  std::vector<double> out(count);
  std::size_t t = 0;
#if defined(__GNUC__) && defined(__SSE2__)
  for (; t + 1 < count; t += 2) {
    const __m128d c = _mm_loadu_pd(cross2.data() + t), l = _mm_loadu_pd(length2.data() + t);
    _mm_storeu_pd(out.data() + t, _mm_div_pd(_mm_sqrt_pd(c), _mm_sqrt_pd(l)));
    if (cross2[t] < 0.0) out[t] = marker(cross2[t]);
    if (cross2[t + 1] < 0.0) out[t + 1] = marker(cross2[t + 1]);
  }
#endif
  for (; t < count; ++t) out[t] = cross2[t] < 0.0 ? marker(cross2[t]) : std::sqrt(cross2[t]) / std::sqrt(length2[t]);
  return out;
}

}  // namespace sculpt::curves::detail
