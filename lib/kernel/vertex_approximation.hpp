#pragma once
/// \file vertex_approximation.hpp
/// The floating-point approximation of a vertex p ∩ q ∩ r (Cramer's rule with a rigorous error
/// bound, docs/kernel.md), written once for T = double and for T = a pair of doubles (GCC vector
/// extension). Each lane of a pair operation is the scalar IEEE operation (-ffp-contract=off), so a
/// batch that computes two corners at once (bsp/ring_boundary.cpp) gets exactly approximate_vertex's
/// bits: approximate_vertex (kernel/predicates.cpp) is this code for T = double.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "kernel/plane.hpp"

namespace sculpt::kernel::approximation {

constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, unit roundoff

__extension__ typedef double Pair __attribute__((vector_size(16)));
__extension__ typedef std::int64_t PairMask __attribute__((vector_size(16)));

inline double abs_of(double v) { return std::fabs(v); }
inline Pair abs_of(Pair v) {  // clears the sign bits, as fabs does
  constexpr std::int64_t kMagnitude = std::numeric_limits<std::int64_t>::max();
  return Pair(PairMask(v) & PairMask{kMagnitude, kMagnitude});
}
inline double max_of(double a, double b) { return std::max(a, b); }
inline Pair max_of(Pair a, Pair b) { return a < b ? b : a; }  // std::max's choice in each lane

template <class T>
struct Normal {  // a plane's normal in double (exact), its largest |component| and d_nearest
  T a, b, c, n, d;
};

inline Normal<double> normal_of(const Plane& p) {
  Normal<double> r{double(p.a), double(p.b), double(p.c), 0.0, p.d_nearest};
  r.n = std::max(std::max(std::fabs(r.a), std::fabs(r.b)), std::fabs(r.c));
  return r;
}

inline Normal<Pair> pair_of(const Normal<double>& u, const Normal<double>& v) {
  return {Pair{u.a, v.a}, Pair{u.b, v.b}, Pair{u.c, v.c}, Pair{u.n, v.n}, Pair{u.d, v.d}};
}

template <class T>
struct Cross {
  T x, y, z;
  T max;  // largest |component| of the computed value
  T err;  // bound on the error of each component
};

template <class T>
Cross<T> cross(const Normal<T>& p, const Normal<T>& q) {
  Cross<T> r;
  r.x = p.b * q.c - p.c * q.b;
  r.y = p.c * q.a - p.a * q.c;
  r.z = p.a * q.b - p.b * q.a;
  r.max = max_of(max_of(abs_of(r.x), abs_of(r.y)), abs_of(r.z));
  r.err = 4.0 * kEps * 2.0 * p.n * q.n;
  return r;
}

// The vertex p ∩ q ∩ r and what its error bound needs: approximate_vertex's err is
// error_bound(a) (split off so the coordinates' divisions of many corners can run before the
// bound's division, which waits for them).
template <class T>
struct Approximation {
  T x, y, z;
  T eV, eW, aW;
  decltype(T{} > T{}) usable;  // false: nearly dependent planes, the kernel's exact rounding is needed
};

template <class T>
T error_bound(T x, T y, T z, T eV, T eW, T aW) {
  const T m = max_of(max_of(abs_of(x), abs_of(y)), abs_of(z));
  return 1.01 * ((eV + m * eW) / (aW - eW) + 2.0 * kEps * m);
}

template <class T>
Approximation<T> approximate(const Normal<T>& pn, const Normal<T>& qn, const Normal<T>& rn) {
  const Cross<T> u = cross(qn, rn), v = cross(rn, pn), w = cross(pn, qn);
  const T pa = pn.a, pb = pn.b, pc = pn.c;
  const T W = pa * u.x + pb * u.y + pc * u.z;
  const T np = pn.n;
  const T eW = 3.0 * np * u.err + 4.0 * kEps * 3.0 * np * u.max;
  const T dp = pn.d, dq = qn.d, dr = rn.d;
  const T vx = dp * u.x + dq * v.x + dr * w.x;
  const T vy = dp * u.y + dq * v.y + dr * w.y;
  const T vz = dp * u.z + dq * v.z + dr * w.z;
  const T adp = abs_of(dp), adq = abs_of(dq), adr = abs_of(dr);
  const T eV = (1.0 + 4.0 * kEps) * (adp * u.err + adq * v.err + adr * w.err) +
               6.0 * kEps * (adp * u.max + adq * v.max + adr * w.max);
  const T aW = abs_of(W);
  Approximation<T> a;
  a.usable = aW > 2.0 * eW;
  a.x = -vx / W;
  a.y = -vy / W;
  a.z = -vz / W;
  a.eV = eV, a.eW = eW, a.aW = aW;
  return a;
}

}  // namespace sculpt::kernel::approximation
