// certainly_reaches (bsp/local/cell_reach.hpp) against the exact clip: whenever it says a polygon
// reaches a cell, clipping the polygon exactly to the cell's six walls leaves a part; and it
// decides most of the polygons that do reach (it is the cell merge's filter before that clip).
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <utility>

#include "bsp/local/cell_reach.hpp"
#include "bsp/tree/triangle_fragment.hpp"
#include "kernel/plane.hpp"

namespace sculpt {
namespace {

using bsp::detail::CellBounds;
using bsp::detail::certainly_reaches;
using kernel::ConvexPolygon;
using kernel::GridPoint;
using kernel::Side;

// The polygon clipped exactly to the closed cell (walls 2 x_k <= hi[k], 2 x_k >= lo[k]): true if
// a part of positive area is left.
bool exact_reach(kernel::PlaneTable& planes, const ConvexPolygon& poly, const CellBounds& c) {
  ConvexPolygon in = poly, out;
  kernel::CornerBox box = kernel::corner_box(in);
  for (int k = 0; k < 3; ++k)
    for (int upper = 0; upper < 2; ++upper) {
      std::int64_t n[3] = {0, 0, 0};
      n[k] = upper ? 2 : -2;
      const std::int32_t wall =
          planes.add(kernel::Plane(n[0], n[1], n[2], upper ? -kernel::Int128(c.hi[k]) : kernel::Int128(c.lo[k])));
      const Side s = kernel::clip_to_negative(planes, in, out, box, wall);
      if (s == Side::Positive || s == Side::On) return false;
      if (s == Side::Both) std::swap(in, out);
    }
  return !in.empty();
}

struct Case {
  ConvexPolygon poly;
  CellBounds cell;
};

// A cell with odd bounds in about [-20, 50]^3 and a triangle of grid points (not collinear):
// anywhere in [-40, 40]^3, or with `near`, within two steps of the cell.
Case random_case(std::mt19937& rng, kernel::PlaneTable& planes, bool near) {
  std::uniform_int_distribution<int> half(-20, 20), size(1, 30);
  Case c;
  for (int k = 0; k < 3; ++k) {
    c.cell.lo[k] = 2 * half(rng) + 1;
    c.cell.hi[k] = c.cell.lo[k] + 2 * size(rng);
  }
  auto coord = [&](int k) {
    const int lo = near ? int((c.cell.lo[k] - 1) / 2) - 2 : -40, hi = near ? int((c.cell.hi[k] + 1) / 2) + 2 : 40;
    return std::uniform_int_distribution<int>(lo, hi)(rng);
  };
  GridPoint v[3];
  for (;;) {
    for (GridPoint& p : v) p = {coord(0), coord(1), coord(2)};
    const std::int64_t ax = v[1].x - v[0].x, ay = v[1].y - v[0].y, az = v[1].z - v[0].z;
    const std::int64_t bx = v[2].x - v[0].x, by = v[2].y - v[0].y, bz = v[2].z - v[0].z;
    if (ay * bz - az * by != 0 || az * bx - ax * bz != 0 || ax * by - ay * bx != 0) break;
  }
  c.poly = bsp::detail::triangle_polygon(planes, planes.add(kernel::plane_through(v[0], v[1], v[2])), v);
  return c;
}

TEST(CellReach, SaysReachOnlyWhereTheExactClipLeavesAPartAndDecidesMostOfThem) {
  std::mt19937 rng(7);
  kernel::PlaneTable planes;
  int reach = 0, decided = 0, inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Case c = random_case(rng, planes, i % 2 == 0);
    const bool exact = exact_reach(planes, c.poly, c.cell);
    const bool quick = certainly_reaches(c.poly, c.cell);
    if (quick) {
      ASSERT_TRUE(exact) << "case " << i;
    }
    reach += exact;
    decided += quick;
    bool all_in = true;
    for (const auto& corner : c.poly.corners) {
      const kernel::ApproxPoint a = corner.at();
      const double x[3] = {a.x, a.y, a.z};
      for (int k = 0; k < 3; ++k) all_in = all_in && 2 * x[k] > double(c.cell.lo[k]) && 2 * x[k] < double(c.cell.hi[k]);
    }
    if (all_in) {
      ++inside;
      EXPECT_TRUE(quick) << "case " << i << ": every corner inside";
    }
  }
  // Both kinds occur, and the filter leaves few of the reaching ones to the exact clip.
  EXPECT_GT(inside, 100);
  EXPECT_GT(reach - inside, 1000);
  EXPECT_GT(decided, reach * 95 / 100) << decided << " of " << reach;
}

TEST(CellReach, ATriangleAcrossACellCornerWithoutMeetingItIsLeftToTheExactClip) {
  // The triangle's box covers the cell [0.5, 1.5]^2 x [-0.5, 0.5], but the triangle passes
  // beside the corner (1.5, 1.5): x + y >= 4 > 3 everywhere on it.
  kernel::PlaneTable planes;
  const GridPoint v[3] = {{0, 4, 0}, {4, 0, 0}, {4, 4, 0}};
  const ConvexPolygon poly =
      bsp::detail::triangle_polygon(planes, planes.add(kernel::plane_through(v[0], v[1], v[2])), v);
  const CellBounds cell{{1, 1, -1}, {3, 3, 1}};
  EXPECT_FALSE(exact_reach(planes, poly, cell));
  EXPECT_FALSE(certainly_reaches(poly, cell));
  // Moved so that it covers the corner: both say it reaches.
  const GridPoint w[3] = {{0, 2, 0}, {2, 0, 0}, {4, 4, 0}};
  const ConvexPolygon across =
      bsp::detail::triangle_polygon(planes, planes.add(kernel::plane_through(w[0], w[1], w[2])), w);
  EXPECT_TRUE(exact_reach(planes, across, cell));
  EXPECT_TRUE(certainly_reaches(across, cell));
}

}  // namespace
}  // namespace sculpt
