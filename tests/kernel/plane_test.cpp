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

TEST(Plane, FromNormalRoundsCloseToTheRequestedPlane) {
  const Plane p = plane_from_normal({1, 2, 3}, -1.5);
  // The point (0.5, 0.5, 0) (world) satisfies x + 2y + 3z - 1.5 = 0.
  const Eigen::Vector3d n = p.normal();
  const double value = (n.x() * 0.5 + n.y() * 0.5) / kGridStep + double(p.d);
  EXPECT_LT(std::fabs(value) / n.norm(), 1e-6);
}

}  // namespace
}  // namespace sculpt::kernel
