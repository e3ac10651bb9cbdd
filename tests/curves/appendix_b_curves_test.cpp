#include "curves/appendix_b_curves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "base/errors.hpp"
#include "support/source_paths.hpp"

using namespace sculpt;
using namespace sculpt::curves;

namespace {
// Residuals of the implicit equations of Appendix B (f = 0 and g = 0).
double residual(AppendixBCurve which, const Eigen::Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  switch (which) {
    case AppendixBCurve::Folium:
      return std::abs(x * x * x - 3 * x * y + y * y * y) + std::abs(z);
    case AppendixBCurve::Cubic:
      return std::abs(x * x * x - y + z) + std::abs(z);
    case AppendixBCurve::Rose:
      return std::abs(std::pow(x, 6) + 3 * std::pow(x, 4) * y * y - 4 * x * x * y * y + 3 * x * x * std::pow(y, 4) +
                      std::pow(y, 6)) +
             std::abs(z);
    case AppendixBCurve::Quartic:
      return std::abs(36 * x * x + 81 * y * y + 9 * z * z - 324) + std::abs(x * x + y * y - 3.94);
    case AppendixBCurve::Sextic:
      return std::abs(y * y - x * x - x * x * x) + std::abs(z - x * x + x - 2);
    case AppendixBCurve::Helix:
      return std::abs(x * x + y * y - 1);
  }
  return 1e300;
}
}  // namespace

TEST(AppendixBCurves, PointsLieOnTheImplicitCurvesOfAppendixB) {
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve c = make_appendix_b_curve(which, {.points = 500});
    ASSERT_EQ(c.points.size(), 500u);
    for (const auto& p : c.points) EXPECT_LT(residual(which, p), 1e-9) << appendix_b_curve_name(which);
  }
}

TEST(AppendixBCurves, PaperPointCountsAndNames) {
  EXPECT_EQ(make_appendix_b_curve(AppendixBCurve::Folium).points.size(), 109u);
  EXPECT_EQ(make_appendix_b_curve(AppendixBCurve::Cubic).points.size(), 408u);
  EXPECT_EQ(make_appendix_b_curve(AppendixBCurve::Quartic).points.size(), 404u);
  EXPECT_EQ(make_appendix_b_curve(AppendixBCurve::Sextic).points.size(), 234u);
  for (AppendixBCurve which : all_appendix_b_curves()) EXPECT_EQ(appendix_b_curve_from_name(appendix_b_curve_name(which)), which);
  EXPECT_EQ(appendix_b_curve_from_name("ROSE"), AppendixBCurve::Rose);
  EXPECT_FALSE(appendix_b_curve_from_name("goblet").has_value());
}

TEST(AppendixBCurves, NoiseIsSeededAndDeterministic) {
  const auto a = make_appendix_b_curve(AppendixBCurve::Helix, {.points = 50, .noise = 0.1, .seed = 42});
  const auto b = make_appendix_b_curve(AppendixBCurve::Helix, {.points = 50, .noise = 0.1, .seed = 42});
  const auto c = make_appendix_b_curve(AppendixBCurve::Helix, {.points = 50, .noise = 0.1, .seed = 43});
  const auto clean = make_appendix_b_curve(AppendixBCurve::Helix, {.points = 50});
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
  double sum = 0;
  for (std::size_t k = 0; k < 50; ++k) sum += (a.points[k] - clean.points[k]).squaredNorm();
  EXPECT_NEAR(std::sqrt(sum / 150), 0.1, 0.03);  // sample standard deviation
  const auto planar = make_appendix_b_curve(AppendixBCurve::Rose, {.points = 50, .noise = 0.1});
  for (const auto& p : planar.points) EXPECT_EQ(p.z(), 0.0);
}

TEST(AppendixBCurves, BadCountsAreErrors) {
  EXPECT_THROW((void)make_appendix_b_curve(AppendixBCurve::Cubic, {.points = 1}), InvalidInput);
  EXPECT_THROW((void)make_appendix_b_curve(AppendixBCurve::Rose, {.points = 2}), InvalidInput);
  EXPECT_THROW((void)make_appendix_b_curve(AppendixBCurve::Rose, {.points = 10, .noise = -1}), InvalidInput);
}

TEST(AppendixBCurves, ModelFilesMatchTheGenerators) {
  // models/<name>_<n>.txt are sampled copies written by the curve_models bench program.
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const int n = paper_point_count(which);
    const std::string path =
        sculpt::test::models_dir() + "/" + appendix_b_curve_name(which) + "_" + std::to_string(n) + ".txt";
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    const DigitizedCurve stored = load_curve(path);
    EXPECT_EQ(stored.points, make_appendix_b_curve(which).points) << path;
  }
}
