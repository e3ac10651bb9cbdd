// offset_polygon: round and miter joins, outwards and inwards, concave corners, offsets larger
// than a notch, an inward offset that splits the polygon or lets it vanish. Every expected area
// is a formula worked out by hand for the shape (and the loops' areas are recomputed here by the
// shoelace formula), never a value of the code under test.
#include "bsp/polygon_offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/extrude.hpp"

namespace sculpt {
namespace {

using Outline = std::vector<Eigen::Vector2d>;

double shoelace(const Outline& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d& u = p[i];
    const Eigen::Vector2d& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return a / 2;
}

/// The area of the regular n-gon inscribed in the circle of radius r: (n/2) r^2 sin(2 pi / n).
double ngon_area(int n, double r) { return 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n); }

// Step 2^-22: snapping the arcs' vertices moves areas by far less than the tolerances below.
const kernel::Grid kFineGrid = kernel::Grid::from_shift(22);
const Outline kPlate{{0, 0}, {2, 0}, {2, 2}, {0, 2}};  // a = 2
// The U: the 3 x 3 square without the 1 x 2 notch at the top middle; area 7, perimeter 16, six
// convex corners, two reflex corners (1, 1) and (2, 1).
const Outline kUShape{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};

/// The offset's single loop (checked counter-clockwise).
Outline single_loop(const Outline& p, double r, const PolygonOffsetOptions& options) {
  const auto loops = offset_polygon(p, r, options);
  EXPECT_EQ(loops.size(), 1u);
  if (loops.empty()) return {};
  EXPECT_GT(shoelace(loops.front()), 0);
  return loops.front();
}

TEST(PolygonOffset, SquareOutwardsWithRoundJoins) {
  // a^2 + 4 a r + the 32-gon of radius r that the four quarter arcs (8 edges each) make up.
  const double a = 2, r = 0.5;
  for (const Outline& p : {kPlate, Outline(kPlate.rbegin(), kPlate.rend())}) {
    const Outline loop = single_loop(p, r, {.join = OffsetJoin::Round, .segments = 32, .grid = kFineGrid});
    EXPECT_NEAR(shoelace(loop), a * a + 4 * a * r + ngon_area(32, r), 1e-5);
    EXPECT_EQ(loop.size(), 4u * 9u);  // each corner: 9 arc vertices, the flat sides between them
  }
  // 12 edges a turn: 3 a corner.
  const Outline coarse = single_loop(kPlate, r, {.segments = 12, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(coarse), a * a + 4 * a * r + ngon_area(12, r), 1e-5);
}

TEST(PolygonOffset, SquareOutwardsWithMiterJoins) {
  const Outline loop = single_loop(kPlate, 0.5, {.join = OffsetJoin::Miter, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(loop), 3.0 * 3.0, 1e-5);  // (a + 2r)^2: the corners reach r sqrt 2 < 2 r
  EXPECT_EQ(loop.size(), 4u);
  // A miter limit of 1.2 < sqrt 2 cuts each corner across its diagonal at 1.2 r from the vertex:
  // the cut-off triangle has height (sqrt 2 - 1.2) r and base twice that.
  const double r = 0.5, h = (std::sqrt(2.0) - 1.2) * r;
  const Outline cut = single_loop(kPlate, r, {.join = OffsetJoin::Miter, .miter_limit = 1.2, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(cut), 9.0 - 4 * h * h, 1e-5);
  EXPECT_EQ(cut.size(), 8u);
}

TEST(PolygonOffset, SquareInwards) {
  for (OffsetJoin join : {OffsetJoin::Round, OffsetJoin::Miter}) {
    const Outline loop = single_loop(kPlate, -0.5, {.join = join, .grid = kFineGrid});
    EXPECT_NEAR(shoelace(loop), 1.0, 1e-6);  // (a - 2r)^2
    EXPECT_EQ(loop.size(), 4u);
  }
}

TEST(PolygonOffset, ConcaveCornersOutwards) {
  const double r = 0.25;  // less than half the notch: the notch narrows to 0.5
  // Round: A + P r + the six quarter arcs - the r x r square counted twice at each reflex corner.
  const Outline round = single_loop(kUShape, r, {.grid = kFineGrid});
  EXPECT_NEAR(shoelace(round), 7 + 16 * r + 6 * ngon_area(32, r) / 4 - 2 * r * r, 1e-5);
  // Miter: the square [-r, 3 + r]^2 without the narrowed notch [1 + r, 2 - r] x [1 + r, 3 + r].
  const Outline miter = single_loop(kUShape, r, {.join = OffsetJoin::Miter, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(miter), 3.5 * 3.5 - 0.5 * 2, 1e-5);
  EXPECT_EQ(miter.size(), 8u);
}

TEST(PolygonOffset, AnOffsetLargerThanTheNotchFillsIt) {
  // r = 0.75 > 1/2: the prongs grow into each other, the notch is gone: the square [-r, 3 + r]^2.
  const Outline miter = single_loop(kUShape, 0.75, {.join = OffsetJoin::Miter, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(miter), 4.5 * 4.5, 1e-5);
  EXPECT_EQ(miter.size(), 4u);
  // Round: no hole either; the notch is filled, the outline has no reflex corner left down there.
  const auto loops = offset_polygon(kUShape, 0.75, {.grid = kFineGrid});
  ASSERT_EQ(loops.size(), 1u);
  for (const Eigen::Vector2d& p : loops.front())
    EXPECT_FALSE(p.y() < 3.0 && p.x() > 0.5 && p.x() < 2.5) << p.transpose();
}

TEST(PolygonOffset, ConcaveCornersInwards) {
  const double r = 0.25;
  // Miter: [r, 3 - r]^2 without the widened notch [1 - r, 2 + r] x [1 - r, 3 - r].
  const Outline miter = single_loop(kUShape, -r, {.join = OffsetJoin::Miter, .grid = kFineGrid});
  EXPECT_NEAR(shoelace(miter), 2.5 * 2.5 - 1.5 * 2, 1e-5);
  // Round: the two reflex corners cut by quarter arcs instead of r x r squares.
  const Outline round = single_loop(kUShape, -r, {.grid = kFineGrid});
  EXPECT_NEAR(shoelace(round), 2.5 * 2.5 - 1.5 * 2 + 2 * (r * r - ngon_area(32, r) / 4), 1e-5);
}

TEST(PolygonOffset, InwardsTheBarOfADumbbellVanishes) {
  // Two 2 x 2 squares joined by a bar 0.5 wide: inwards by 0.4 with miter joins leaves two
  // 1.2 x 1.2 squares (the mitered corners at the bar's four reflex corners cover its mouths).
  const Outline dumbbell{{0, 0}, {2, 0}, {2, 0.75}, {3, 0.75}, {3, 0}, {5, 0},
                         {5, 2}, {3, 2}, {3, 1.25}, {2, 1.25}, {2, 2}, {0, 2}};
  const auto loops = offset_polygon(dumbbell, -0.4, {.join = OffsetJoin::Miter, .grid = kFineGrid});
  ASSERT_EQ(loops.size(), 2u);
  for (const Outline& l : loops) EXPECT_NEAR(shoelace(l), 1.2 * 1.2, 1e-5);
  // Round joins cut the mouths by arcs around those corners, which meet only 0.31 from x = 2
  // (circles of radius 0.4 whose centres are 0.5 apart): each square keeps a bump towards the
  // bar, less than 0.0878 x 0.5 (the part of the mouth outside both circles).
  const auto round = offset_polygon(dumbbell, -0.4, {.grid = kFineGrid});
  ASSERT_EQ(round.size(), 2u);
  for (const Outline& l : round) {
    EXPECT_GT(shoelace(l), 1.2 * 1.2 + 1e-3);
    EXPECT_LT(shoelace(l), 1.2 * 1.2 + (0.4 - std::sqrt(0.4 * 0.4 - 0.25 * 0.25)) * 0.5 + 2e-3);
  }
  // Outwards by 0.4 the hollows above and below the bar narrow to 0.2 but stay open: one loop.
  EXPECT_EQ(offset_polygon(dumbbell, 0.4, {.grid = kFineGrid}).size(), 1u);
}

TEST(PolygonOffset, AnInwardOffsetCanVanish) {
  EXPECT_TRUE(offset_polygon(kPlate, -1.0).empty());  // down to the centre point
  EXPECT_TRUE(offset_polygon(kPlate, -1.5).empty());
  EXPECT_TRUE(offset_polygon(kUShape, -0.6, {.join = OffsetJoin::Miter}).empty());  // every arm is 1 wide
}

TEST(PolygonOffset, ExtrudedOffsetHasTheOffsetsAreaTimesHeight) {
  const Outline loop = single_loop(kUShape, 0.25, {.grid = kFineGrid});
  EXPECT_NEAR(volume(extrude(loop, 0, 2, kFineGrid)),
              2 * (7 + 16 * 0.25 + 6 * ngon_area(32, 0.25) / 4 - 2 * 0.25 * 0.25), 1e-4);
}

TEST(PolygonOffset, BadInputIsRefused) {
  EXPECT_THROW((void)offset_polygon({{0, 0}, {1, 0}}, 1), InvalidInput);
  EXPECT_THROW((void)offset_polygon({{0, 0}, {1, 0}, {2, 0}}, 1), InvalidInput);
  EXPECT_THROW((void)offset_polygon(kPlate, NAN), InvalidInput);
  EXPECT_THROW((void)offset_polygon(kPlate, 1, {.segments = 2}), InvalidInput);
  EXPECT_THROW((void)offset_polygon(kPlate, 1, {.miter_limit = 0.5}), InvalidInput);
  try {
    (void)offset_polygon({{0, 0}, {2, 2}, {2, 0}, {0, 1}}, 0.1);  // crosses itself
    FAIL() << "no error";
  } catch (const GeometryError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("offset:", 0), 0u) << e.what();
  }
  // Distance 0: the polygon itself, counter-clockwise.
  const auto same = offset_polygon(Outline(kPlate.rbegin(), kPlate.rend()), 0);
  ASSERT_EQ(same.size(), 1u);
  EXPECT_DOUBLE_EQ(shoelace(same.front()), 4.0);
}

}  // namespace
}  // namespace sculpt
