#include "splines/degree_reduction.hpp"

#include <Eigen/Dense>
#include <string>

#include "base/errors.hpp"

namespace sculpt::splines {

namespace {

void check(const BSpline& bezier, int k) {
  if (!bezier.is_bezier()) throw InvalidInput("degree reduction: the curve is not a Bezier curve");
  if (k < 1 || k >= bezier.degree())
    throw InvalidInput("degree reduction: target degree must be in [1, " + std::to_string(bezier.degree() - 1) + "], got " +
                       std::to_string(k));
}

double binomial(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// integral_0^1 B_i^m(t) B_j^n(t) dt
double bernstein_product(int m, int i, int n, int j) {
  return binomial(m, i) * binomial(n, j) / ((m + n + 1) * binomial(m + n, i + j));
}

}  // namespace

FitResult reduce_degree(const BSpline& bezier, int k, const ApproximateOptions& options) {
  check(bezier, k);
  // Fig. 6: the start curve's control points lie on the target at parameters i / k.
  const auto [a, b] = bezier.domain();
  std::vector<Eigen::Vector3d> c(k + 1);
  for (int i = 0; i <= k; ++i) c[i] = bezier.point(a + (b - a) * i / k);
  const BSpline start = BSpline::bezier(c, bezier.dimension());
  ApproximateOptions o = options;
  o.fixed = {0, k};
  return approximate(target_of(bezier), start, o);
}

BSpline reduce_degree_l2(const BSpline& bezier, int k) {
  check(bezier, k);
  const int n = bezier.degree();
  const auto& P = bezier.controls();
  const int m = k - 1;  // interior unknowns Q_1 .. Q_{k-1}
  std::vector<Eigen::Vector3d> Q(k + 1);
  Q[0] = P.front();
  Q[k] = P.back();
  if (m > 0) {
    Eigen::MatrixXd G(m, m), R = Eigen::MatrixXd::Zero(m, 3);
    for (int i = 1; i <= m; ++i) {
      for (int j = 1; j <= m; ++j) G(i - 1, j - 1) = bernstein_product(k, i, k, j);
      for (int l = 0; l <= n; ++l) R.row(i - 1) += bernstein_product(k, i, n, l) * P[l].transpose();
      R.row(i - 1) -= bernstein_product(k, i, k, 0) * Q[0].transpose() + bernstein_product(k, i, k, k) * Q[k].transpose();
    }
    const Eigen::MatrixXd X = G.ldlt().solve(R);
    for (int i = 1; i <= m; ++i) Q[i] = X.row(i - 1).transpose();
  }
  return BSpline::bezier(Q, bezier.dimension());
}

}  // namespace sculpt::splines
