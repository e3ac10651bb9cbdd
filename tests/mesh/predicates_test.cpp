// The exact orientation predicates against an independent rational evaluation, on inputs built
// to be degenerate or nearly so, with coordinate magnitudes that exercise every exact tier.
#include "mesh/predicates.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <boost/multiprecision/cpp_int.hpp>
#include "support/rational_orientation.hpp"
#include <random>

namespace sculpt {
namespace {

using boost::multiprecision::cpp_rational;

using checks::rational_orient2d;
using checks::rational_orient3d;

TEST(Predicates, SignConventions) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {2, 2}), 0);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);  // d on the normal's side
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}), -1);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 7, 0}), 0);
}

TEST(Predicates, NearlyDegenerateInputsAgreeWithRationals) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> tier(0, 3);
  int zeros = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // Spread of magnitudes: small (int256), large (int512) or extreme (rationals).
    const int spread = std::array<int, 4>{0, 20, 100, 600}[tier(rng)];
    std::uniform_int_distribution<int> exponent(-spread / 2, spread / 2);
    auto coord = [&] { return std::ldexp(unit(rng), exponent(rng)); };
    const Eigen::Vector3d a(coord(), coord(), coord()), b(coord(), coord(), coord()), c(coord(), coord(), coord());
    // d on the plane abc up to rounding (often exactly on it when t is dyadic).
    const double s = std::ldexp(std::round(unit(rng) * 8), -3), t = std::ldexp(std::round(unit(rng) * 8), -3);
    Eigen::Vector3d d = a + s * (b - a) + t * (c - a);
    if (trial % 3 == 0) d = a + unit(rng) * (b - a) + unit(rng) * (c - a);
    if (trial % 5 == 0) d = b;  // repeated point: exactly zero
    const int got3 = orient3d(a, b, c, d);
    ASSERT_EQ(got3, rational_orient3d(a, b, c, d)) << a.transpose() << " | " << b.transpose() << " | " << c.transpose()
                                             << " | " << d.transpose();
    zeros += got3 == 0;
    const Eigen::Vector2d p = a.head<2>(), q = b.head<2>();
    const Eigen::Vector2d r = trial % 2 ? Eigen::Vector2d(p + s * (q - p)) : Eigen::Vector2d(p + unit(rng) * (q - p));
    ASSERT_EQ(orient2d(p, q, r), rational_orient2d(p, q, r));
  }
  EXPECT_GT(zeros, 200);  // the degenerate cases were really reached
}

// The plane part of orient3d's filter kept for many queries (Orient3dPlane): every sign it gives is
// the exact one, on random and nearly coplanar queries over magnitudes from tiny to huge, and it
// decides almost every query that is not nearly coplanar.
TEST(Predicates, KeptPlaneFilterGivesOnlyExactSigns) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-40, 40);
  int decided = 0, general = 0, general_decided = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int e = trial % 7 == 0 ? -520 : (trial % 11 == 0 ? 500 : exponent(rng));
    auto coord = [&] { return std::ldexp(unit(rng), e); };
    const Eigen::Vector3d a(coord(), coord(), coord()), b(coord(), coord(), coord()), c(coord(), coord(), coord());
    const Orient3dPlane plane = orient3d_plane(a, b, c);
    for (int q = 0; q < 8; ++q) {
      Eigen::Vector3d d(coord(), coord(), coord());
      const bool coplanar = q % 2 == 1;
      if (coplanar) d = a + unit(rng) * (b - a) + unit(rng) * (c - a);  // on the plane up to rounding
      if (q == 7) d = c;                                                  // exactly on it
      const int filtered = orient3d_filtered(plane, d);
      if (filtered == kUndecided) continue;
      ++decided;
      ASSERT_EQ(filtered, rational_orient3d(a, b, c, d)) << trial << " " << q;
      ASSERT_EQ(filtered, orient3d(a, b, c, d));
    }
    // A query far from a plane through well-spread corners (magnitudes without underflow).
    if (e > -100 && e < 100) {
      ++general;
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const Eigen::Vector3d far = a + n.normalized() * std::ldexp(1.0, e);
      general_decided += orient3d_filtered(plane, far) != kUndecided;
    }
  }
  EXPECT_GT(decided, 8000);
  EXPECT_GT(general_decided, general * 9 / 10);  // the filter is useful, not only safe
}

TEST(Predicates, ExtremeMagnitudes) {
  const double tiny = 4.9406564584124654e-324, huge = 1.7976931348623157e308;
  EXPECT_EQ(orient2d({0, 0}, {tiny, 0}, {0, tiny}), 1);
  EXPECT_EQ(orient2d({-huge, -huge}, {huge, huge}, {0, 0}), 0);
  EXPECT_EQ(orient2d({-huge, -huge}, {huge, huge}, {0, tiny}), 1);
  EXPECT_EQ(orient3d({0, 0, 0}, {huge, 0, 0}, {0, huge, 0}, {0, 0, tiny}), 1);
  EXPECT_EQ(orient3d({1, 1, 1}, {1 + 1e-16 * 4, 1, 1}, {1, 1 + 4e-16, 1}, {1, 1, 1 - tiny}), 0);  // 1 - tiny == 1
  // Tiny magnitudes whose products underflow (the filter then defers to the exact path).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    const double s = std::ldexp(1.0, -520 - trial % 40);
    const Eigen::Vector2d a(s * unit(rng), s * unit(rng)), b(s * unit(rng), s * unit(rng));
    const Eigen::Vector2d c = a + std::ldexp(unit(rng), -(trial % 30)) * (b - a);
    ASSERT_EQ(orient2d(a, b, c), rational_orient2d(a, b, c)) << trial;
    const Eigen::Vector3d p(s * unit(rng), s * unit(rng), s * unit(rng)), q(s * unit(rng), s * unit(rng), s * unit(rng));
    const Eigen::Vector3d r(s * unit(rng), s * unit(rng), s * unit(rng));
    const Eigen::Vector3d d = p + unit(rng) * (q - p) + unit(rng) * (r - p);
    ASSERT_EQ(orient3d(p, q, r, d), rational_orient3d(p, q, r, d)) << trial;
  }
}

// The second stage (exact differences evaluated as floating-point expansions): points on a small
// dyadic lattice near a common offset, so that every difference is exact, on and off coordinate
// planes, on and near a common plane or line, with offsets near the ends of the stage's range
// (2^-300 .. 2^300) and beyond it.
TEST(Predicates, ExactDifferencesAgreeWithRationals) {
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<int> small(-64, 64), pick(0, 5);
  int zeros = 0, nonzeros = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int e = std::array<int, 6>{-20, 0, 30, -290, 280, -330}[trial % 6];
    const double unit = std::ldexp(1.0, e);
    const Eigen::Vector3d base(std::ldexp(double(small(rng)), e + 6), std::ldexp(double(small(rng)), e + 6),
                               std::ldexp(double(small(rng)), e + 6));
    auto point = [&] { return Eigen::Vector3d(base + unit * Eigen::Vector3d(small(rng), small(rng), small(rng))); };
    Eigen::Vector3d a = point(), b = point(), c = point(), d = point();
    switch (pick(rng)) {
      case 0: a.z() = b.z() = c.z() = d.z() = base.z(); break;  // on a coordinate plane
      case 1: d = a + (b - a) * 2 - (c - a); break;                 // on the plane abc (exact lattice point)
      case 2: d = a + (b - a) + (c - a); d.x() = std::nextafter(d.x(), 1e300); break;  // one ulp off it
      case 3: c = a + (b - a) * 3; break;                           // a, b, c collinear
      default: break;
    }
    const int got3 = orient3d(a, b, c, d);
    ASSERT_EQ(got3, rational_orient3d(a, b, c, d)) << trial;
    (got3 == 0 ? zeros : nonzeros)++;
    ASSERT_EQ(orient2d(a.head<2>(), b.head<2>(), c.head<2>()), rational_orient2d(a.head<2>(), b.head<2>(), c.head<2>())) << trial;
    ASSERT_EQ(orient2d(a.head<2>(), b.head<2>(), d.head<2>()), rational_orient2d(a.head<2>(), b.head<2>(), d.head<2>())) << trial;
  }
  EXPECT_GT(zeros, 3000);
  EXPECT_GT(nonzeros, 3000);
}

}  // namespace
}  // namespace sculpt
