#include "kernel/convex_polygon.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace sculpt::kernel {
namespace {

double area(const ConvexPolygon& p) {
  const auto c = approximate_corners(p);
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < c.size(); ++i) s += c[i].cross(c[(i + 1) % c.size()]);
  return 0.5 * s.norm();
}

TEST(ConvexPolygon, WorldPolygonIsTheBoxSectionCounterClockwise) {
  PlaneTable t;
  const std::int32_t z = t.add({0, 0, 1, -5});
  const ConvexPolygon p = world_polygon(t, z);
  ASSERT_EQ(p.corners.size(), 4u);
  const double k = double(PlaneTable::kWorld);
  EXPECT_DOUBLE_EQ(area(p), 4 * k * k);
  // Counter-clockwise about +z: positive signed area in xy.
  const auto c = approximate_corners(p);
  double signed_area = 0;
  for (std::size_t i = 0; i < c.size(); ++i) signed_area += c[i].x() * c[(i + 1) % 4].y() - c[(i + 1) % 4].x() * c[i].y();
  EXPECT_GT(signed_area, 0);
  for (const auto& v : c) EXPECT_DOUBLE_EQ(v.z(), 5.0);
}

TEST(ConvexPolygon, SplitIsExactAndPartsAddUp) {
  PlaneTable t;
  const std::int32_t s = t.add({0, 0, 1, 0});
  const ConvexPolygon p = world_polygon(t, s);
  const std::int32_t cut = t.add({1, 1, 0, -7}), opp = t.add({-1, -1, 0, 7});
  const PolygonSplit r = split(t, p, cut, opp);
  ASSERT_EQ(r.side, Side::Both);
  EXPECT_NEAR(area(r.negative) + area(r.positive), area(p), 1e-6 * area(p));
  // Every corner of the parts lies on the right side (or on the cut), decided exactly.
  for (const auto& c : r.negative.corners)
    EXPECT_NE(orient(t[s], t[c.p], t[c.q], c.at, t[cut]), Sign::Positive);
  for (const auto& c : r.positive.corners)
    EXPECT_NE(orient(t[s], t[c.p], t[c.q], c.at, t[cut]), Sign::Negative);
  // Splitting again by the same plane puts each part on one side; by the support: On.
  EXPECT_EQ(classify(t, r.negative, cut), Side::Negative);
  EXPECT_EQ(classify(t, r.positive, cut), Side::Positive);
  EXPECT_EQ(classify(t, p, s), Side::On);
}

TEST(ConvexPolygon, CutThroughTwoCornersMakesTwoTriangles) {
  PlaneTable t;
  const std::int32_t s = t.add({0, 0, 1, 0});
  const ConvexPolygon p = world_polygon(t, s);
  const std::int32_t diag = t.add({1, -1, 0, 0}), opp = t.add({-1, 1, 0, 0});
  const PolygonSplit r = split(t, p, diag, opp);
  ASSERT_EQ(r.side, Side::Both);
  EXPECT_EQ(r.negative.corners.size(), 3u);
  EXPECT_EQ(r.positive.corners.size(), 3u);
  EXPECT_DOUBLE_EQ(area(r.negative), area(r.positive));
}

}  // namespace
}  // namespace sculpt::kernel
