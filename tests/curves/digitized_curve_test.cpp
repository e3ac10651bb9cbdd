#include "curves/digitized_curve.hpp"
#include "support/scratch_path.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::curves;

namespace {

SourceLocation error_location(const std::string& text) {
  try {
    (void)parse_curve(text, "test.txt");
  } catch (const InvalidInput& e) {
    return e.where();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

}  // namespace

TEST(DigitizedCurve, ParsesTwoDimensionalPointsCommentsAndBlankLines) {
  const DigitizedCurve c = parse_curve("# header\n\n1 2\n  3.5\t-4e-1  # trailing\n\n5 6\n", "a");
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.dimension, 2);
  EXPECT_EQ(c.points[1], Eigen::Vector3d(3.5, -0.4, 0.0));
  EXPECT_FALSE(c.closed);
}

TEST(DigitizedCurve, ParsesThreeDimensionalPoints) {
  const DigitizedCurve c = parse_curve("1 2 3\n4 5 6\n");
  EXPECT_EQ(c.dimension, 3);
  EXPECT_EQ(c.points[1], Eigen::Vector3d(4, 5, 6));
}

TEST(DigitizedCurve, MalformedLineNamesFileLineAndColumn) {
  const SourceLocation where = error_location("0 0\n1 1\n2 x\n");
  EXPECT_EQ(where.file, "test.txt");
  EXPECT_EQ(where.line, 3);
  EXPECT_EQ(where.column, 3);
}

TEST(DigitizedCurve, NanAndInfinityAreErrorsWithLines) {
  EXPECT_EQ(error_location("0 0\n\n# c\nnan 1\n").line, 4);
  EXPECT_EQ(error_location("0 0\n1 inf\n").line, 2);
  EXPECT_EQ(error_location("0 0\n1 -Infinity\n").line, 2);
  EXPECT_EQ(error_location("0 0\n1 1e999\n").line, 2);
}

TEST(DigitizedCurve, WrongCoordinateCountsAreErrors) {
  EXPECT_EQ(error_location("1\n").line, 1);
  EXPECT_EQ(error_location("1 2\n1 2 3 4\n").line, 2);
  EXPECT_EQ(error_location("1 2\n1 2 3\n").line, 2);  // mixed 2D and 3D
  EXPECT_EQ(error_location("1 2 3\n4 5\n").line, 2);
}

TEST(DigitizedCurve, MessageStartsWithFileLineColumn) {
  try {
    (void)parse_curve("0 0\n1 y\n", "curve.txt");
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("curve.txt:2:3: error:", 0), 0u) << e.what();
  }
}

TEST(DigitizedCurve, EmptyTextGivesEmptyCurve) { EXPECT_TRUE(parse_curve("# nothing\n\n").points.empty()); }

TEST(DigitizedCurve, WriteAndReadBackIsExact) {
  DigitizedCurve c;
  c.dimension = 3;
  c.points = {{0.1, 1.0 / 3.0, -2e-300}, {1e300, -0.0, 5.0}, {std::nextafter(1.0, 2.0), 7.25, -1.0 / 7.0}};
  const std::string path = test::scratch_path("sculpt_curve_roundtrip.txt").string();
  save_curve(c, path);
  const DigitizedCurve back = load_curve(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.points.size(), c.points.size());
  for (std::size_t k = 0; k < c.points.size(); ++k) EXPECT_EQ(back.points[k], c.points[k]);
  EXPECT_EQ(back.dimension, 3);
}

TEST(DigitizedCurve, TwoDimensionalRoundTripKeepsDimension) {
  const DigitizedCurve c = parse_curve("0.5 0.25\n1 2\n");
  EXPECT_EQ(parse_curve(format_curve(c)).dimension, 2);
}

TEST(DigitizedCurve, MissingFileIsIoError) { EXPECT_THROW((void)load_curve("/nonexistent/dir/curve.txt"), IoError); }

TEST(DigitizedCurve, ClosedCurvePathRepeatsFirstPoint) {
  DigitizedCurve c = parse_curve("0 0\n1 0\n1 1\n");
  c.closed = true;
  const auto path = path_points(c);
  ASSERT_EQ(path.size(), 4u);
  EXPECT_EQ(path.back(), path.front());
}

TEST(DigitizedCurve, ValidateRejectsNonFiniteAndBadDimension) {
  DigitizedCurve c;
  c.points = {{0, 0, 0}, {std::nan(""), 0, 0}};
  EXPECT_THROW(validate(c), InvalidInput);
  c.points[1] = {1, 1, 1};
  c.dimension = 4;
  EXPECT_THROW(validate(c), InvalidInput);
}
