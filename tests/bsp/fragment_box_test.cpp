#include "bsp/solid.hpp"
#include "bsp/tree/fragment_boxes.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

namespace sculpt {
namespace {

using bsp::detail::FragmentBox;
using bsp::detail::FragmentBoxes;
using bsp::detail::fragment_box;

// fragment_box rounds the corner box outwards to float with its own steps on the bit pattern; the
// reference is float(x) stepped with std::nextafter where the rounding went inwards, as it was.
float reference_lo(double x) {
  float f = float(x);
  if (double(f) > x) f = std::nextafter(f, -HUGE_VALF);
  return f;
}
float reference_hi(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, HUGE_VALF);
  return f;
}

// One corner at (x, y, z) with error 0: its corner box is the point itself.
kernel::ConvexPolygon point(double x, double y, double z) {
  kernel::ConvexPolygon p;
  p.support = 0;
  p.corners.push_back({0, 0, 0, {x, y, z, 0.0}});
  return p;
}

TEST(FragmentBox, RoundsOutwardsLikeNextafter) {
  std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-38, -1e-38, 1e-40, -1e-40, 1e-45, -1e-45,
                                1e-46, -1e-46, 1e-50, -1e-50, 1e-300, -1e-300, double(FLT_MAX), -double(FLT_MAX),
                                double(FLT_MAX) * (1 + 1e-9), -double(FLT_MAX) * (1 + 1e-9), 3.5e38, -3.5e38, 1e39,
                                -1e39, 1e300, -1e300, double(FLT_MIN), -double(FLT_MIN),
                                double(std::nextafter(0.0f, 1.0f)), -double(std::nextafter(0.0f, 1.0f)),
                                double(std::nextafter(0.0f, 1.0f)) * 0.5, double(std::nextafter(0.0f, 1.0f)) * 1.5,
                                -double(std::nextafter(0.0f, 1.0f)) * 0.5, -double(std::nextafter(0.0f, 1.0f)) * 1.5};
  std::mt19937_64 rng(3);
  for (int i = 0; i < 200000; ++i) {  // every exponent a double may have, both signs, and floats exactly
    const double v = std::ldexp(std::uniform_real_distribution<double>(0.5, 1.0)(rng), int(rng() % 400) - 200);
    const double s = rng() % 2 ? v : -v;
    values.push_back(i % 5 == 0 ? double(float(s)) : s);
  }
  int stepped = 0;
  for (std::size_t i = 0; i + 2 < values.size(); ++i) {
    const double x = values[i], y = values[i + 1], z = values[i + 2];
    const kernel::ConvexPolygon p = point(x, y, z);
    const FragmentBox f = fragment_box(p);
    const kernel::CornerBox b = kernel::corner_box(p);  // x - 0 and x + 0 (-0 + 0 is +0)
    ASSERT_TRUE(f.valid);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(std::bit_cast<std::uint32_t>(f.lo[k]), std::bit_cast<std::uint32_t>(reference_lo(b.lo[k]))) << b.lo[k];
      ASSERT_EQ(std::bit_cast<std::uint32_t>(f.hi[k]), std::bit_cast<std::uint32_t>(reference_hi(b.hi[k]))) << b.hi[k];
      ASSERT_LE(double(f.lo[k]), b.lo[k]);  // and the box holds the point
      ASSERT_GE(double(f.hi[k]), b.hi[k]);
      stepped += double(float(b.lo[k])) != b.lo[k];
    }
  }
  EXPECT_GT(stepped, 300000);
  EXPECT_FALSE(fragment_box(kernel::ConvexPolygon{}).valid);
}

}  // namespace
}  // namespace sculpt
