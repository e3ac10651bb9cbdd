#include "splines/spline_io.hpp"

#include <gtest/gtest.h>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::splines;
using V = Eigen::Vector3d;

namespace {
SourceLocation error_location(const std::string& text) {
  try {
    (void)parse_spline(text, "s.txt");
  } catch (const InvalidInput& e) {
    return e.where();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}
}  // namespace

TEST(SplineText, RoundTripIsExact) {
  const BSpline open(3, {0, 0, 0, 0, 0.1 / 3, 1, 1, 1, 1}, {V(0, 0, 0), V(1, 2.5, 0), V(0.1, 1e-17, 0), V(3, 1, 0), V(4, 0, 0)}, false);
  const BSpline closed = BSpline::periodic(2, {V(0, 0, 1), V(1, 0, 2), V(1, 1, 3), V(0, 1, 4.25)});
  for (const BSpline& s : {open, closed}) {
    const BSpline r = parse_spline(format_spline(s));
    EXPECT_EQ(r.degree(), s.degree());
    EXPECT_EQ(r.closed(), s.closed());
    EXPECT_EQ(r.dimension(), s.dimension());
    EXPECT_EQ(r.knots(), s.knots());
    EXPECT_EQ(r.controls(), s.controls());
  }
}

TEST(SplineText, HandWrittenFormWithoutKnotsUsesUniformKnots) {
  const BSpline s = parse_spline("# a square\ndegree 2\nclosed true\ncontrols\n0 0\n1 0\n1 1\n0 1\n");
  EXPECT_TRUE(s.closed());
  EXPECT_EQ(s.dimension(), 2);
  EXPECT_EQ(s.knots(), (std::vector<double>{0, 1, 2, 3, 4}));
}

TEST(SplineText, ErrorsNameLineAndColumn) {
  EXPECT_EQ(error_location("degree 3\nbogus 1\ncontrols\n").line, 2);
  EXPECT_EQ(error_location("degree x\ncontrols\n").column, 8);
  EXPECT_EQ(error_location("degree 1\ncontrols\n0 0\n1 nan\n").line, 4);
  EXPECT_EQ(error_location("degree 1\ndimension 3\ncontrols\n0 0 0\n1 1\n").line, 5);
  EXPECT_EQ(error_location("degree 2\nknots 0 0 0 1 1\ncontrols\n0 0\n1 1\n2 0\n").line, 3);  // wrong knot count
  EXPECT_EQ(error_location("degree 0\ncontrols\n0 0\n1 1\n").line, 2);
  EXPECT_EQ(error_location("closed maybe\n").line, 1);
  EXPECT_THROW((void)parse_spline("controls\n0 0\n1 1\n"), InvalidInput);  // no degree
  EXPECT_THROW((void)parse_spline("degree 1\n"), InvalidInput);           // no controls
}

TEST(SplineText, MissingFileIsAnIoError) { EXPECT_THROW((void)load_spline("/nonexistent/x.spline"), IoError); }
