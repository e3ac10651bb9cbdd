#include "curves/curve_measures.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace sculpt::curves {
namespace {

using Vec = Eigen::Vector3d;

Vec unit_or(const Vec& v, const Vec& fallback, double scale = 0.0) {
  const double length = v.norm();
  return length > 1e-12 * scale ? Vec(v / length) : fallback;
}

// Sec. 4.2: t_k = (beta v_k + alpha v_{k+1}) / (alpha + beta) with alpha = |v_{k-1} x v_k|,
// beta = |v_{k+1} x v_{k+2}|, v_k = p_k - p_{k-1}; Bessel end conditions for open curves.
std::vector<Vec> five_point(const std::vector<Vec>& p, bool closed) {
  const int n = static_cast<int>(p.size());
  // v[k + 1] holds v_k for k = -1 .. n+1 (n points p_0 .. p_{n-1}).
  std::vector<Vec> v(n + 3, Vec::Zero());
  const auto at = [&v](int k) -> Vec& { return v[k + 1]; };
  if (closed) {
    for (int k = -1; k <= n + 1; ++k) at(k) = p[((k % n) + n) % n] - p[(((k - 1) % n) + n) % n];
  } else if (n >= 3) {
    for (int k = 1; k < n; ++k) at(k) = p[k] - p[k - 1];
    at(0) = 2.0 * at(1) - at(2);
    at(-1) = 2.0 * at(0) - at(1);
    at(n) = 2.0 * at(n - 1) - at(n - 2);
    at(n + 1) = 2.0 * at(n) - at(n - 1);
  } else {  // two points: every difference is the chord
    for (auto& w : v) w = p[1] - p[0];
  }
  std::vector<Vec> t(n);
  for (int k = 0; k < n; ++k) {
    const Vec& vm1 = at(k - 1);
    const Vec& v0 = at(k);
    const Vec& v1 = at(k + 1);
    const Vec& v2 = at(k + 2);
    const double alpha = vm1.cross(v0).norm();
    const double beta = v1.cross(v2).norm();
    const Vec blend = alpha + beta > 0.0 ? Vec((beta * v0 + alpha * v1) / (alpha + beta)) : Vec(0.5 * (v0 + v1));
    // A blend that cancels (e.g. Bessel ends extrapolated backwards) falls back to v_{k+1}.
    const double scale = v0.norm() + v1.norm();
    t[k] = unit_or(blend, unit_or(v0 + v1, unit_or(v1, unit_or(v0, Vec(1, 0, 0))), scale), scale);
  }
  return t;
}

std::vector<Vec> central(const std::vector<Vec>& p, bool closed) {
  const int n = static_cast<int>(p.size());
  std::vector<Vec> t(n);
  for (int k = 0; k < n; ++k) {
    int a = k - 1, b = k + 1;
    if (closed) {
      a = (a + n) % n;
      b = b % n;
    } else {
      a = std::max(a, 0);
      b = std::min(b, n - 1);
    }
    t[k] = unit_or(p[b] - p[a], unit_or(p[std::min(k + 1, n - 1)] - p[k], Vec(1, 0, 0)));
  }
  return t;
}

}  // namespace

std::vector<Eigen::Vector3d> tangents(const DigitizedCurve& curve, TangentMethod method) {
  const std::vector<Vec> path = path_points(curve);
  const int size = static_cast<int>(path.size());
  std::vector<Vec> result(size, Vec(1, 0, 0));
  if (size == 0) return result;
  // Work on the points with consecutive repeats removed; repeats share their tangent.
  std::vector<Vec> distinct;
  std::vector<int> owner(size);
  for (int k = 0; k < size; ++k) {
    if (distinct.empty() || path[k] != distinct.back()) distinct.push_back(path[k]);
    owner[k] = static_cast<int>(distinct.size()) - 1;
  }
  const bool closed = curve.closed;
  if (closed && distinct.size() > 1 && distinct.back() == distinct.front()) {
    distinct.pop_back();
    for (int& o : owner)
      if (o == static_cast<int>(distinct.size())) o = 0;
  }
  if (distinct.size() < 2) return result;
  const bool wrap = closed && distinct.size() >= 3;
  const std::vector<Vec> t = method == TangentMethod::FivePoint ? five_point(distinct, wrap) : central(distinct, wrap);
  for (int k = 0; k < size; ++k) result[k] = t[owner[k]];
  return result;
}

CurveMeasures::CurveMeasures(const DigitizedCurve& curve, TangentMethod method) {
  const std::vector<Vec> p = path_points(curve);
  const std::vector<Vec> t = tangents(curve, method);
  const std::size_t n = p.size();
  chord_.assign(n, 0.0);
  image_.assign(n, 0.0);
  moment_.assign(n, 0.0);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double turn = (t[k + 1] - t[k]).norm();
    chord_[k + 1] = chord_[k] + (p[k + 1] - p[k]).norm();
    image_[k + 1] = image_[k] + turn;
    moment_[k + 1] = moment_[k] + chord_[k] * turn;
  }
}

}  // namespace sculpt::curves
