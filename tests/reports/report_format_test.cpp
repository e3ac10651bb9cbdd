#include "reports/tree_report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "bsp/primitives.hpp"
#include "revolution/revolve.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::reports;

namespace {
std::vector<TreeReport> two_trees() {
  const Solid a = revolve({{1, 0}, {1, 1}}, polygon_path({{1, 0}, {0, 1}, {-1, 0}, {0, -1}}));
  const Solid b = revolve({{1, 0}, {1, 1}}, circular_path(16));
  return compare_trees({{"diamond \"cylinder\"", a}, {"16-gon cylinder", b}}, {.query_samples = 500});
}
}  // namespace

TEST(ReportFormat, CompareUsesOneSampleBox) {
  const auto r = two_trees();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_TRUE(r[0].depth.sample_box.isApprox(r[1].depth.sample_box));
  ASSERT_EQ(r[0].queries.size(), 3u);
  EXPECT_EQ(r[0].queries[0].shape, QueryShape::Point);
}

TEST(ReportFormat, TextHasOneColumnPerTreeAndTheHistograms) {
  const auto r = two_trees();
  const std::string text = report_text(r);
  EXPECT_NE(text.find("16-gon cylinder"), std::string::npos);
  EXPECT_NE(text.find("expected depth"), std::string::npos);
  EXPECT_NE(text.find("entropy bound"), std::string::npos);
  char expected[32];
  std::snprintf(expected, sizeof expected, "%.4f", r[0].depth.expected_depth);
  EXPECT_NE(text.find(expected), std::string::npos) << text;
  EXPECT_NE(text.find("depth histogram of diamond"), std::string::npos);
}

TEST(ReportFormat, JsonIsBalancedAndEscaped) {
  const std::string json = report_json(two_trees());
  EXPECT_EQ(std::count(json.begin(), json.end(), '{'), std::count(json.begin(), json.end(), '}'));
  EXPECT_EQ(std::count(json.begin(), json.end(), '['), std::count(json.begin(), json.end(), ']'));
  EXPECT_NE(json.find("\"name\": \"diamond \\\"cylinder\\\"\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"expected_depth\": 5.25"), std::string::npos) << json;
  EXPECT_NE(json.find("\"shape\": \"segment\""), std::string::npos);
}

TEST(ReportFormat, SvgDrawsTwoBarsPerDepthAndTree) {
  const auto r = two_trees();
  const std::string svg = depth_chart_svg(r);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  std::size_t bins = 0;
  for (const auto& t : r) bins += t.depth.histogram.size();
  std::size_t rects = 0;
  for (std::size_t at = svg.find("<rect"); at != std::string::npos; at = svg.find("<rect", at + 1)) ++rects;
  EXPECT_EQ(rects, 1 + 2 * bins + r.size());  // background, bars, legend swatches
  EXPECT_NE(svg.find("diamond &quot;cylinder&quot;"), std::string::npos);
}
