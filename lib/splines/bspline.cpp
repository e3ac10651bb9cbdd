#include "splines/bspline.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::splines {

namespace {

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Basis functions and derivatives at t in span r (Piegl & Tiller A2.3).
Eigen::MatrixXd basis_derivatives(const std::vector<double>& U, int p, int r, double t, int order) {
  const int n = std::min(order, p);
  Eigen::MatrixXd ndu(p + 1, p + 1), ders = Eigen::MatrixXd::Zero(order + 1, p + 1), a(2, p + 1);
  Eigen::VectorXd left(p + 1), right(p + 1);
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[r + 1 - j];
    right[j] = U[r + j] - t;
    double saved = 0.0;
    for (int k = 0; k < j; ++k) {
      ndu(j, k) = right[k + 1] + left[j - k];
      const double temp = ndu(k, j - 1) / ndu(j, k);
      ndu(k, j) = saved + right[k + 1] * temp;
      saved = left[j - k] * temp;
    }
    ndu(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j) ders(0, j) = ndu(j, p);
  for (int k = 0; k <= p; ++k) {
    int s1 = 0, s2 = 1;
    a(0, 0) = 1.0;
    for (int m = 1; m <= n; ++m) {
      double d = 0.0;
      const int rk = k - m, pk = p - m;
      if (k >= m) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        d = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (k - 1 <= pk) ? m - 1 : p - k;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        d += a(s2, j) * ndu(rk + j, pk);
      }
      if (k <= pk) {
        a(s2, m) = -a(s1, m - 1) / ndu(pk + 1, k);
        d += a(s2, m) * ndu(k, pk);
      }
      ders(m, k) = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= n; ++k) {
    ders.row(k) *= factor;
    factor *= (p - k);
  }
  return ders;
}

// The same for degree <= kMaxFastDegree and order <= 3 on plain stack arrays (the hot path of the
// foot point search): out[k][j] is the k-th derivative of basis function j.
void basis_derivatives_fast(const std::vector<double>& U, int p, int r, double t, int order, double out[4][kMaxFastDegree + 1]) {
  constexpr int S = kMaxFastDegree + 1;
  double ndu[S][S], a[2][S], left[S], right[S];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - U[r + 1 - j];
    right[j] = U[r + j] - t;
    double saved = 0.0;
    for (int k = 0; k < j; ++k) {
      ndu[j][k] = right[k + 1] + left[j - k];
      const double temp = ndu[k][j - 1] / ndu[j][k];
      ndu[k][j] = saved + right[k + 1] * temp;
      saved = left[j - k] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int k = 0; k <= order; ++k)
    for (int j = 0; j <= p; ++j) out[k][j] = 0.0;
  for (int j = 0; j <= p; ++j) out[0][j] = ndu[j][p];
  const int n = std::min(order, p);
  for (int k = 0; k <= p && n > 0; ++k) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int m = 1; m <= n; ++m) {
      double d = 0.0;
      const int rk = k - m, pk = p - m;
      if (k >= m) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (k - 1 <= pk) ? m - 1 : p - k;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (k <= pk) {
        a[s2][m] = -a[s1][m - 1] / ndu[pk + 1][k];
        d += a[s2][m] * ndu[k][pk];
      }
      out[m][k] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) out[k][j] *= factor;
    factor *= (p - k);
  }
}

// Boehm's insertion of t into an arbitrary knot vector U with controls P (Piegl & Tiller A5.1, r = 1).
void boehm(std::vector<double>& U, std::vector<Eigen::Vector3d>& P, int p, double t) {
  const int n = static_cast<int>(P.size());
  int k = static_cast<int>(std::upper_bound(U.begin(), U.end(), t) - U.begin()) - 1;
  k = std::clamp(k, p, n - 1);
  std::vector<Eigen::Vector3d> Q(n + 1);
  for (int i = 0; i <= k - p; ++i) Q[i] = P[i];
  for (int i = k; i < n; ++i) Q[i + 1] = P[i];
  for (int i = k - p + 1; i <= k; ++i) {
    const double denom = U[i + p] - U[i];
    const double alpha = denom > 0 ? (t - U[i]) / denom : 0.0;
    Q[i] = alpha * P[i] + (1.0 - alpha) * P[i - 1];
  }
  U.insert(U.begin() + k + 1, t);
  P = std::move(Q);
}

std::string num(double v) { return std::to_string(v); }

}  // namespace

BSpline::BSpline(int degree, std::vector<double> knots, std::vector<Eigen::Vector3d> controls, bool closed,
                 int dimension)
    : degree_(degree), closed_(closed), knots_(std::move(knots)), controls_(std::move(controls)) {
  if (degree_ < 1) throw InvalidInput("B-spline: degree must be at least 1, got " + std::to_string(degree_));
  const int n = static_cast<int>(controls_.size()), p = degree_;
  if (n < p + 1)
    throw InvalidInput("B-spline: degree " + std::to_string(p) + " needs at least " + std::to_string(p + 1) +
                       " control points, got " + std::to_string(n));
  const std::size_t expected = closed_ ? n + 1 : n + p + 1;
  if (knots_.size() != expected)
    throw InvalidInput("B-spline: " + std::string(closed_ ? "closed" : "open") + " curve with " + std::to_string(n) +
                       " control points of degree " + std::to_string(p) + " needs " + std::to_string(expected) +
                       " knots, got " + std::to_string(knots_.size()));
  for (std::size_t i = 0; i < knots_.size(); ++i) {
    if (!std::isfinite(knots_[i])) throw InvalidInput("B-spline: knot " + std::to_string(i) + " is not finite");
    if (i > 0 && knots_[i] < knots_[i - 1])
      throw InvalidInput("B-spline: knots decrease at index " + std::to_string(i) + " (" + num(knots_[i - 1]) +
                         " > " + num(knots_[i]) + ")");
  }
  for (int i = 0; i < n; ++i)
    if (!controls_[i].allFinite()) throw InvalidInput("B-spline: control point " + std::to_string(i) + " is not finite");
  if (dimension == 0) {
    dimension = 2;
    for (const auto& c : controls_)
      if (c.z() != 0.0) dimension = 3;
  }
  if (dimension != 2 && dimension != 3)
    throw InvalidInput("B-spline: dimension must be 2 or 3, got " + std::to_string(dimension));
  if (dimension == 2)
    for (int i = 0; i < n; ++i)
      if (controls_[i].z() != 0.0)
        throw InvalidInput("B-spline: 2D curve with nonzero z at control point " + std::to_string(i));
  dimension_ = dimension;

  if (closed_) {
    const double period = knots_[n] - knots_[0];
    if (!(period > 0)) throw InvalidInput("B-spline: closed curve with an empty period");
    ext_knots_.resize(n + 2 * p + 1);
    for (int i = 0; i <= n + 2 * p; ++i) {
      const int j = i - p, q = floor_div(j, n);
      ext_knots_[i] = knots_[j - q * n] + q * period;
    }
    ext_controls_ = controls_;
    for (int i = 0; i < p; ++i) ext_controls_.push_back(controls_[i % n]);
  } else {
    if (!(knots_[n] > knots_[p])) throw InvalidInput("B-spline: open curve with an empty domain");
    ext_knots_ = knots_;
    ext_controls_ = controls_;
  }
  // Interior multiplicity (the domain's knots, periodic for closed curves) at most p.
  const auto [a, b] = domain();
  for (std::size_t i = 0; i < ext_knots_.size();) {
    std::size_t j = i;
    while (j < ext_knots_.size() && ext_knots_[j] == ext_knots_[i]) ++j;
    const bool interior = closed_ ? (ext_knots_[i] >= a && ext_knots_[i] <= b) : (ext_knots_[i] > a && ext_knots_[i] < b);
    if (interior && static_cast<int>(j - i) > p)
      throw InvalidInput("B-spline: knot " + num(ext_knots_[i]) + " has multiplicity " + std::to_string(j - i) +
                         ", more than the degree " + std::to_string(p));
    i = j;
  }
}

BSpline BSpline::clamped(int degree, std::vector<Eigen::Vector3d> controls, int dimension) {
  const int n = static_cast<int>(controls.size());
  if (degree < 1) throw InvalidInput("B-spline: degree must be at least 1, got " + std::to_string(degree));
  if (n < degree + 1)
    throw InvalidInput("B-spline: degree " + std::to_string(degree) + " needs at least " + std::to_string(degree + 1) +
                       " control points, got " + std::to_string(n));
  std::vector<double> knots(n + degree + 1, 0.0);
  const int spans = n - degree;
  for (int i = 0; i < static_cast<int>(knots.size()); ++i)
    knots[i] = i <= degree ? 0.0 : i >= n ? 1.0 : static_cast<double>(i - degree) / spans;
  return BSpline(degree, std::move(knots), std::move(controls), false, dimension);
}

BSpline BSpline::periodic(int degree, std::vector<Eigen::Vector3d> controls, int dimension) {
  std::vector<double> knots(controls.size() + 1);
  for (std::size_t i = 0; i < knots.size(); ++i) knots[i] = static_cast<double>(i);
  return BSpline(degree, std::move(knots), std::move(controls), true, dimension);
}

BSpline BSpline::bezier(std::vector<Eigen::Vector3d> controls, int dimension) {
  const int degree = static_cast<int>(controls.size()) - 1;
  if (degree < 1) throw InvalidInput("Bezier curve: needs at least 2 control points, got " + std::to_string(controls.size()));
  return clamped(degree, std::move(controls), dimension);
}

std::pair<double, double> BSpline::domain() const {
  const int n = control_count();
  return closed_ ? std::pair{knots_[0], knots_[n]} : std::pair{knots_[degree_], knots_[n]};
}

std::vector<double> BSpline::breaks() const {
  const auto [a, b] = domain();
  std::vector<double> out;
  for (double k : knots_)
    if (k >= a && k <= b && (out.empty() || k > out.back())) out.push_back(k);
  return out;
}

bool BSpline::is_bezier() const {
  if (closed_) return false;
  const int n = control_count();
  return n == degree_ + 1 && knots_.front() == knots_[degree_] && knots_.back() == knots_[n];
}

double BSpline::wrap(double t) const {
  if (!std::isfinite(t)) throw InvalidInput("B-spline: parameter is not finite");
  const auto [a, b] = domain();
  if (!closed_) return std::clamp(t, a, b);
  const double period = b - a;
  double s = a + std::fmod(t - a, period);
  if (s < a) s += period;
  if (s >= b) s = a;
  return s;
}

int BSpline::span(double t) const {
  const int N = static_cast<int>(ext_controls_.size()), p = degree_;
  int r = static_cast<int>(std::upper_bound(ext_knots_.begin(), ext_knots_.end(), t) - ext_knots_.begin()) - 1;
  r = std::clamp(r, p, N - 1);
  while (r > p && ext_knots_[r] == ext_knots_[r + 1]) --r;  // t at the end of the domain
  return r;
}

Basis BSpline::basis(double t, int order) const {
  if (order < 0) throw InvalidInput("B-spline: derivative order must be >= 0");
  const double s = wrap(t);
  const int r = span(s), n = control_count();
  Basis out;
  out.value = basis_derivatives(ext_knots_, degree_, r, s, order);
  out.index.resize(degree_ + 1);
  for (int j = 0; j <= degree_; ++j) out.index[j] = (r - degree_ + j) % n;
  return out;
}

std::vector<Eigen::Vector3d> BSpline::derivatives(double t, int order) const {
  const Basis b = basis(t, order);
  std::vector<Eigen::Vector3d> out(order + 1, Eigen::Vector3d::Zero());
  for (int k = 0; k <= order; ++k)
    for (int j = 0; j <= degree_; ++j) out[k] += b.value(k, j) * controls_[b.index[j]];
  return out;
}

std::array<Eigen::Vector3d, 4> BSpline::jet(double t, int order) const {
  if (order < 0 || order > 3) throw InvalidInput("B-spline: jet order must be in [0, 3]");
  std::array<Eigen::Vector3d, 4> out;
  out.fill(Eigen::Vector3d::Zero());
  if (degree_ > kMaxFastDegree) {
    const auto d = derivatives(t, order);
    std::copy(d.begin(), d.end(), out.begin());
    return out;
  }
  const double s = wrap(t);
  const int r = span(s);
  double v[4][kMaxFastDegree + 1];
  basis_derivatives_fast(ext_knots_, degree_, r, s, order, v);
  for (int j = 0; j <= degree_; ++j) {
    const Eigen::Vector3d& c = ext_controls_[r - degree_ + j];
    for (int k = 0; k <= order; ++k) out[k] += v[k][j] * c;
  }
  return out;
}

SmallBasis BSpline::small_basis(double t, bool with_derivative) const {
  SmallBasis out;
  if (degree_ > kMaxFastDegree) throw InvalidInput("B-spline: small_basis needs degree <= " + std::to_string(kMaxFastDegree));
  const double s = wrap(t);
  const int r = span(s), n = control_count();
  double v[4][kMaxFastDegree + 1];
  basis_derivatives_fast(ext_knots_, degree_, r, s, with_derivative ? 1 : 0, v);
  out.count = degree_ + 1;
  for (int j = 0; j <= degree_; ++j) {
    out.index[j] = (r - degree_ + j) % n;
    out.value[j] = v[0][j];
    if (with_derivative) out.derivative[j] = v[1][j];
  }
  return out;
}

BasisJet BSpline::basis_jet(double t, int order) const {
  if (degree_ > kMaxFastDegree) throw InvalidInput("B-spline: basis_jet needs degree <= " + std::to_string(kMaxFastDegree));
  if (order < 0 || order > 2) throw InvalidInput("B-spline: basis_jet order must be in [0, 2]");
  BasisJet out;
  const double s = wrap(t);
  const int r = span(s), n = control_count();
  double v[4][kMaxFastDegree + 1];
  basis_derivatives_fast(ext_knots_, degree_, r, s, order, v);
  out.count = degree_ + 1;
  for (int j = 0; j <= degree_; ++j) {
    out.index[j] = (r - degree_ + j) % n;
    for (int k = 0; k <= order; ++k) out.value[k][j] = v[k][j];
  }
  return out;
}

Eigen::Vector3d BSpline::point(double t) const { return jet(t, 0)[0]; }

double BSpline::curvature(double t) const {
  const auto d = jet(t, 2);
  const double speed = d[1].norm();
  if (!(speed > 1e-300)) return 0.0;
  const Eigen::Vector3d cross = d[1].cross(d[2]);
  const double k = cross.norm() / (speed * speed * speed);
  if (dimension_ == 2) return cross.z() < 0 ? -k : k;
  return k;
}

BSpline BSpline::insert_knot(double t) const {
  if (!std::isfinite(t)) throw InvalidInput("insert_knot: parameter is not finite");
  const int p = degree_, n = control_count();
  const auto [a, b] = domain();
  if (!closed_) {
    if (!(t > a && t < b))
      throw InvalidInput("insert_knot: " + num(t) + " is not inside the domain [" + num(a) + ", " + num(b) + "]");
    std::vector<double> U = knots_;
    std::vector<Eigen::Vector3d> P = controls_;
    boehm(U, P, p, t);
    return BSpline(p, std::move(U), std::move(P), false, dimension_);
  }
  // Closed: unroll three periods, insert every image of t, cut the middle period out again.
  const double period = b - a, s = wrap(t);
  const int N = 3 * n + p;
  std::vector<double> U(N + p + 1);
  for (int i = 0; i <= N + p; ++i) {
    const int j = i - p, q = floor_div(j, n);
    U[i] = knots_[j - q * n] + q * period;
  }
  std::vector<Eigen::Vector3d> P(N);
  for (int i = 0; i < N; ++i) P[i] = controls_[i % n];
  for (int q = 0; q < 3; ++q) boehm(U, P, p, s + q * period);
  const int start = static_cast<int>(std::lower_bound(U.begin(), U.end(), a + period) - U.begin()) - p;
  std::vector<double> breaks(n + 2);
  for (int i = 0; i <= n + 1; ++i) breaks[i] = U[start + p + i] - period;
  breaks.front() = a;
  breaks.back() = b;
  std::vector<Eigen::Vector3d> Q(P.begin() + start, P.begin() + start + n + 1);
  return BSpline(p, std::move(breaks), std::move(Q), true, dimension_);
}

BSpline BSpline::with_controls(std::vector<Eigen::Vector3d> controls) const {
  if (static_cast<int>(controls.size()) != control_count())
    throw InvalidInput("B-spline: expected " + std::to_string(control_count()) + " control points, got " +
                       std::to_string(controls.size()));
  return BSpline(degree_, knots_, std::move(controls), closed_, dimension_);
}

}  // namespace sculpt::splines
