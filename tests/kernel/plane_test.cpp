#include "kernel/plane.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

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

Int128 euclid(Int128 x, Int128 y) {
  x = x < 0 ? -x : x, y = y < 0 ? -y : y;
  while (y != 0) {
    const Int128 t = x % y;
    x = y, y = t;
  }
  return x;
}

// The plane a, b, c, d divided by the gcd of all four (plain Euclid): what make_plane must give.
void expect_reduced(const Plane& p, Int128 a, Int128 b, Int128 c, Int128 d, const char* what, int trial) {
  const Int128 g = euclid(euclid(a, b), euclid(c, d));
  ASSERT_EQ(Int128(p.a), a / g) << what << " " << trial;
  ASSERT_EQ(Int128(p.b), b / g) << what << " " << trial;
  ASSERT_EQ(Int128(p.c), c / g) << what << " " << trial;
  ASSERT_EQ(p.d, d / g) << what << " " << trial;
  ASSERT_EQ(p.d_nearest, double(d / g)) << what << " " << trial;
}

// The cases the gcd's shortcuts take: an operand that is a power of two (its odd part is 1, as in
// plane_from_normal's normals), operands of very different sizes (one division first), equal
// operands, zeros, the budget's largest normal components (2^53) and offsets beyond 64 bits.
TEST(Plane, MakePlaneShortcutsGiveTheGreatestCommonDivisor) {
  std::uint64_t state = 987654321;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  auto sign = [&](Int128 v) { return next() % 2 ? v : -v; };
  auto value = [&](int bits) -> Int128 {  // a random kind of value of at most `bits` bits
    const int k = int(next() % 8), shift = int(next() % std::uint64_t(bits));
    switch (k) {
      case 0: return 0;
      case 1: return sign(Int128(1) << shift);                                    // power of two
      case 2: return sign(Int128(next() >> (64 - std::min(bits, 12))));           // small
      case 3: return sign(Int128(1 + (next() >> (64 - std::min(bits, 20)))) << (shift / 2));
      default: return sign(Int128(next() >> (64 - std::min(bits, 63))) >> (next() % 40));
    }
  };
  int shortcuts = 0;
  for (int trial = 0; trial < 60000; ++trial) {
    const Int128 f = trial % 4 == 0 ? 1 : Int128(value(20) | 1) * (Int128(1) << (next() % 10));  // common factor
    const Int128 fa = f < 0 ? -f : f;
    const int nb = 53 - 64 + std::countl_zero(std::uint64_t(fa));  // bits left for the cofactors
    Int128 a = value(std::max(nb, 1)), b = value(std::max(nb, 1)), c = value(std::max(nb, 1));
    if (trial % 5 == 1) b = a;                                             // equal operands
    if (trial % 7 == 2) c = sign(Int128(1) << std::max(nb - 1, 0));        // power of two, largest
    if (a == 0 && b == 0 && c == 0) a = 1;
    Int128 d = value(60);
    if (trial % 3 == 0) d *= Int128(1) << 18;                              // beyond 64 bits
    a *= fa, b *= fa, c *= fa, d *= fa;
    if (euclid(euclid(a, b), c) > 1) ++shortcuts;
    expect_reduced(make_plane(a, b, c, d), a, b, c, d, "make_plane", trial);
    const Int128 gab = euclid(a, b);
    expect_reduced(make_plane(a, b, c, d, {.ab_gcd = std::uint64_t(gab)}), a, b, c, d, "ab_gcd", trial);
  }
  EXPECT_GT(shortcuts, 10000);  // the offset's gcd ran often
  // The budget's corners: normal components 2^53 and offsets 2^80 reduce or are rejected alike.
  const Int128 m = Int128(1) << kNormalBits, o = Int128(1) << kOffsetBits;
  expect_reduced(make_plane(m, m, m, o), m, m, m, o, "corner", 0);
  expect_reduced(make_plane(m, -m + 2, 0, -o, {.ab_gcd = 2}), m, -m + 2, 0, -o, "corner", 1);
  expect_reduced(make_plane(m, 3, -m, o - 1), m, 3, -m, o - 1, "corner", 2);
  EXPECT_THROW(make_plane(m + 1, 0, 1, 0), RangeError);
  EXPECT_THROW(make_plane(m + 1, 1, 0, 0, {.ab_gcd = 1}), RangeError);
  EXPECT_THROW(make_plane(1, 0, 0, o + 1, {.ab_gcd = 1}), RangeError);
  EXPECT_THROW(make_plane(0, 0, 0, 1), InvalidInput);
  EXPECT_THROW(make_plane(0, 0, 0, 1, {.ab_gcd = 0}), InvalidInput);
}

// The faces of a solid of revolution (primitives.cpp): a, b = dz (nx, ny) with gcd dz gcd(nx, ny),
// c = -dc, d = dc z - dz c0; the shortcuts (the xy gcd, the gcd of all four) give make_plane's
// planes on sphere-like and random rings.
TEST(Plane, KnownXyGcdGivesTheSamePlanes) {
  std::uint64_t state = 42;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  for (int trial = 0; trial < 20000; ++trial) {
    const double angle = double(next() >> 11) * 0x1p-53 * 6.283185307179586;
    const std::int64_t nx = std::llround(std::ldexp(std::cos(angle), 26)), ny = std::llround(std::ldexp(std::sin(angle), 26));
    const std::int64_t dz = 1 + std::int64_t(next() % (trial % 2 ? 2000 : (std::uint64_t(1) << 26)));
    const std::int64_t z = std::int64_t(next() % (std::uint64_t(1) << 26)) - (std::int64_t(1) << 25);
    const Int128 c0 = Int128(std::int64_t(next() >> 20)), c1 = trial % 5 == 0 ? c0 : Int128(std::int64_t(next() >> 20));
    const Int128 dc = c1 - c0;
    const Int128 a = Int128(dz) * nx, b = Int128(dz) * ny, c = -dc, d = dc * z - Int128(dz) * c0;
    const std::uint64_t gxy = std::uint64_t(euclid(nx, ny));
    const Plane general = make_plane(a, b, c, d);
    ASSERT_EQ(make_plane(a, b, c, d, {.ab_gcd = std::uint64_t(dz) * gxy}), general) << trial;
    expect_reduced(general, a, b, c, d, "face", trial);
    // The gcd of all four as primitives.cpp finds it: gcd(dc, dz gcd(gcd(nx, ny), c0)).
    const Int128 all = euclid(dc, Int128(dz) * euclid(Int128(gxy), c0));
    ASSERT_EQ(all, euclid(euclid(a, b), euclid(c, d))) << trial;
    ASSERT_EQ(make_plane(a, b, c, d, {.gcd = std::uint64_t(all)}), general) << trial;
  }
}

// plane_from_normal converts offsets below 2^62 through 64 bits: the same planes as the formula
// n s . g + offset s / step = 0 with s = 2^52 / max |n_i|, on both sides of that bound.
TEST(Plane, FromNormalGivesTheRoundedScaledPlane) {
  std::uint64_t state = 7;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  auto unit = [&] { return double(next() >> 11) * 0x1p-53 * 2 - 1; };
  for (int trial = 0; trial < 20000; ++trial) {
    Eigen::Vector3d n(unit(), unit(), trial % 3 == 0 ? 0.0 : unit());
    if (n.cwiseAbs().maxCoeff() == 0) n.x() = 1;
    const double s = std::ldexp(1.0, kNormalBits - 1) / n.cwiseAbs().maxCoeff();
    // Offsets from tiny to the range's end, some with d just below and above 2^62.
    double offset = unit() * std::ldexp(1.0, int(next() % 12));
    if (trial % 4 == 0) offset = std::ldexp(1.0, 62) * kGridStep / s * (1 + 0x1p-40 * double(int(next() % 5) - 2));
    const double d = offset * s / kGridStep;
    if (!(std::fabs(d) < std::ldexp(1.0, kOffsetBits - 1))) continue;
    const Plane p = plane_from_normal(n, offset);
    const Int128 a = Int128(std::nearbyint(n.x() * s)), b = Int128(std::nearbyint(n.y() * s)),
                 c = Int128(std::nearbyint(n.z() * s)), id = Int128(std::nearbyint(d));
    expect_reduced(p, a, b, c, id, "from_normal", trial);
  }
}

// Common factors with large odd parts (make_plane divides exact multiples by a product with the
// odd part's inverse modulo 2^64 and a shift): planes f (a, b, c, d) with odd f up to 2^45 times a
// power of two, both signs, offsets up to 63 bits, reduce to the plain-Euclid result.
TEST(Plane, MakePlaneDividesExactlyByLargeOddFactors) {
  std::uint64_t state = 2024;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  for (int trial = 0; trial < 20000; ++trial) {
    const int odd_bits = 1 + int(next() % 45), shift = int(next() % 6);
    const Int128 f = Int128((next() >> (64 - odd_bits)) | 1) << shift;
    const int room = 52 - odd_bits - shift;  // cofactor bits that keep the normal within 2^53
    auto cofactor = [&](int bits) {
      const Int128 v = bits <= 0 ? Int128(next() % 2) : Int128(next() >> (64 - bits));
      return next() % 2 ? v : -v;
    };
    Int128 a = cofactor(room), b = cofactor(room), c = cofactor(room);
    if (a == 0 && b == 0 && c == 0) a = 1;
    const Int128 d = cofactor(62 - odd_bits - shift);  // |d f| below 2^63: the 64-bit path
    expect_reduced(make_plane(a * f, b * f, c * f, d * f), a * f, b * f, c * f, d * f, "odd factor", trial);
  }
}

// scale_normal does plane_from_normal's normal work once: the rounded scaled normal, its scale and
// gcd (plain Euclid); plane_from_normal on it gives make_plane of the rounded coefficients.
TEST(Plane, FromScaledNormalGivesTheSamePlanesForEveryOffset) {
  std::uint64_t state = 99;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  auto unit = [&] { return double(next() >> 11) * 0x1p-53 * 2 - 1; };
  int tested = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    Eigen::Vector3d n(unit(), unit(), trial % 3 == 0 ? 0.0 : unit());
    if (trial % 7 == 0) n.y() = std::ldexp(n.y(), -40);  // components that round to small integers
    if (n.cwiseAbs().maxCoeff() == 0) n.x() = 1;
    const ScaledNormal sn = scale_normal(n);
    const double s = std::ldexp(1.0, kNormalBits - 1) / n.cwiseAbs().maxCoeff();
    ASSERT_EQ(sn.scale, s);
    ASSERT_EQ(sn.a, std::int64_t(std::nearbyint(n.x() * s)));
    ASSERT_EQ(sn.b, std::int64_t(std::nearbyint(n.y() * s)));
    ASSERT_EQ(sn.c, std::int64_t(std::nearbyint(n.z() * s)));
    ASSERT_EQ(Int128(sn.gcd), euclid(euclid(sn.a, sn.b), sn.c));
    for (int k = 0; k < 4; ++k) {
      const double offset = unit() * std::ldexp(1.0, int(next() % 12) - 4);
      if (!(std::fabs(offset * s / kGridStep) < std::ldexp(1.0, kOffsetBits - 1))) continue;  // out of range
      const Plane p = plane_from_scaled_normal(sn, offset);
      ASSERT_EQ(p, plane_from_normal(n, offset));
      ASSERT_EQ(p, make_plane(sn.a, sn.b, sn.c, Int128(std::nearbyint(offset * s / kGridStep))));
      ++tested;
    }
  }
  EXPECT_GT(tested, 15000);
  EXPECT_THROW(scale_normal({0, 0, 0}), InvalidInput);
  EXPECT_THROW(scale_normal({std::nan(""), 1, 0}), InvalidInput);
  EXPECT_THROW(scale_normal({HUGE_VAL, 1, 0}), InvalidInput);
  const ScaledNormal x = scale_normal({1, 0, 0});
  EXPECT_THROW(plane_from_scaled_normal(x, HUGE_VAL), InvalidInput);
  EXPECT_THROW(plane_from_scaled_normal(x, 1e30), RangeError);
  EXPECT_EQ(plane_from_scaled_normal(x, -0.5), make_plane(1, 0, 0, -16384));
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
