#include "revolution/trees/profile_pieces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::revolution::detail;

namespace {

const kernel::Grid kGrid{};

/// ∫∫ 2 r dr dz over the region of a simple polygon (r, z), by Green's theorem:
/// ∫∫ r dA = 1/6 Σ (r_i + r_j)(r_i z_j − r_j z_i), orientation made positive.
double twice_r_moment(const std::vector<Eigen::Vector2d>& p) {
  double m = 0, area = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &a = p[i], &b = p[(i + 1) % p.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    m += (a.x() + b.x()) * cross / 6;
    area += cross / 2;
  }
  return 2 * (area < 0 ? -m : m);
}

/// The same from the pieces: Σ over slabs of ∫ (b^2 - a^2) dz, r linear in each slab.
double pieces_moment(const std::vector<ProfilePiece>& pieces) {
  auto squares = [](const RevolveSlab& s) { return (s.z1 - s.z0) * (s.r0 * s.r0 + s.r0 * s.r1 + s.r1 * s.r1) / 3; };
  double m = 0;
  for (const ProfilePiece& piece : pieces) {
    for (const RevolveSlab& s : piece.outer) m += squares(s);
    for (const RevolveSlab& s : piece.inner) m -= squares(s);
  }
  return m;
}

/// Each piece's slabs are contiguous, its inner radius is at most its outer one, and every slab
/// lies on its line (line ends are the polygon's points).
void check_pieces(const std::vector<ProfilePiece>& pieces) {
  for (const ProfilePiece& piece : pieces) {
    ASSERT_FALSE(piece.outer.empty());
    ASSERT_TRUE(piece.inner.empty() || piece.inner.size() == piece.outer.size());
    for (std::size_t k = 0; k < piece.outer.size(); ++k) {
      const RevolveSlab& b = piece.outer[k];
      EXPECT_LT(b.z0, b.z1);
      if (k > 0) {
        EXPECT_EQ(b.z0, piece.outer[k - 1].z1);
      }
      EXPECT_LE(b.line_z0, b.z0);
      EXPECT_GE(b.line_z1, b.z1);
      if (piece.inner.empty()) continue;
      const RevolveSlab& a = piece.inner[k];
      EXPECT_EQ(a.z0, b.z0);
      EXPECT_EQ(a.z1, b.z1);
      EXPECT_LE(a.r0, b.r0);
      EXPECT_LE(a.r1, b.r1);
    }
  }
}

std::vector<ProfilePiece> pieces_of(const std::vector<Eigen::Vector2d>& profile) {
  return monotone_pieces(closed_profile(profile, kGrid), kGrid);
}

}  // namespace

TEST(ProfilePieces, ClosedProfileIsSnappedCounterClockwiseWithoutTheClosingPoint) {
  const std::vector<Eigen::Vector2d> clockwise{{1, 0}, {1, 1}, {2, 1}, {2, 0}, {1, 0}};
  const auto p = closed_profile(clockwise, kGrid);
  ASSERT_EQ(p.size(), 4u);
  double area = 0;
  for (std::size_t i = 0; i < p.size(); ++i) area += p[i].x() * p[(i + 1) % 4].y() - p[(i + 1) % 4].x() * p[i].y();
  EXPECT_EQ(area, 2.0);  // twice the area, counter-clockwise
  const auto snapped = closed_profile({{1 + 1e-7, 0}, {2, 0}, {2, 1}, {1, 1}}, kGrid);
  EXPECT_EQ(snapped.front(), Eigen::Vector2d(1, 0));  // 1e-7 is below the grid step 2^-15
}

TEST(ProfilePieces, ASquareAwayFromTheAxisIsOnePieceWithAnInnerRadius) {
  const std::vector<Eigen::Vector2d> square{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const auto pieces = pieces_of(square);
  ASSERT_EQ(pieces.size(), 1u);
  ASSERT_EQ(pieces[0].outer.size(), 1u);
  ASSERT_EQ(pieces[0].inner.size(), 1u);
  EXPECT_EQ(pieces[0].outer[0].r0, 2.0);
  EXPECT_EQ(pieces[0].inner[0].r1, 1.0);
  check_pieces(pieces);
  EXPECT_DOUBLE_EQ(pieces_moment(pieces), twice_r_moment(square));
}

TEST(ProfilePieces, AHollowVaseWallIsOnePieceWhoseInnerRadiusLeavesTheAxis) {
  // Outer wall from the foot (r = 2) bulging to 2.5 and back to 2.25 at the lip, inner wall down
  // to a floor of thickness 0.25 on the axis.
  const std::vector<Eigen::Vector2d> vase{{0, 0}, {2, 0},      {2.5, 1.5},   {2.25, 3},
                                          {2, 3}, {2.25, 1.5}, {1.75, 0.25}, {0, 0.25}};
  const auto pieces = pieces_of(vase);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].outer.size(), 3u);  // levels 0, 0.25, 1.5, 3
  ASSERT_EQ(pieces[0].inner.size(), 3u);
  EXPECT_EQ(pieces[0].inner[0].r0, 0.0);  // the floor: inner radius 0 up to z = 0.25
  EXPECT_EQ(pieces[0].inner[0].r1, 0.0);
  check_pieces(pieces);
  EXPECT_NEAR(pieces_moment(pieces), twice_r_moment(vase), 1e-12);
}

TEST(ProfilePieces, AUpwardOpeningChannelSplitsIntoTwoPieces) {
  // A U: the bottom bar continues into the left prong, the right prong is a piece of its own.
  const std::vector<Eigen::Vector2d> u{{1, 0}, {3, 0}, {3, 2}, {2.5, 2}, {2.5, 0.5}, {1.5, 0.5}, {1.5, 2}, {1, 2}};
  const auto pieces = pieces_of(u);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_EQ(pieces[0].outer.size(), 2u);
  EXPECT_EQ(pieces[1].outer.size(), 1u);
  EXPECT_EQ(pieces[1].inner[0].r0, 2.5);
  check_pieces(pieces);
  EXPECT_NEAR(pieces_moment(pieces), twice_r_moment(u), 1e-12);
}

TEST(ProfilePieces, APieceAlongTheAxisHasNoInnerSolid) {
  // Along the axis from z = 3 down to 0, with a notch: at 1 < z < 2 two intervals.
  const std::vector<Eigen::Vector2d> notched{{0, 0}, {2, 0}, {2, 2}, {1, 2}, {1, 1}, {0.5, 1}, {0.5, 3}, {0, 3}};
  const auto pieces = pieces_of(notched);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_TRUE(pieces[0].inner.empty());  // [0, 2], then [0, 0.5] twice: on the axis throughout
  EXPECT_EQ(pieces[0].outer.size(), 3u);
  EXPECT_EQ(pieces[1].inner.size(), 1u);  // [1, 2] at 1 < z < 2
  check_pieces(pieces);
  EXPECT_NEAR(pieces_moment(pieces), twice_r_moment(notched), 1e-12);
}

TEST(ProfilePieces, EdgesCrossingSeveralSlabsKeepTheirLine) {
  // A long edge from (3, 0) to (1, 4) spans the slabs made by the notch's vertices on the left.
  const std::vector<Eigen::Vector2d> p{{0.5, 0}, {3, 0}, {1, 4}, {0.5, 4}, {0.5, 3}, {0.75, 2}, {0.5, 1}};
  const auto pieces = pieces_of(p);
  ASSERT_EQ(pieces.size(), 1u);
  ASSERT_EQ(pieces[0].outer.size(), 4u);
  for (const RevolveSlab& s : pieces[0].outer) {
    EXPECT_EQ(s.line_z0, 0.0);
    EXPECT_EQ(s.line_z1, 4.0);
    EXPECT_EQ(s.line_r0, 3.0);
    EXPECT_EQ(s.line_r1, 1.0);
    EXPECT_DOUBLE_EQ(s.r0, 3 - 0.5 * s.z0);
  }
  check_pieces(pieces);
  EXPECT_NEAR(pieces_moment(pieces), twice_r_moment(p), 1e-12);
}

TEST(ProfilePieces, ManyTeethMakeOnePiecePerTooth) {
  // A comb: a bar on the axis with 20 teeth above it; the first tooth continues the bar.
  std::vector<Eigen::Vector2d> comb{{0, 0}, {10, 0}, {10, 1}};
  for (int k = 19; k >= 0; --k) {
    comb.emplace_back(0.5 * k + 0.25, 1);
    comb.emplace_back(0.5 * k + 0.25, 2 + 0.125 * k);
    comb.emplace_back(0.5 * k, 2 + 0.125 * k);
    if (k > 0) comb.emplace_back(0.5 * k, 1);
  }
  const auto pieces = pieces_of(comb);
  EXPECT_EQ(pieces.size(), 20u);
  check_pieces(pieces);
  EXPECT_NEAR(pieces_moment(pieces), twice_r_moment(comb), 1e-9);
}

TEST(ProfilePieces, ReportsBadClosedProfiles) {
  auto message = [](const std::vector<Eigen::Vector2d>& p) -> std::string {
    try {
      (void)closed_profile(p, kGrid);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "no error";
  };
  // A bow tie: the edges 0-1 and 2-3 cross at (1.5, 0.5).
  const std::string bow = message({{1, 0}, {2, 1}, {2, 0}, {1, 1}});
  EXPECT_NE(bow.find("not a simple polygon"), std::string::npos) << bow;
  EXPECT_NE(bow.find("point 0 to point 1"), std::string::npos) << bow;
  EXPECT_NE(bow.find("point 2 to point 3"), std::string::npos) << bow;
  EXPECT_NE(bow.find("(1.5, 0.5)"), std::string::npos) << bow;
  // Touching itself at a vertex (two triangles sharing the point (2, 1)).
  const std::string touch = message({{1, 0}, {3, 0}, {2, 1}, {3, 2}, {1, 2}, {2, 1}});
  EXPECT_NE(touch.find("cross or touch"), std::string::npos) << touch;
  // Running back over its own edge.
  const std::string back = message({{1, 0}, {3, 0}, {2, 0}, {2, 1}});
  EXPECT_NE(back.find("runs back over itself at point 1"), std::string::npos) << back;
  const std::string negative = message({{1, 0}, {2, 0}, {-0.5, 1}});
  EXPECT_NE(negative.find("point 2 has r = -0.5"), std::string::npos) << negative;
  EXPECT_NE(message({{1, 0}, {2, 0}, {3, 0}}).find("encloses no area"), std::string::npos);
  EXPECT_NE(message({{1, 0}, {2, 0}, {1, 0}}).find("at least 3 distinct points"), std::string::npos);
  EXPECT_NE(message({{1, 0}, {2, NAN}, {1, 1}}).find("point 1 is not finite"), std::string::npos);
  // Distinct points that snap to one grid point leave too few.
  EXPECT_NE(message({{1, 0}, {1 + 1e-7, 0}, {1, 1e-7}}).find("at least 3 distinct points"), std::string::npos);
}
