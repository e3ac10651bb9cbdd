#pragma once
/// \file wide_int.hpp
/// A minimal fixed-width signed 256-bit integer (two's complement, four 64-bit limbs) for the
/// exact path of the predicates: products of Int128 values and sums of such products. About
/// ten times faster than Boost's cpp_int for these sizes; checked against it in the tests.
/// Arithmetic is modulo 2^256: callers keep results within the bit budget of exact_int.hpp.

#include <cstdint>

#include "kernel/exact_int.hpp"

namespace sculpt::kernel {

struct Wide {
  std::uint64_t limb[4] = {0, 0, 0, 0};  ///< little endian, two's complement

  __extension__ typedef unsigned __int128 U128;

  static Wide from(Int128 v) {
    Wide r;
    r.limb[0] = std::uint64_t(U128(v));
    r.limb[1] = std::uint64_t(U128(v) >> 64);
    r.limb[2] = r.limb[3] = v < 0 ? ~std::uint64_t(0) : 0;
    return r;
  }
  [[nodiscard]] bool negative() const { return (limb[3] >> 63) != 0; }
  [[nodiscard]] bool zero() const { return (limb[0] | limb[1] | limb[2] | limb[3]) == 0; }
  [[nodiscard]] int sign() const { return negative() ? -1 : (zero() ? 0 : 1); }

  [[nodiscard]] Wide operator-() const {
    Wide r;
    U128 carry = 1;
    for (int i = 0; i < 4; ++i) {
      const U128 s = U128(~limb[i]) + carry;
      r.limb[i] = std::uint64_t(s);
      carry = s >> 64;
    }
    return r;
  }
  friend Wide operator+(const Wide& a, const Wide& b) {
    Wide r;
    U128 carry = 0;
    for (int i = 0; i < 4; ++i) {
      const U128 s = U128(a.limb[i]) + b.limb[i] + carry;
      r.limb[i] = std::uint64_t(s);
      carry = s >> 64;
    }
    return r;
  }
  friend Wide operator-(const Wide& a, const Wide& b) { return a + (-b); }
  friend bool operator==(const Wide& a, const Wide& b) {
    return a.limb[0] == b.limb[0] && a.limb[1] == b.limb[1] && a.limb[2] == b.limb[2] && a.limb[3] == b.limb[3];
  }

  /// |a| * |b| for magnitudes below 2^128 each, lower 256 bits.
  static Wide mul_magnitudes(const std::uint64_t* a, int na, const std::uint64_t* b, int nb) {
    Wide r;
    for (int i = 0; i < na; ++i) {
      U128 carry = 0;
      for (int j = 0; j < nb && i + j < 4; ++j) {
        const U128 t = U128(a[i]) * b[j] + r.limb[i + j] + carry;
        r.limb[i + j] = std::uint64_t(t);
        carry = t >> 64;
      }
      if (i + nb < 4) r.limb[i + nb] = std::uint64_t(carry);
    }
    return r;
  }
  /// Product of two Int128 values (exact: < 2^254 in magnitude).
  static Wide mul(Int128 a, Int128 b) {
    const U128 ma = a < 0 ? U128(0) - U128(a) : U128(a), mb = b < 0 ? U128(0) - U128(b) : U128(b);
    const std::uint64_t x[2] = {std::uint64_t(ma), std::uint64_t(ma >> 64)};
    const std::uint64_t y[2] = {std::uint64_t(mb), std::uint64_t(mb >> 64)};
    Wide r = mul_magnitudes(x, x[1] ? 2 : 1, y, y[1] ? 2 : 1);
    return (a < 0) != (b < 0) ? -r : r;
  }
  /// Product with an Int128 value, modulo 2^256.
  friend Wide operator*(const Wide& a, Int128 b) {
    const bool na = a.negative();
    const Wide ma = na ? -a : a;
    const U128 mb = b < 0 ? U128(0) - U128(b) : U128(b);
    const std::uint64_t y[2] = {std::uint64_t(mb), std::uint64_t(mb >> 64)};
    Wide r = mul_magnitudes(ma.limb, 4, y, y[1] ? 2 : 1);
    return na != (b < 0) ? -r : r;
  }
};

/// Signed 256-bit sum of products of two Int128 values, for the fast exact paths (the 4x4
/// orientation determinant of predicates.cpp, the vertex-on-plane test of the mesh assembly):
/// two's complement in two unsigned 128-bit halves, four 64 x 64 -> 128-bit products per term,
/// straight-line code. Modulo 2^256: callers keep sums within the bit budget.
struct ProductSum256 {
  __extension__ typedef unsigned __int128 U128;
  U128 lo = 0, hi = 0;

  void add_product(Int128 a, Int128 b, bool subtract) {
    const bool negative = ((a < 0) != (b < 0)) != subtract;
    const U128 ua = a < 0 ? U128(0) - U128(a) : U128(a), ub = b < 0 ? U128(0) - U128(b) : U128(b);
    const std::uint64_t a0 = std::uint64_t(ua), a1 = std::uint64_t(ua >> 64);
    const std::uint64_t b0 = std::uint64_t(ub), b1 = std::uint64_t(ub >> 64);
    const U128 p00 = U128(a0) * b0, p01 = U128(a0) * b1, p10 = U128(a1) * b0, p11 = U128(a1) * b1;
    const U128 mid = (p00 >> 64) + std::uint64_t(p01) + std::uint64_t(p10);
    const U128 plo = (mid << 64) | std::uint64_t(p00);
    const U128 phi = p11 + (p01 >> 64) + (p10 >> 64) + (mid >> 64);
    if (negative) {
      const U128 nlo = lo - plo;
      hi = hi - phi - (nlo > lo ? 1 : 0);
      lo = nlo;
    } else {
      const U128 nlo = lo + plo;
      hi = hi + phi + (nlo < lo ? 1 : 0);
      lo = nlo;
    }
  }
  [[nodiscard]] bool zero() const { return (hi | lo) == 0; }
  [[nodiscard]] int sign() const {
    if ((hi >> 127) != 0) return -1;
    return (hi | lo) != 0 ? 1 : 0;
  }
};

}  // namespace sculpt::kernel
