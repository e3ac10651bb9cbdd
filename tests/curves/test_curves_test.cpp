#include "curves/test_curves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::curves;

namespace {
// Residuals of the implicit equations of Appendix B (f = 0 and g = 0).
double residual(TestCurve which, const Eigen::Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  switch (which) {
    case TestCurve::Folium:
      return std::abs(x * x * x - 3 * x * y + y * y * y) + std::abs(z);
    case TestCurve::Cubic:
      return std::abs(x * x * x - y + z) + std::abs(z);
    case TestCurve::Rose:
      return std::abs(std::pow(x, 6) + 3 * std::pow(x, 4) * y * y - 4 * x * x * y * y + 3 * x * x * std::pow(y, 4) +
                      std::pow(y, 6)) +
             std::abs(z);
    case TestCurve::Quartic:
      return std::abs(36 * x * x + 81 * y * y + 9 * z * z - 324) + std::abs(x * x + y * y - 3.94);
    case TestCurve::Sextic:
      return std::abs(y * y - x * x - x * x * x) + std::abs(z - x * x + x - 2);
    case TestCurve::Helix:
      return std::abs(x * x + y * y - 1);
  }
  return 1e300;
}
}  // namespace

TEST(TestCurves, PointsLieOnTheImplicitCurvesOfAppendixB) {
  for (TestCurve which : all_test_curves()) {
    const DigitizedCurve c = make_test_curve(which, {.points = 500});
    ASSERT_EQ(c.points.size(), 500u);
    for (const auto& p : c.points) EXPECT_LT(residual(which, p), 1e-9) << test_curve_name(which);
  }
}

TEST(TestCurves, PaperPointCountsAndNames) {
  EXPECT_EQ(make_test_curve(TestCurve::Folium).points.size(), 109u);
  EXPECT_EQ(make_test_curve(TestCurve::Cubic).points.size(), 408u);
  EXPECT_EQ(make_test_curve(TestCurve::Quartic).points.size(), 404u);
  EXPECT_EQ(make_test_curve(TestCurve::Sextic).points.size(), 234u);
  for (TestCurve which : all_test_curves()) EXPECT_EQ(test_curve_from_name(test_curve_name(which)), which);
  EXPECT_EQ(test_curve_from_name("ROSE"), TestCurve::Rose);
  EXPECT_FALSE(test_curve_from_name("goblet").has_value());
}

TEST(TestCurves, NoiseIsSeededAndDeterministic) {
  const auto a = make_test_curve(TestCurve::Helix, {.points = 50, .noise = 0.1, .seed = 42});
  const auto b = make_test_curve(TestCurve::Helix, {.points = 50, .noise = 0.1, .seed = 42});
  const auto c = make_test_curve(TestCurve::Helix, {.points = 50, .noise = 0.1, .seed = 43});
  const auto clean = make_test_curve(TestCurve::Helix, {.points = 50});
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
  double sum = 0;
  for (std::size_t k = 0; k < 50; ++k) sum += (a.points[k] - clean.points[k]).squaredNorm();
  EXPECT_NEAR(std::sqrt(sum / 150), 0.1, 0.03);  // sample standard deviation
  const auto planar = make_test_curve(TestCurve::Rose, {.points = 50, .noise = 0.1});
  for (const auto& p : planar.points) EXPECT_EQ(p.z(), 0.0);
}

TEST(TestCurves, BadCountsAreErrors) {
  EXPECT_THROW((void)make_test_curve(TestCurve::Cubic, {.points = 1}), InvalidInput);
  EXPECT_THROW((void)make_test_curve(TestCurve::Rose, {.points = 2}), InvalidInput);
  EXPECT_THROW((void)make_test_curve(TestCurve::Rose, {.points = 10, .noise = -1}), InvalidInput);
}

TEST(TestCurves, ModelFilesMatchTheGenerators) {
  // models/<name>_<n>.txt are sampled copies written by the curve_models bench program.
  for (TestCurve which : all_test_curves()) {
    const int n = paper_point_count(which);
    const std::string path =
        std::string(SCULPT_MODELS_DIR) + "/" + test_curve_name(which) + "_" + std::to_string(n) + ".txt";
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const DigitizedCurve stored = load_curve(path);
    EXPECT_EQ(stored.points, make_test_curve(which).points) << path;
  }
}
