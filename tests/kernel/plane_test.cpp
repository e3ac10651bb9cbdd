#include "kernel/plane.hpp"

#include <gtest/gtest.h>

#include "base/errors.hpp"

namespace sculpt::kernel {
namespace {

TEST(Grid, SnapsToTheGridAndRejectsOutOfRange) {
  EXPECT_EQ(snap(1.0), 32768);
  EXPECT_EQ(snap(-0.5), -16384);
  EXPECT_EQ(snap(kMaxWorld), kMaxCoord);
  EXPECT_THROW(snap(kMaxWorld * 1.0001), RangeError);
  EXPECT_THROW(snap(std::nan("")), RangeError);
  try {
    snap(5000.0);
    FAIL();
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("[-1024, 1024]"), std::string::npos) << e.what();
  }
}

TEST(Plane, ThroughThreePointsIsNormalizedAndOriented) {
  const Plane p = plane_through({0, 0, 2}, {4, 0, 2}, {0, 4, 2});  // z = 2, normal +z
  EXPECT_EQ(p, (Plane{0, 0, 1, -2}));
  EXPECT_EQ(p.eval({5, 5, 3}), 1);
  EXPECT_THROW(plane_through({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), InvalidInput);
}

TEST(Plane, LargestGridPointsStayWithinTheBudget) {
  const std::int64_t m = kMaxCoord;
  const Plane p = plane_through({-m, -m, m}, {m, -m + 1, -m}, {-m + 1, m, -m + 3});
  EXPECT_LE(std::abs(p.a), std::int64_t(1) << kNormalBits);
  EXPECT_EQ(p.eval({-m, -m, m}), 0);
  EXPECT_EQ(p.eval({m, -m + 1, -m}), 0);
  EXPECT_THROW(make_plane(Int128(1) << 60, 1, 0, 0), RangeError);
}

// make_plane divides by the gcd of all four coefficients (64-bit binary gcd for the normal, 128-bit
// Euclid for the offset): checked against plain Euclid on 128 bits, with common factors, signs,
// zeros and offsets beyond 64 bits.
TEST(Plane, MakePlaneDividesByTheGreatestCommonDivisor) {
  auto euclid = [](Int128 x, Int128 y) {
    x = x < 0 ? -x : x, y = y < 0 ? -y : y;
    while (y != 0) {
      const Int128 t = x % y;
      x = y, y = t;
    }
    return x;
  };
  std::uint64_t state = 12345;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  for (int trial = 0; trial < 20000; ++trial) {
    const Int128 f = Int128(1 + next() % 1000) * ((trial % 3 == 0) ? 1 : Int128(1) << (next() % 12));
    auto coefficient = [&](int bits) {
      const Int128 v = Int128(next() >> (64 - bits)) * (next() % 2 ? 1 : -1);
      return next() % 7 == 0 ? Int128(0) : v;
    };
    Int128 a = coefficient(40), b = coefficient(40), c = coefficient(40);
    if (a == 0 && b == 0 && c == 0) c = 1;
    const Int128 d = coefficient(60) * (trial % 2 ? Int128(1) << 20 : Int128(1));
    const Plane p = make_plane(a * f, b * f, c * f, d * f);
    const Int128 g = euclid(euclid(a * f, b * f), euclid(c * f, d * f));
    ASSERT_EQ(Int128(p.a), a * f / g) << trial;
    ASSERT_EQ(Int128(p.b), b * f / g) << trial;
    ASSERT_EQ(Int128(p.c), c * f / g) << trial;
    ASSERT_EQ(p.d, d * f / g) << trial;
  }
}

TEST(Plane, FromNormalRoundsCloseToTheRequestedPlane) {
  const Plane p = plane_from_normal({1, 2, 3}, -1.5);
  // The point (0.5, 0.5, 0) (world) satisfies x + 2y + 3z - 1.5 = 0.
  const Eigen::Vector3d n = p.normal();
  const double value = (n.x() * 0.5 + n.y() * 0.5) / kGridStep + double(p.d);
  EXPECT_LT(std::fabs(value) / n.norm(), 1e-6);
}

}  // namespace
}  // namespace sculpt::kernel
