#include "mesh/predicates.hpp"

#include <boost/multiprecision/cpp_int.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sculpt {
namespace {

using Rational = boost::multiprecision::cpp_rational;
using Int256 = boost::multiprecision::int256_t;
using Int512 = boost::multiprecision::int512_t;

// Shewchuk's first-stage bounds (ccwerrboundA, o3derrboundA), shared with Orient3dPlane.
constexpr double kOrient2dBound = detail::kOrient2dFilterBound;
constexpr double kOrient3dBound = detail::kOrient3dFilterBound;
// The bounds assume no underflow; below this magnitude the exact path decides (each underflow
// loses at most 2^-1074, far below kOrient*Bound * 1e-280).
constexpr double kNoUnderflow = detail::kFilterNoUnderflow;

/// Finite doubles as integers times a common power of two: x_i = m_i * 2^(e_i) with |m_i| < 2^53,
/// and `shift` = max e_i - min e_i over the non-zero inputs. All inputs scaled by 2^-min(e) are
/// integers of at most 53 + shift bits, so sums and products in fixed-width integers are exact
/// when the width covers the bit count of the determinant.
template <size_t N>
struct Scaled {
  std::array<long long, N> mantissa{};
  std::array<int, N> exponent{};
  int min_exponent = 0;
  int shift = 0;

  explicit Scaled(const std::array<double, N>& x) {
    int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
    for (size_t i = 0; i < N; ++i) {
      if (x[i] == 0) continue;
      int e = 0;
      const double f = std::frexp(x[i], &e);  // x = f 2^e, 0.5 <= |f| < 1
      mantissa[i] = static_cast<long long>(std::ldexp(f, 53));
      exponent[i] = e - 53;
      lo = std::min(lo, exponent[i]);
      hi = std::max(hi, exponent[i]);
    }
    min_exponent = lo == std::numeric_limits<int>::max() ? 0 : lo;
    shift = lo == std::numeric_limits<int>::max() ? 0 : hi - lo;
  }

  template <typename Int>
  [[nodiscard]] Int value(size_t i) const {
    if (mantissa[i] == 0) return Int(0);
    const Int magnitude = Int(mantissa[i] < 0 ? -mantissa[i] : mantissa[i]) << (exponent[i] - min_exponent);
    return mantissa[i] < 0 ? Int(-magnitude) : magnitude;
  }
};

template <typename Num, typename Get>
int orient2d_sign(Get get) {
  const Num acx = get(0) - get(4), bcx = get(2) - get(4);
  const Num acy = get(1) - get(5), bcy = get(3) - get(5);
  const Num det = acx * bcy - acy * bcx;
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const std::array<double, 6> x = {a.x(), a.y(), b.x(), b.y(), c.x(), c.y()};
  const Scaled<6> s(x);
  // |det| < 2 (2^(54 + shift))^2: 2 * (54 + shift) + 2 bits.
  if (2 * (54 + s.shift) + 2 < 255) return orient2d_sign<Int256>([&](size_t i) { return s.value<Int256>(i); });
  if (2 * (54 + s.shift) + 2 < 511) return orient2d_sign<Int512>([&](size_t i) { return s.value<Int512>(i); });
  return orient2d_sign<Rational>([&](size_t i) { return Rational(x[i]); });
}

template <typename Num, typename Get>
int orient3d_sign(Get get) {
  // det[b-a, c-a, d-a] with a, b, c, d at indices 0, 3, 6, 9.
  Num m[3][3];
  for (int k = 0; k < 3; ++k) {
    m[0][k] = get(3 + k) - get(k);
    m[1][k] = get(6 + k) - get(k);
    m[2][k] = get(9 + k) - get(k);
  }
  const Num det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                  m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                  m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return det > 0 ? 1 : (det < 0 ? -1 : 0);
}

int orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                   const Eigen::Vector3d& d) {
  const std::array<double, 12> x = {a.x(), a.y(), a.z(), b.x(), b.y(), b.z(),
                                    c.x(), c.y(), c.z(), d.x(), d.y(), d.z()};
  const Scaled<12> s(x);
  // |det| < 6 (2^(54 + shift))^3: 3 * (54 + shift) + 3 bits.
  if (3 * (54 + s.shift) + 3 < 255) return orient3d_sign<Int256>([&](size_t i) { return s.value<Int256>(i); });
  if (3 * (54 + s.shift) + 3 < 511) return orient3d_sign<Int512>([&](size_t i) { return s.value<Int512>(i); });
  return orient3d_sign<Rational>([&](size_t i) { return Rational(x[i]); });
}


// Second stage (Shewchuk 1997, "Adaptive precision floating-point arithmetic and fast robust
// geometric predicates", sec. 2): when the coordinate differences are exact, the determinant of
// the differences is a sum of products of doubles, evaluated exactly as a floating-point
// expansion (non-overlapping components, increasing magnitude); its sign is the sign of the
// largest component. Exactness needs no overflow and no underflow: every non-zero difference is
// kept within [2^-300, 2^300] (so every product of three is a multiple of 2^-1056 and below 2^903).
constexpr double kExpansionMin = 0x1p-300;
constexpr double kExpansionMax = 0x1p300;

bool in_expansion_range(double x) {
  const double m = std::abs(x);
  return m == 0 || (m >= kExpansionMin && m <= kExpansionMax);
}

/// a - b as x + tail exactly (Knuth's two-difference); true when the tail is zero.
bool exact_difference(double a, double b, double& x) {
  x = a - b;
  const double bv = a - x, av = x + bv;
  return (a - av) + (bv - b) == 0;
}

/// x + y = hi + lo exactly (Knuth's two-sum).
void two_sum(double x, double y, double& hi, double& lo) {
  hi = x + y;
  const double bv = hi - x, av = hi - bv;
  lo = (x - av) + (y - bv);
}

/// a b - c d as an expansion of at most 4 components (zero components dropped), increasing.
int two_two_diff_products(double a, double b, double c, double d, double* out) {
  const double p = a * b, pe = std::fma(a, b, -p);
  const double q = c * d, qe = std::fma(c, d, -q);
  // (p + pe) - (q + qe): Shewchuk's Two_Two_Diff.
  double x0, x1, x2, x3, i, j, k;
  two_sum(pe, -qe, i, x0);
  two_sum(p, i, j, k);
  two_sum(k, -q, i, x1);
  two_sum(j, i, x3, x2);
  int n = 0;
  for (double v : {x0, x1, x2, x3})
    if (v != 0) out[n++] = v;
  return n;
}

/// e * b (e an expansion of n components) as an expansion, zero components dropped
/// (Shewchuk's Scale_Expansion_Zeroelim); returns the length.
int scale_expansion(int n, const double* e, double b, double* h) {
  int len = 0;
  double q = e[0] * b, hh = std::fma(e[0], b, -q);
  if (hh != 0) h[len++] = hh;
  for (int i = 1; i < n; ++i) {
    const double p1 = e[i] * b, p0 = std::fma(e[i], b, -p1);
    double sum;
    two_sum(q, p0, sum, hh);
    if (hh != 0) h[len++] = hh;
    two_sum(p1, sum, q, hh);  // p1 and sum do not overlap: Fast_Two_Sum would do
    if (hh != 0) h[len++] = hh;
  }
  if (q != 0 || len == 0) h[len++] = q;
  return len;
}

/// e + f as an expansion, zero components dropped (Shewchuk's Fast_Expansion_Sum_Zeroelim:
/// the components of both, merged by magnitude, summed from the smallest up; exact for
/// non-overlapping expansions under round-to-nearest-even); returns the length.
int sum_expansions(int n, const double* e, int m, const double* f, double* h) {
  if (n == 0 || m == 0) {
    const double* src = n == 0 ? f : e;
    const int len = n == 0 ? m : n;
    for (int i = 0; i < len; ++i) h[i] = src[i];
    return len;
  }
  int i = 0, j = 0, len = 0;
  auto next = [&] {  // the smaller in magnitude of e[i] and f[j] (either list may be used up)
    if (j >= m || (i < n && std::abs(e[i]) < std::abs(f[j]))) return e[i++];
    return f[j++];
  };
  double q = next();
  while (i < n || j < m) {
    double hi, lo;
    two_sum(q, next(), hi, lo);
    if (lo != 0) h[len++] = lo;
    q = hi;
  }
  if (q != 0 || len == 0) h[len++] = q;
  return len;
}

int expansion_sign(int n, const double* e) {
  for (int i = n - 1; i >= 0; --i)
    if (e[i] != 0) return e[i] > 0 ? 1 : -1;
  return 0;
}

/// Sign of det[[ax, ay, az], [bx, by, bz], [cx, cy, cz]] (rows a, b, c: the exact differences),
/// evaluated exactly; the caller checked the range.
int det3_sign(const double* a, const double* b, const double* c) {
  double m1[4], m2[4], m3[4], t1[8], t2[8], t3[8], s12[16], all[24];
  // det = az (bx cy - cx by) + bz (cx ay - ax cy) + cz (ax by - bx ay)
  const int n1 = two_two_diff_products(b[0], c[1], c[0], b[1], m1);
  const int n2 = two_two_diff_products(c[0], a[1], a[0], c[1], m2);
  const int n3 = two_two_diff_products(a[0], b[1], b[0], a[1], m3);
  const int k1 = n1 == 0 || a[2] == 0 ? 0 : scale_expansion(n1, m1, a[2], t1);
  const int k2 = n2 == 0 || b[2] == 0 ? 0 : scale_expansion(n2, m2, b[2], t2);
  const int k3 = n3 == 0 || c[2] == 0 ? 0 : scale_expansion(n3, m3, c[2], t3);
  const int k12 = sum_expansions(k1, t1, k2, t2, s12);
  const int k = sum_expansions(k12, s12, k3, t3, all);
  return expansion_sign(k, all);
}

/// Sign of det[a-d; b-d; c-d] from the raw coordinates, exactly (Shewchuk's orient3dexact):
/// expanding the 4x4 determinant [p, 1] along z, D = az (m_bc + m_cd + m_db) - bz (m_ac + m_cd +
/// m_da) + cz (m_ab + m_bd + m_da) - dz (m_ab + m_bc + m_ca) with m_pq = xp yq - xq yp. Every
/// non-zero coordinate must lie within [2^-300, 2^300] (products of three stay exact).
int det4_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  struct Minor {
    double e[4];
    int n = 0;
  };
  auto minor = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    Minor m;
    m.n = two_two_diff_products(p.x(), q.y(), q.x(), p.y(), m.e);
    return m;
  };
  auto negated = [](Minor m) {
    for (int i = 0; i < m.n; ++i) m.e[i] = -m.e[i];
    return m;
  };
  const Minor ab = minor(a, b), ac = minor(a, c), ad = minor(a, d), bc = minor(b, c), bd = minor(b, d), cd = minor(c, d);
  const Minor da = negated(ad), db = negated(bd), ca = negated(ac);
  // z times the sum of three minors, as an expansion (at most 24 components).
  auto term = [](double z, const Minor& x, const Minor& y, const Minor& w, double* out) {
    if (z == 0) return 0;
    double s1[8], s2[12];
    const int n1 = sum_expansions(x.n, x.e, y.n, y.e, s1);
    const int n2 = sum_expansions(n1, s1, w.n, w.e, s2);
    if (n2 == 0) return 0;
    return scale_expansion(n2, s2, z, out);
  };
  double ta[24], tb[24], tc[24], td[24], s1[48], s2[48], all[96];
  const int na = term(a.z(), bc, cd, db, ta);
  const int nb = term(-b.z(), ac, cd, da, tb);
  const int nc = term(c.z(), ab, bd, da, tc);
  const int nd = term(-d.z(), ab, bc, ca, td);
  const int n1 = sum_expansions(na, ta, nb, tb, s1);
  const int n2 = sum_expansions(nc, tc, nd, td, s2);
  return expansion_sign(sum_expansions(n1, s1, n2, s2, all), all);
}

}  // namespace

int orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  // Same expression as Shewchuk's orient2dfast, so that his error bound applies.
  const double detleft = (a.x() - c.x()) * (b.y() - c.y());
  const double detright = (a.y() - c.y()) * (b.x() - c.x());
  const double det = detleft - detright;
  const double detsum = std::abs(detleft) + std::abs(detright);
  const double bound = kOrient2dBound * detsum;
  if (std::isfinite(det) && std::isfinite(bound) && detsum > kNoUnderflow && (det > bound || -det > bound))
    return det > 0 ? 1 : -1;
  if (detsum == 0 && in_expansion_range(a.x() - c.x()) && in_expansion_range(b.y() - c.y()) &&
      in_expansion_range(a.y() - c.y()) && in_expansion_range(b.x() - c.x()))
    return 0;  // both products zero, each because a factor is (as in orient3d)
  // Second stage: exact differences give the determinant exactly as an expansion.
  double acx = 0, acy = 0, bcx = 0, bcy = 0;
  if (exact_difference(a.x(), c.x(), acx) && exact_difference(a.y(), c.y(), acy) && exact_difference(b.x(), c.x(), bcx) &&
      exact_difference(b.y(), c.y(), bcy) && in_expansion_range(acx) && in_expansion_range(acy) &&
      in_expansion_range(bcx) && in_expansion_range(bcy)) {
    double m[4];
    return expansion_sign(two_two_diff_products(acx, bcy, acy, bcx, m), m);
  }
  return orient2d_exact(a, b, c);
}

namespace {

/// orient3d's first stage: the differences to d, the determinant's permanent, and its sign when
/// the filter certifies it (kUndecided otherwise).
struct Orient3dFilter {
  double dx[3], dy[3], dz[3];  // a - d, b - d, c - d by coordinate
  double permanent = 0;
  int sign = kUndecided;
};

Orient3dFilter orient3d_filter(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                               const Eigen::Vector3d& d) {
  // Shewchuk's orient3d evaluates det[a-d, b-d, c-d], which is -det[b-a, c-a, d-a].
  Orient3dFilter f;
  const Eigen::Vector3d* rows[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) f.dx[i] = (*rows[i]).x() - d.x(), f.dy[i] = (*rows[i]).y() - d.y(), f.dz[i] = (*rows[i]).z() - d.z();
  const double adx = f.dx[0], bdx = f.dx[1], cdx = f.dx[2], ady = f.dy[0], bdy = f.dy[1], cdy = f.dy[2];
  const double adz = f.dz[0], bdz = f.dz[1], cdz = f.dz[2];
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  f.permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  const double bound = kOrient3dBound * f.permanent;
  if (std::isfinite(det) && std::isfinite(bound) && f.permanent > kNoUnderflow && (det > bound || -det > bound))
    f.sign = det > 0 ? -1 : 1;
  return f;
}

}  // namespace

int orient3d_filtered(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& d) {
  return orient3d_filter(a, b, c, d).sign;
}

int orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
             const Eigen::Vector3d& d) {
  const Orient3dFilter f = orient3d_filter(a, b, c, d);
  if (f.sign != kUndecided) return f.sign;
  // All terms zero (points on a plane parallel to a coordinate plane, say): a product of computed
  // differences is zero only when a factor is, which is exact (a - b rounds to 0 only when a == b),
  // unless a product of non-zero factors underflowed; with every non-zero difference at least
  // 2^-300 in magnitude no product of three does.
  if (f.permanent == 0 && std::all_of(std::begin(f.dx), std::end(f.dx), in_expansion_range) &&
      std::all_of(std::begin(f.dy), std::end(f.dy), in_expansion_range) &&
      std::all_of(std::begin(f.dz), std::end(f.dz), in_expansion_range))
    return 0;
  // Second stage: the differences are exact (often for nearby points), so det[a-d, b-d, c-d] is
  // evaluated exactly as an expansion.
  double r[3][3];
  const Eigen::Vector3d* rows[3] = {&a, &b, &c};
  bool exact = true;
  for (int i = 0; i < 3 && exact; ++i)
    for (int k = 0; k < 3 && exact; ++k)
      exact = exact_difference((*rows[i])[k], d[k], r[i][k]) && in_expansion_range(r[i][k]);
  if (exact) return -det3_sign(r[0], r[1], r[2]);
  // Third stage: the coordinates themselves in range, the whole determinant as an expansion.
  bool in_range = true;
  for (const Eigen::Vector3d* p : {&a, &b, &c, &d})
    for (int k = 0; k < 3; ++k) in_range = in_range && in_expansion_range((*p)[k]);
  if (in_range) return -det4_sign(a, b, c, d);
  return orient3d_exact(a, b, c, d);
}

}  // namespace sculpt
