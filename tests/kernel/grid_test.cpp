// kernel::Grid, the world <-> grid mapping (docs/kernel.md, "World range"): powers of two only,
// exact conversions, the range 2^25 steps, and RangeError messages that name a grid that fits.
#include "kernel/grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::kernel {
namespace {

std::string range_message(const Grid& grid, double v) {
  try {
    (void)grid.snap(v);
  } catch (const RangeError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Grid, DefaultIsTheFixedGridOfBefore) {
  const Grid g;
  EXPECT_EQ(g.shift(), 15);
  EXPECT_EQ(g.step(), kGridStep);
  EXPECT_EQ(g.max_world(), 1024.0);
  EXPECT_EQ(g.unit(), 1.0);
  EXPECT_EQ(g.name(), "2^-15");
  EXPECT_EQ(g.range_text(), "[-1024, 1024] world units (grid step 2^-15)");
  EXPECT_EQ(Grid::from_step(std::ldexp(1.0, -15)), g);
  EXPECT_EQ(Grid::from_shift(15), g);
}

TEST(Grid, StepsArePowersOfTwoInTheDocumentedRange) {
  EXPECT_EQ(Grid::from_step(0.125).shift(), 3);
  EXPECT_EQ(Grid::from_step(4.0).shift(), -2);
  EXPECT_EQ(Grid::from_step(std::ldexp(1.0, -Grid::kMaxShift)).shift(), Grid::kMaxShift);
  EXPECT_EQ(Grid::from_step(std::ldexp(1.0, -Grid::kMinShift)).shift(), Grid::kMinShift);
  EXPECT_THROW((void)Grid::from_step(std::ldexp(1.0, -Grid::kMaxShift - 1)), InvalidInput);
  EXPECT_THROW((void)Grid::from_step(std::ldexp(1.0, -Grid::kMinShift + 1)), InvalidInput);
  EXPECT_THROW((void)Grid::from_step(0.0), InvalidInput);
  EXPECT_THROW((void)Grid::from_step(-0.5), InvalidInput);
  EXPECT_THROW((void)Grid::from_step(std::nan("")), InvalidInput);
  try {
    (void)Grid::from_step(0.001);
    FAIL();
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("the nearest is 2^-10"), std::string::npos) << e.what();
  }
}

TEST(Grid, RangeIsTwoToThe25Steps) {
  for (int k : {-32, -3, 0, 13, 15, 20, 40, 64}) {
    const Grid g = Grid::from_shift(k);
    EXPECT_EQ(g.max_world(), std::ldexp(1.0, 25 - k));
    EXPECT_EQ(g.snap(g.max_world()), kMaxCoord);
    EXPECT_EQ(g.snap(-g.max_world()), -kMaxCoord);
    EXPECT_THROW((void)g.snap(std::nextafter(g.max_world(), INFINITY)), RangeError);
    EXPECT_EQ(g.unit(), std::ldexp(1.0, 15 - k));
  }
}

TEST(Grid, ConversionsAreExactScalings) {
  const Grid g = Grid::from_shift(13);
  EXPECT_EQ(g.snap(3000.0), 3000 * 8192);
  EXPECT_EQ(g.snap(-1.0 / 16384), -1);  // half a step: away from zero, as std::llround
  EXPECT_EQ(g.snap(1.0 / 16384), 1);
  EXPECT_EQ(g.to_world(GridPoint{8192, -3, 1}), Eigen::Vector3d(1.0, -3.0 / 8192, 1.0 / 8192));
  // Snapping at shift k is snapping the value scaled by 2^(15 - k) at the default grid.
  for (double v : {0.1, -7.3, 123.456, 1000.0 / 3})
    EXPECT_EQ(g.snap(4 * v), Grid{}.snap(v)) << v;
}

TEST(Grid, FittingIsTheFinestGridThatHoldsTheValue) {
  EXPECT_EQ(Grid::fitting(3000.0)->shift(), 13);   // 2^12 = 4096 >= 3000 > 2048
  EXPECT_EQ(Grid::fitting(4096.0)->shift(), 13);   // exactly the range
  EXPECT_EQ(Grid::fitting(4097.0)->shift(), 12);
  EXPECT_EQ(Grid::fitting(1024.0)->shift(), 15);
  EXPECT_EQ(Grid::fitting(0.5)->shift(), 26);
  EXPECT_EQ(Grid::fitting(-5000.0)->shift(), 12);
  EXPECT_FALSE(Grid::fitting(1e300).has_value());
  EXPECT_FALSE(Grid::fitting(INFINITY).has_value());
  for (double v : {1e-9, 0.3, 1.0, 777.0, 1e6, 3e15}) {
    const Grid g = *Grid::fitting(v);
    EXPECT_LE(v, g.max_world()) << v;
    if (g.shift() < Grid::kMaxShift) {
      EXPECT_GT(v, Grid::from_shift(g.shift() + 1).max_world()) << v;
    }
  }
}

TEST(Grid, OutOfRangeMessageNamesAGridThatFits) {
  const std::string m = range_message(Grid{}, 3000.0);
  EXPECT_NE(m.find("coordinate 3000 is outside the exact kernel's range [-1024, 1024] world units (grid step 2^-15)"),
            std::string::npos) << m;
  EXPECT_NE(m.find("a grid of step 2^-13 would fit coordinates up to 4096"), std::string::npos) << m;
  const std::string fine = range_message(Grid::from_shift(20), 40.0);  // range 32 at step 2^-20
  EXPECT_NE(fine.find("a grid of step 2^-19 would fit coordinates up to 64"), std::string::npos) << fine;
  EXPECT_EQ(range_message(Grid{}, std::nan("")).find("would fit"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::kernel
