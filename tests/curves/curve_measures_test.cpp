#include "curves/curve_measures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace sculpt::curves;
using Vec = Eigen::Vector3d;

namespace {

DigitizedCurve circle(int n, bool closed, double arc = 2.0 * std::numbers::pi) {
  DigitizedCurve c;
  c.dimension = 2;
  c.closed = closed;
  for (int k = 0; k < n; ++k) {
    const double t = arc * k / (closed ? n : n - 1);
    c.points.push_back({std::cos(t), std::sin(t), 0.0});
  }
  return c;
}

}  // namespace

TEST(Tangents, FivePointIsExactOnUniformCircleInterior) {
  // Equal spacing makes alpha = beta, so t is the direction of p[k+1] - p[k-1]: the true tangent.
  const DigitizedCurve c = circle(40, false, 3.0);
  const auto t = tangents(c, TangentMethod::FivePoint);
  for (int k = 2; k + 2 < 40; ++k) {
    const Vec& p = c.points[k];
    const Vec exact(-p.y(), p.x(), 0.0);
    EXPECT_NEAR((t[k] - exact).norm(), 0.0, 1e-12) << k;
  }
  // Bessel end conditions: close to the true tangent at the ends too.
  EXPECT_LT((t[0] - Vec(0, 1, 0)).norm(), 0.05);
  const Vec& q = c.points.back();
  EXPECT_LT((t.back() - Vec(-q.y(), q.x(), 0)).norm(), 0.05);
}

TEST(Tangents, ClosedCircleWrapsAround) {
  const DigitizedCurve c = circle(24, true);
  for (auto method : {TangentMethod::FivePoint, TangentMethod::CentralDifference}) {
    const auto t = tangents(c, method);
    ASSERT_EQ(t.size(), 25u);  // path repeats the first point
    for (int k = 0; k < 24; ++k) {
      const Vec& p = c.points[k];
      EXPECT_NEAR((t[k] - Vec(-p.y(), p.x(), 0)).norm(), 0.0, 1e-12) << k;
    }
    EXPECT_EQ(t[24], t[0]);
  }
}

TEST(Tangents, UnitLengthAndNoNanWithRepeatedPoints) {
  DigitizedCurve c;
  c.points = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 3, 1}, {3, 3, 1}};
  for (auto method : {TangentMethod::FivePoint, TangentMethod::CentralDifference})
    for (const Vec& t : tangents(c, method)) {
      EXPECT_TRUE(t.allFinite());
      EXPECT_NEAR(t.norm(), 1.0, 1e-12);
    }
}

TEST(Tangents, AllPointsEqualGivesDefinedTangents) {
  DigitizedCurve c;
  c.points.assign(5, Vec(1, 2, 3));
  for (const Vec& t : tangents(c)) EXPECT_EQ(t, Vec(1, 0, 0));
}

TEST(Tangents, StraightLineHasConstantTangentAndNoImage) {
  DigitizedCurve c;
  for (int k = 0; k < 10; ++k) c.points.push_back(Vec(1, 2, 2) * (k * k * 0.1));
  const auto t = tangents(c);
  for (const Vec& v : t) EXPECT_NEAR((v - Vec(1, 2, 2) / 3.0).norm(), 0.0, 1e-12);
  const CurveMeasures m(c);
  EXPECT_NEAR(m.image_length(0, 9), 0.0, 1e-12);
  EXPECT_NEAR(m.chord_length(0, 9), 3.0 * 8.1, 1e-12);
}

TEST(CurveMeasures, RangeQueriesMatchDirectSums) {
  const DigitizedCurve c = circle(30, false, 2.5);
  const CurveMeasures m(c);
  const auto t = tangents(c);
  for (int i = 0; i < 30; i += 3)
    for (int j = i; j < 30; j += 4) {
      double chord = 0, image = 0, moment = 0;
      for (int k = i; k < j; ++k) {
        moment += chord * (t[k + 1] - t[k]).norm();
        chord += (c.points[k + 1] - c.points[k]).norm();
        image += (t[k + 1] - t[k]).norm();
      }
      EXPECT_NEAR(m.chord_length(i, j), chord, 1e-12);
      EXPECT_NEAR(m.image_length(i, j), image, 1e-12);
      EXPECT_NEAR(m.image_moment(i, j), moment, 1e-12);
    }
}

TEST(CurveMeasures, ClosedCircleImageLengthIsAnalytic) {
  // Exact unit tangents turn by 2 pi / n per point: chord of the unit circle 2 sin(pi / n) each.
  const int n = 50;
  const CurveMeasures m(circle(n, true));
  EXPECT_NEAR(m.image_length(0, n), n * 2.0 * std::sin(std::numbers::pi / n), 1e-12);
  EXPECT_NEAR(m.chord_length(0, n), n * 2.0 * std::sin(std::numbers::pi / n), 1e-12);
}
