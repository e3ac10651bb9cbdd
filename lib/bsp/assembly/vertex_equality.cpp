#include "bsp/assembly/vertex_equality.hpp"

#include "kernel/wide_int.hpp"

namespace sculpt::bsp::detail {

using kernel::Int128;
using kernel::Plane;

namespace {

constexpr Int128 kSmallOffset = Int128(1) << 72;

bool small(const Plane& e) { return e.d < kSmallOffset && e.d > -kSmallOffset; }

Int128 minor_ab(const Plane& x, const Plane& y) { return Int128(x.a) * y.b - Int128(y.a) * x.b; }
Int128 minor_cd(const Plane& x, const Plane& y) { return Int128(x.c) * y.d - Int128(y.c) * x.d; }

// Bits of |x| (0 for 0).
int magnitude_bits(Int128 x) {
  __extension__ typedef unsigned __int128 U128;
  const U128 u = x < 0 ? U128(0) - U128(x) : U128(x);
  const auto hi = std::uint64_t(u >> 64), lo = std::uint64_t(u);
  return hi != 0 ? 128 - __builtin_clzll(hi) : (lo != 0 ? 64 - __builtin_clzll(lo) : 0);
}

}  // namespace

VertexMinors vertex_minors(const Plane& p, const Plane& q, const Plane& r, const kernel::ApproxPoint& at) {
  VertexMinors v{{&p, &q, &r}, &at, small(p) && small(q) && small(r), 0, 0, 0, 0, 0, 0};
  if (v.small) {
    v.m01 = minor_ab(p, q), v.m02 = minor_ab(p, r), v.m12 = minor_ab(q, r);
    v.n01 = minor_cd(p, q), v.n02 = minor_cd(p, r), v.n12 = minor_cd(q, r);
  }
  return v;
}

bool vertex_on_plane(const VertexMinors& v, const Plane& s) {
  const Plane &p = *v.rows[0], &q = *v.rows[1], &r = *v.rows[2];
  if (!v.small || !small(s)) return kernel::orient(p, q, r, *v.at, s) == kernel::Sign::Zero;
  // Laplace expansion by the (a, b) and (c, d) column pairs, rows 0..2 = p, q, r and 3 = s:
  // det = m01 n23 - m02 n13 + m03 n12 + m12 n03 - m13 n02 + m23 n01.
  struct Term {
    Int128 m, n;
    bool subtract;
  };
  const Term terms[6] = {{v.m01, minor_cd(r, s), false}, {v.m02, minor_cd(q, s), true},  {minor_ab(p, s), v.n12, false},
                         {v.m12, minor_cd(p, s), false}, {minor_ab(q, s), v.n02, true}, {minor_ab(r, s), v.n01, false}};
  // 128-bit path: when every product has at most 124 bits, the six sum to less than 2^127.
  // (Axis-aligned planes make most minors zero or small: every box and most sphere tests.)
  bool narrow = true;
  for (const Term& t : terms) narrow = narrow && magnitude_bits(t.m) + magnitude_bits(t.n) <= 124;
  if (narrow) {
    Int128 sum = 0;
    for (const Term& t : terms) sum += t.subtract ? -(t.m * t.n) : t.m * t.n;
    return sum == 0;
  }
  kernel::ProductSum256 det;  // (kernel/wide_int.hpp, shared with kernel::orient)
  for (const Term& t : terms)
    if (t.m != 0 && t.n != 0) det.add_product(t.m, t.n, t.subtract);
  return det.zero();
}

}  // namespace sculpt::bsp::detail
