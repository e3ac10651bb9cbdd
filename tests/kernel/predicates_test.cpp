#include "kernel/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <boost/multiprecision/cpp_int.hpp>
#include <random>

#include "kernel/wide_int.hpp"

namespace sculpt::kernel {
namespace {

Int256 big(Int128 v) {
  Int256 r = Int256(std::int64_t(v >> 64));
  r <<= 64;
  r += Int256(std::uint64_t(v));
  return r;
}

// Reference orientation with Boost's cpp_int straight from Cramer's rule.
int reference_orient(const Plane& p, const Plane& q, const Plane& r, const Plane& s) {
  const HomogeneousPoint h = exact_vertex(p, q, r);
  const Int256 t = h.x * s.a + h.y * s.b + h.z * s.c + h.w * big(s.d);
  return t.sign() * h.w.sign();
}

TEST(Wide, MatchesBoostOnRandomProducts) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Int128 a = (Int128(std::int64_t(rng())) << 20) ^ Int128(rng() >> 3);
    const Int128 b = Int128(std::int64_t(rng()) >> (rng() % 40));
    const Int128 c = (Int128(std::int64_t(rng())) << 15) + Int128(rng() % 1000);
    const Wide w = Wide::mul(a, b) * c - Wide::mul(c, a);
    const Int256 ref = big(a) * big(b) * big(c) - big(c) * big(a);
    EXPECT_EQ(w.sign(), ref.sign());
    // Compare all bits through the low and high limbs.
    Int256 low = ref & Int256(std::uint64_t(-1));
    EXPECT_EQ(w.limb[0], low.convert_to<std::uint64_t>());
  }
}

// Sums of up to six signed products of 126-bit values, including exact cancellation to zero.
TEST(ProductSum256, SignMatchesBoostOnRandomSums) {
  std::mt19937_64 rng(23);
  auto value = [&] {
    const Int128 v = (Int128(std::int64_t(rng())) << 62) ^ Int128(rng() >> 2);
    return v >> (rng() % 100);
  };
  for (int i = 0; i < 5000; ++i) {
    ProductSum256 sum;
    Int256 ref = 0;
    const int terms = 1 + int(rng() % 6);
    for (int t = 0; t < terms; ++t) {
      const Int128 a = value(), b = value();
      const bool subtract = rng() & 1;
      sum.add_product(a, b, subtract);
      ref += subtract ? Int256(-(big(a) * big(b))) : Int256(big(a) * big(b));
    }
    if (i % 5 == 0) {  // cancel to exactly zero: subtract the same products again
      ProductSum256 zero;
      const Int128 a = value(), b = value();
      zero.add_product(a, b, false);
      zero.add_product(b, a, true);
      EXPECT_TRUE(zero.zero());
      EXPECT_EQ(zero.sign(), 0);
    }
    EXPECT_EQ(sum.sign(), ref.sign());
    EXPECT_EQ(sum.zero(), ref == 0);
  }
}

// Random planes through random grid points: the filtered orientation equals the reference.
TEST(Orient, FilterAndExactPathAgreeWithBoostReference) {
  std::mt19937_64 rng(11);
  auto point = [&](std::int64_t range) {
    std::uniform_int_distribution<std::int64_t> d(-range, range);
    return GridPoint{d(rng), d(rng), d(rng)};
  };
  predicate_counters() = {};
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::int64_t range = i % 2 ? kMaxCoord : 100;
    const GridPoint v = point(range);  // a common vertex of p, q, r
    Plane pl[3];
    for (auto& p : pl) {
      GridPoint a = point(range), b = point(range);
      try {
        p = plane_through(v, a, b);
      } catch (...) {
        p = plane_through(v, {v.x + 1, v.y, v.z}, {v.x, v.y + 1, v.z});
      }
    }
    if (!independent(pl[0], pl[1], pl[2])) continue;
    // s through the vertex (degenerate) half of the time, else through random points.
    const Plane s = i % 3 == 0 ? plane_through(v, point(range), point(range)) : plane_through(point(range), point(range), point(range));
    const ApproxPoint at = approximate_vertex(pl[0], pl[1], pl[2]);
    ASSERT_GE(at.err, 0);
    EXPECT_EQ(int(orient(pl[0], pl[1], pl[2], at, s)), reference_orient(pl[0], pl[1], pl[2], s));
    if (i % 3 == 0) {
      EXPECT_EQ(orient(pl[0], pl[1], pl[2], at, s), Sign::Zero);
    }
    const int ref = reference_orient(pl[0], pl[1], pl[2], s);
    EXPECT_EQ(orient(v, s), ref > 0 ? Sign::Positive : (ref < 0 ? Sign::Negative : Sign::Zero));
    ++checked;
  }
  EXPECT_GT(checked, 2500);
  // Degenerate cases go to the exact path; the others are filtered.
  EXPECT_GT(predicate_counters().exact, 500u);
  EXPECT_GT(predicate_counters().filtered, 1000u);
}

// A vertex given exactly (error bound 0 at a grid point: the corners of hull faces) is decided by
// the plane's value there; the result equals the determinant's with approximate_vertex, on the
// plane (zero) or off it, near the origin and at the ends of the grid range.
TEST(Orient, AnExactGridCornerGivesTheSameSignsAsItsApproximation) {
  std::mt19937_64 rng(23);
  auto point = [&](std::int64_t range) {
    std::uniform_int_distribution<std::int64_t> d(-range, range);
    return GridPoint{d(rng), d(rng), d(rng)};
  };
  int checked = 0, zeros = 0;
  for (int i = 0; i < 2000; ++i) {
    const std::int64_t range = i % 2 ? kMaxCoord : 50;
    const GridPoint v = point(range);
    Plane pl[3];
    for (auto& p : pl) {
      try {
        p = plane_through(v, point(range), point(range));
      } catch (...) {
        p = plane_through(v, {v.x + 1, v.y, v.z}, {v.x, v.y + 1, v.z});
      }
    }
    if (!independent(pl[0], pl[1], pl[2])) continue;
    const Plane s = i % 3 == 0 ? plane_through(v, point(range), point(range)) : plane_through(point(range), point(range), point(range));
    const ApproxPoint exact{double(v.x), double(v.y), double(v.z), 0.0};
    const Sign with_exact = orient(pl[0], pl[1], pl[2], exact, s);
    EXPECT_EQ(with_exact, orient(pl[0], pl[1], pl[2], approximate_vertex(pl[0], pl[1], pl[2]), s));
    EXPECT_EQ(int(with_exact), reference_orient(pl[0], pl[1], pl[2], s));
    zeros += with_exact == Sign::Zero;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
  EXPECT_GT(zeros, 400);
}

// Planes with offsets below 2^72 (the fast 4x4-determinant path of the exact stage) and above
// it (the general path): both agree with the Boost reference, degenerate cases included.
TEST(Orient, FastAndGeneralExactPathsAgreeWithBoostReference) {
  std::mt19937_64 rng(5);
  for (const std::int64_t range : {std::int64_t(1) << 15, std::int64_t(1) << 18, kMaxCoord}) {
    std::uniform_int_distribution<std::int64_t> d(-range, range);
    auto point = [&] { return GridPoint{d(rng), d(rng), d(rng)}; };
    predicate_counters() = {};
    int zeros = 0;
    for (int i = 0; i < 2000; ++i) {
      const GridPoint v = point();
      Plane pl[3];
      bool ok = true;
      for (auto& p : pl) {
        try {
          p = plane_through(v, point(), point());
        } catch (...) {
          ok = false;
        }
      }
      if (!ok || !independent(pl[0], pl[1], pl[2])) continue;
      // Through the vertex (exact zero), or through a point one grid step away from it.
      GridPoint w = v;
      w.x += i % 3 == 1 ? 1 : 0;
      Plane s;
      try {
        s = plane_through(w, point(), point());
      } catch (...) {
        continue;
      }
      const ApproxPoint at = approximate_vertex(pl[0], pl[1], pl[2]);
      const int ref = reference_orient(pl[0], pl[1], pl[2], s);
      EXPECT_EQ(int(orient(pl[0], pl[1], pl[2], at, s)), ref);
      zeros += ref == 0;
    }
    EXPECT_GT(zeros, 500) << range;
    EXPECT_GT(predicate_counters().exact_zero, 500u) << range;
    // Non-zero values the filter cannot decide: s misses the grid vertex v by f_s(v) = -1 or +1
    // with a 52-bit normal (relative size 2^-70), or passes through it.
    predicate_counters() = {};
    std::uniform_int_distribution<std::int64_t> big_n(std::int64_t(1) << 50, std::int64_t(1) << 52);
    std::uniform_int_distribution<std::int64_t> small(-9, 9);
    for (int i = 0; i < 600; ++i) {
      const GridPoint v = point();
      auto near = [&] { return GridPoint{v.x + small(rng), v.y + small(rng), v.z + small(rng)}; };
      Plane pl[3];
      bool ok = true;
      for (auto& p : pl) {
        try {
          p = plane_through(v, near(), near());
        } catch (...) {
          ok = false;
        }
      }
      if (!ok || !independent(pl[0], pl[1], pl[2])) continue;
      const std::int64_t a = big_n(rng), b = -big_n(rng), c = big_n(rng) / 3;
      const Int128 offset = -(Int128(a) * v.x + Int128(b) * v.y + Int128(c) * v.z) + (i % 3) - 1;
      const Plane s{a, b, c, offset};
      const ApproxPoint at = approximate_vertex(pl[0], pl[1], pl[2]);
      EXPECT_EQ(int(orient(pl[0], pl[1], pl[2], at, s)), reference_orient(pl[0], pl[1], pl[2], s));
      EXPECT_EQ(int(orient(pl[0], pl[1], pl[2], at, s)), (i % 3) - 1);
    }
    EXPECT_GT(predicate_counters().exact, 500u) << range;
  }
}

TEST(Orient, NearlyDegenerateCasesAreDecidedExactly) {
  // Vertex (0,0,0) of three axis planes; planes passing within one unit of the last bit.
  const Plane x{1, 0, 0, 0}, y{0, 1, 0, 0}, z{0, 0, 1, 0};
  const ApproxPoint at = approximate_vertex(x, y, z);
  const std::int64_t big_n = std::int64_t(1) << 52;
  EXPECT_EQ(orient(x, y, z, at, Plane{big_n, big_n - 1, 3, 1}), Sign::Positive);
  EXPECT_EQ(orient(x, y, z, at, Plane{big_n, big_n - 1, 3, -1}), Sign::Negative);
  EXPECT_EQ(orient(x, y, z, at, Plane{big_n, big_n - 1, 3, 0}), Sign::Zero);
  // A vertex far away from the origin, made by nearly parallel planes.
  const Plane p{big_n, 1, 0, 0}, q{big_n, 0, 1, -(Int128(1) << 70)};
  ASSERT_TRUE(independent(p, q, z));
  const ApproxPoint far = approximate_vertex(p, q, z);
  const HomogeneousPoint h = exact_vertex(p, q, z);
  const Plane through{1, 0, 0, 0};
  EXPECT_EQ(int(orient(p, q, z, far, through)), reference_orient(p, q, z, through));
  (void)h;
}

// IEEE division of two doubles is correctly rounded: the independent reference for quotients of
// integers that doubles hold exactly, scaled by powers of two (also past 2^64, past the double's
// range of exact integers, and with remainders far below the last bit).
TEST(RoundedQuotient, MatchesIeeeDivisionOfExactDoubles) {
  std::mt19937_64 rng(23);
  for (int i = 0; i < 20000; ++i) {
    const std::int64_t n = std::int64_t(rng() >> 11) * (rng() % 2 ? 1 : -1);  // < 2^53: exact
    std::int64_t d = std::int64_t(rng() >> (11 + rng() % 50));
    if (d == 0) d = 1;
    if (rng() % 2) d = -d;
    const int sn = int(rng() % 120), sd = int(rng() % 120);
    const Int256 bn = Int256(n) << sn, bd = Int256(d) << sd;
    const double expected = std::ldexp(double(n), sn) / std::ldexp(double(d), sd);
    ASSERT_EQ(rounded_quotient(bn, bd), expected) << n << " * 2^" << sn << " / " << d << " * 2^" << sd;
  }
  EXPECT_EQ(rounded_quotient(Int256(0), Int256(-7)), 0.0);
  // Ties go to even: (2^53 + 1) / 1 and (2^53 + 3) / 1 are halfway between two doubles.
  EXPECT_EQ(rounded_quotient(Int256((std::int64_t(1) << 53) + 1), Int256(1)), 0x1p53);
  EXPECT_EQ(rounded_quotient(Int256((std::int64_t(1) << 53) + 3), Int256(1)), 0x1p53 + 4);
  // Just above a tie (a remainder far below the last bit) rounds up.
  const Int256 above = (Int256((std::int64_t(1) << 53) + 1) << 100) + 1;
  EXPECT_EQ(rounded_quotient(above, Int256(1) << 100), 0x1p53 + 2);
}

/// The exact value of a double.
boost::multiprecision::cpp_rational rational(double x) {
  using boost::multiprecision::cpp_int;
  using boost::multiprecision::cpp_rational;
  int e = 0;
  const double m = std::frexp(x, &e);
  const cpp_int mant = cpp_int(std::int64_t(std::ldexp(m, 53)));
  return e - 53 >= 0 ? cpp_rational(mant << (e - 53)) : cpp_rational(mant, cpp_int(1) << (53 - e));
}

/// y is the double nearest n / d, the even one of two equally near (the definition, in rationals).
bool nearest_in_rationals(double y, const Int256& n, const Int256& d) {
  using boost::multiprecision::cpp_int;
  using boost::multiprecision::cpp_rational;
  // (Boost 1.74's two-argument rational constructor rejects some negative denominators.)
  const cpp_rational exact = cpp_rational(cpp_int(n)) / cpp_rational(cpp_int(d));
  const cpp_rational dy = abs(exact - rational(y));
  for (const double other : {std::nextafter(y, -1e300), std::nextafter(y, 1e300)}) {
    const cpp_rational dother = abs(exact - rational(other));
    int e = 0;
    const bool odd = (std::int64_t(std::ldexp(std::frexp(y, &e), 53)) & 1) != 0;
    if (dother < dy || (dother == dy && odd)) return false;
  }
  return true;
}

// Quotients of wide integers (numerators to 2^240, denominators to 2^160, as exact vertices have)
// against the definition in rationals: no double is nearer the exact quotient, and of two equally
// near the result is the even one. Near ties and exact ties are built on purpose (the quotient
// within a few parts in 2^200 of a midpoint between two doubles), where the double-double
// approximation cannot decide and the exact division must.
TEST(RoundedQuotient, WideQuotientsAreNearestInRationals) {
  using boost::multiprecision::cpp_int;
  using boost::multiprecision::cpp_rational;
  std::mt19937_64 rng(29);
  auto wide = [&](int bits) {
    Int256 v = 0;
    for (int b = 0; b < bits; b += 60) v = (v << 60) + Int256(rng() >> 4);
    v >>= (bits + 59) / 60 * 60 - bits;
    return v == 0 ? Int256(1) : v;
  };
  auto check = [](const Int256& n, const Int256& d) { return nearest_in_rationals(rounded_quotient(n, d), n, d); };
  int ties = 0;
  for (int i = 0; i < 4000; ++i) {
    Int256 n = wide(1 + int(rng() % 240)), d = wide(1 + int(rng() % 160));
    if (rng() % 2) n = -n;
    if (rng() % 2) d = -d;
    ASSERT_TRUE(check(n, d)) << n << " / " << d;
    // A midpoint m = (2k + 1) 2^(e-1) between two doubles, as a quotient with denominator d2 =
    // 2^s, then moved by -1, 0 or +1 in the numerator (a tie or within 2^-s of one).
    const std::int64_t k = std::int64_t(rng() >> 11) | (std::int64_t(1) << 52);  // 53 bits
    const int s = 60 + int(rng() % 120);
    const Int256 d2 = Int256(1) << s;
    const Int256 n2 = ((Int256(2 * k + 1)) << (s - 40)) + Int256(int(rng() % 3) - 1);
    ties += (n2 & 1) == 0 ? 1 : 0;
    ASSERT_TRUE(check(n2, d2)) << n2 << " / " << d2;
    ASSERT_TRUE(check(-n2, d2)) << -n2 << " / " << d2;
  }
  EXPECT_GT(ties, 1000);
}

// The splits of wide integers into two doubles at their edge cases, against the definition:
// numerators just below a power of two (the leading double rounds up to the next power, and the
// rest, up to 2^74 of 2^128, is negative), and numerators whose leading 128 bits lie at or next to a
// midpoint between two doubles, with and without bits below them (the sticky bit decides).
TEST(RoundedQuotient, SplitsAtRoundingEdgesAreNearestInRationals) {
  const std::array<Int256, 5> denominators = {Int256(3), Int256(-7), Int256(1000003), (Int256(1) << 64) + 13,
                                              -((Int256(1) << 150) + 12345)};
  const std::array<Int256, 6> below = {Int256(1), Int256(3), (Int256(1) << 40) + 1, (Int256(1) << 60) - 1,
                                       (Int256(1) << 73) + 5, (Int256(1) << 74) - 1};
  for (int k = 128; k <= 250; k += 7)
    for (const Int256& j : below) {
      const Int256 n = (Int256(1) << k) - (j << (k - 128));
      for (const Int256& d : denominators) {
        ASSERT_TRUE(nearest_in_rationals(rounded_quotient(n, d), n, d)) << n << " / " << d;
        ASSERT_TRUE(nearest_in_rationals(rounded_quotient(-n, d), -n, d)) << -n << " / " << d;
      }
    }
  for (int shift = 0; shift <= 100; shift += 25)
    for (const int low : {-1, 0, 1})
      for (const int odd : {0, 1}) {
        // Leading 128 bits 2^127 + (2 odd + 1) 2^74 (+ 2^75 odd): a midpoint; `low` below them.
        const Int256 top = (Int256(1) << 127) + (Int256(2 * odd + 1) << 74);
        const Int256 n = (top << shift) + low;
        for (const Int256& d : denominators) ASSERT_TRUE(nearest_in_rationals(rounded_quotient(n, d), n, d)) << n << " / " << d;
      }
}

// rounded_vertex's own path (256-bit sums of products and the double-double quotient, taken when
// the approximation's error bound is not small enough) against the exact vertex in rationals, on
// planes through random grid points (many nearly parallel), with the approximation's bound
// withheld (err < 0) so that every vertex takes that path.
TEST(RoundedVertex, EveryCoordinateIsNearestInRationals) {
  std::mt19937_64 rng(31);
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::int64_t span = std::int64_t(1) << (4 + rng() % 21);
    auto coord = [&] { return std::int64_t(rng() % std::uint64_t(2 * span)) - span; };
    auto point = [&] { return GridPoint{coord(), coord(), coord()}; };
    const GridPoint v = point();
    auto near = [&](const GridPoint& g) {  // sometimes a plane tilted by one step from another
      return GridPoint{g.x + std::int64_t(rng() % 3) - 1, g.y + std::int64_t(rng() % 3) - 1, g.z + std::int64_t(rng() % 3) - 1};
    };
    const GridPoint a = point(), b = point();
    const Plane p = plane_through(v, a, b);
    const Plane q = rng() % 2 ? plane_through(point(), near(a), near(b)) : plane_through(point(), point(), point());
    const Plane r = plane_through(point(), point(), point());
    if (!independent(p, q, r)) continue;
    const Eigen::Vector3d got = rounded_vertex(p, q, r, ApproxPoint{});
    const HomogeneousPoint h = exact_vertex(p, q, r);
    ASSERT_TRUE(nearest_in_rationals(got.x(), h.x, h.w)) << i;
    ASSERT_TRUE(nearest_in_rationals(got.y(), h.y, h.w)) << i;
    ASSERT_TRUE(nearest_in_rationals(got.z(), h.z, h.w)) << i;
    ++checked;
  }
  EXPECT_GT(checked, 2500);
}

// A grid point defined by ill-conditioned planes (two nearly coplanar planes through it) is written
// as exactly that grid point, although the filter's approximation is off by far more than an ulp.
TEST(RoundedVertex, GridPointOfIllConditionedPlanesIsExact) {
  const GridPoint v{12345, -6789, 321};
  const GridPoint a{v.x + 1000000, v.y + 3, v.z + 1}, b{v.x + 2, v.y + 1000000, v.z - 1};
  const GridPoint c{v.x + 1000000, v.y + 3, v.z + 2};  // the second plane tilts by 1 step in 10^6
  const Plane p = plane_through(v, a, b), q = plane_through(v, c, b);
  const Plane r = plane_through(v, GridPoint{v.x, v.y, v.z + 5}, GridPoint{v.x + 7, v.y - 3, v.z + 5});
  ASSERT_TRUE(independent(p, q, r));
  const ApproxPoint at = approximate_vertex(p, q, r);
  // The filter cannot vouch for the last bits here: rounded_vertex takes its exact path.
  EXPECT_GT(at.err, 0x1p-50 * 12345.0);
  const Eigen::Vector3d w = rounded_vertex(p, q, r, at);
  EXPECT_EQ(w, Eigen::Vector3d(double(v.x), double(v.y), double(v.z)));
}

}  // namespace
}  // namespace sculpt::kernel
