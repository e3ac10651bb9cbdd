#include "curves/rational_bezier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"

using sculpt::curves::RationalBezier;

namespace {

double binomial(int n, int k) {
  double b = 1;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

/// Independent reference: the rational Bernstein form sum w_i B_i P_i / sum w_i B_i.
Eigen::Vector2d bernstein(const RationalBezier& c, double t) {
  const int n = c.degree();
  Eigen::Vector2d num = Eigen::Vector2d::Zero();
  double den = 0;
  for (int i = 0; i <= n; ++i) {
    const double b = binomial(n, i) * std::pow(t, i) * std::pow(1 - t, n - i) * c.weights()[i];
    num += b * c.points()[i];
    den += b;
  }
  return num / den;
}

}  // namespace

TEST(RationalBezier, QuadraticWithCos45WeightIsAnExactQuarterCircle) {
  const RationalBezier arc({{1, 0}, {1, 1}, {0, 1}}, {1, std::sqrt(0.5), 1});
  for (int k = 0; k <= 64; ++k) EXPECT_NEAR(arc.evaluate(k / 64.0).norm(), 1.0, 1e-15);
  // The midpoint of the arc is at 45 degrees.
  const Eigen::Vector2d mid = arc.evaluate(0.5);
  EXPECT_NEAR(mid.x(), std::cos(std::numbers::pi / 4), 1e-15);
  EXPECT_NEAR(mid.y(), std::sin(std::numbers::pi / 4), 1e-15);
}

TEST(RationalBezier, DeCasteljauAgreesWithTheBernsteinForm) {
  const RationalBezier c({{0, 0}, {1, 3}, {2.5, -1}, {4, 2}, {5, 0}}, {1, 2.5, 0.3, 1.7, 0.9});
  for (int k = 0; k <= 100; ++k) {
    const double t = k / 100.0;
    EXPECT_LT((c.evaluate(t) - bernstein(c, t)).norm(), 1e-13) << "t = " << t;
  }
}

TEST(RationalBezier, InterpolatesItsEndPoints) {
  const RationalBezier c({{0.5, -2}, {7, 1}, {3, 3}, {-1, 4}}, {1, 5, 0.1, 1});
  EXPECT_EQ(c.evaluate(0.0), Eigen::Vector2d(0.5, -2));
  EXPECT_EQ(c.evaluate(1.0), Eigen::Vector2d(-1, 4));
}

TEST(RationalBezier, UnitWeightsGiveThePolynomialCurve) {
  const auto c = RationalBezier::polynomial({{0, 0}, {1, 2}, {2, 0}});
  EXPECT_EQ(c.degree(), 2);
  // Polynomial quadratic: B(t) = 2 t (1 - t) P1 + ..., the apex at t = 0.5 has y = 1.
  EXPECT_NEAR(c.evaluate(0.5).y(), 1.0, 1e-15);
}

TEST(RationalBezier, RejectsBadInput) {
  using sculpt::InvalidInput;
  EXPECT_THROW(RationalBezier({{0, 0}}, {1}), InvalidInput);
  EXPECT_THROW(RationalBezier({{0, 0}, {1, 1}}, {1}), InvalidInput);
  EXPECT_THROW(RationalBezier({{0, 0}, {1, 1}}, {1, 0}), InvalidInput);
  EXPECT_THROW(RationalBezier({{0, 0}, {1, 1}}, {1, -2}), InvalidInput);
  EXPECT_THROW(RationalBezier({{0, NAN}, {1, 1}}, {1, 1}), InvalidInput);
  const RationalBezier ok({{0, 0}, {1, 1}}, {1, 1});
  EXPECT_THROW((void)ok.evaluate(1.5), InvalidInput);
  EXPECT_THROW((void)ok.evaluate(NAN), InvalidInput);
}
