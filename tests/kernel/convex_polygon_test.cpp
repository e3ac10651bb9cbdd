#include "kernel/convex_polygon.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <boost/multiprecision/cpp_int.hpp>
#include <cstring>
#include <random>

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
  for (const auto& c : r.negative.corners) EXPECT_NE(orient(t[s], t[c.p], t[c.q], c.at(), t[cut]), Sign::Positive);
  for (const auto& c : r.positive.corners) EXPECT_NE(orient(t[s], t[c.p], t[c.q], c.at(), t[cut]), Sign::Negative);
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

// A corner keeps its approximation's error bound as a float no smaller than the double one
// (and at most one float step above it), and the coordinates as they were.
TEST(Corner, KeepsItsErrorBoundRoundedUp) {
  for (const double err : {0.0, 1e-300, 3.0e-12, 0.1, 1.0 / 3.0, 12345.678, 1e30}) {
    const Corner c(1, 2, 3, ApproxPoint{1.0 / 3.0, -2.5, 1e9 + 0.25, err});
    const ApproxPoint at = c.at();
    EXPECT_GE(at.err, err) << err;
    EXPECT_LE(at.err, err == 0 ? 0.0 : std::max(err * (1 + std::ldexp(1.0, -22)), 1.5e-45)) << err;
    EXPECT_EQ(at.x, 1.0 / 3.0);
    EXPECT_EQ(at.y, -2.5);
    EXPECT_EQ(at.z, 1e9 + 0.25);
  }
  EXPECT_LT(Corner(0, 0, 0, ApproxPoint{0, 0, 0, -1}).at().err, 0);  // no approximation stays so
  EXPECT_EQ(Corner(0, 0, 0, ApproxPoint{0, 0, 0, 1e300}).at().err, std::numeric_limits<double>::infinity());
  EXPECT_EQ(sizeof(Corner), 40u);
}

bool same_corners(const ConvexPolygon& a, const ConvexPolygon& b) {
  if (a.support != b.support || a.corners.size() != b.corners.size()) return false;
  for (std::size_t i = 0; i < a.corners.size(); ++i) {
    const Corner &x = a.corners[i], &y = b.corners[i];
    const ApproxPoint u = x.at(), v = y.at();
    if (x.edge != y.edge || x.p != y.p || x.q != y.q || std::memcmp(&u, &v, sizeof u) != 0) return false;
  }
  return true;
}

bool same_box(const CornerBox& a, const CornerBox& b) {
  return a.valid == b.valid && std::memcmp(a.lo, b.lo, sizeof a.lo) == 0 && std::memcmp(a.hi, b.hi, sizeof a.hi) == 0;
}

// A random plane through a random grid point, with small integer normals (many exact ties).
Plane random_plane(std::mt19937& rng) {
  std::uniform_int_distribution<int> n(-3, 3), p(-40, 40);
  std::int64_t a = 0, b = 0, c = 0;
  while (a == 0 && b == 0 && c == 0) a = n(rng), b = n(rng), c = n(rng);
  const Int128 d = -(Int128(a) * p(rng) + Int128(b) * p(rng) + Int128(c) * p(rng));
  return make_plane(a, b, c, d);
}

// clip_to_negative repeats split().negative corner for corner (labels and approximation bits)
// and keeps the box equal to corner_box; the other sides leave everything alone.
TEST(ConvexPolygon, ClipToNegativeEqualsTheNegativePartOfSplit) {
  std::mt19937 rng(11);
  int both = 0, ties = 0;
  for (int trial = 0; trial < 400; ++trial) {
    PlaneTable t;
    const std::int32_t s = t.add(random_plane(rng));
    ConvexPolygon poly = world_polygon(t, s);
    CornerBox box = corner_box(poly);
    for (int step = 0; step < 8 && !poly.empty(); ++step) {
      const std::int32_t cut = t.add(random_plane(rng));
      const std::int32_t opp = t.add(t[cut].opposite());
      const PolygonSplit ref = split(t, poly, cut, opp);
      ConvexPolygon out;
      const CornerBox before = box;
      const Side side = clip_to_negative(t, poly, out, box, cut);
      if (side == Side::Negative && ref.side != Side::Negative) ++ties;  // box decided: must be strict
      EXPECT_TRUE(side == ref.side || (side == Side::Negative && ref.side == Side::Negative));
      if (side != Side::Both) {
        EXPECT_TRUE(out.empty());
        EXPECT_TRUE(same_box(before, box));
        if (side == Side::Positive || side == Side::On) break;
        continue;
      }
      ++both;
      ASSERT_TRUE(same_corners(out, ref.negative));
      const CornerBox expect = corner_box(out);
      EXPECT_TRUE(same_box(expect, box));
      poly = std::move(out);
    }
  }
  EXPECT_EQ(ties, 0);
  EXPECT_GT(both, 500);
}

// Quick world corners: the exact vertex lies within the stated error of the approximation, and
// refresh_world_corners restores approximate_vertex's bits.
TEST(ConvexPolygon, QuickWorldCornersBoundTheExactVertex) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::int64_t> big(-(std::int64_t(1) << 52), std::int64_t(1) << 52);
  for (int trial = 0; trial < 500; ++trial) {
    PlaneTable t;
    const Plane p = trial % 2 ? random_plane(rng)
                              : make_plane(big(rng), big(rng), big(rng) | 1, Int128(big(rng)) << (trial % 27));
    const std::int32_t s = t.add(p);
    ConvexPolygon quick = world_polygon(t, s, {.quick_corners = true});
    const ConvexPolygon usual = world_polygon(t, s);
    for (const Corner& c : quick.corners) {
      const HomogeneousPoint h = exact_vertex(t[s], t[c.p], t[c.q]);
      // Exact rational comparison: |X / W - x| <= err for each coordinate.
      using boost::multiprecision::cpp_rational;
      const double xs[3] = {c.at().x, c.at().y, c.at().z};
      const Int256* X[3] = {&h.x, &h.y, &h.z};
      for (int i = 0; i < 3; ++i) {
        const cpp_rational exact(cpp_rational(boost::multiprecision::cpp_int(*X[i])) /
                                 cpp_rational(boost::multiprecision::cpp_int(h.w)));
        EXPECT_LE(abs(exact - cpp_rational(xs[i])), cpp_rational(c.at().err)) << "corner off its bound";
      }
      EXPECT_GE(c.at().err, 0);
    }
    refresh_world_corners(t, quick);
    EXPECT_TRUE(same_corners(quick, usual));
  }
}

}  // namespace
}  // namespace sculpt::kernel
