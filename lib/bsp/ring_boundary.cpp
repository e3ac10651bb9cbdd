#include "bsp/ring_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace sculpt::detail {

using kernel::ApproxPoint;
using kernel::Plane;

namespace {

// kernel/predicates.cpp's approximate_vertex, operation for operation (the same expressions in the
// same order, -ffp-contract=off), so every result has the same bits; the test
// RingBoundary.BatchApproximationsHaveTheKernelsBits checks that on ring corners and random planes.
// Written once for T = double and for T = a pair of doubles (GCC vector extension): each lane of a
// pair operation is the scalar IEEE operation, so two corners are computed at once with the same
// bits (half the instructions and divisions per corner).
constexpr double kEps = 1.1102230246251565e-16;  // 2^-53, unit roundoff

__extension__ typedef double Pair __attribute__((vector_size(16)));
__extension__ typedef std::int64_t PairMask __attribute__((vector_size(16)));

inline double abs_of(double v) { return std::fabs(v); }
inline Pair abs_of(Pair v) {  // clears the sign bits, as fabs does
  return Pair(PairMask(v) & PairMask{std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::max()});
}
inline double max_of(double a, double b) { return std::max(a, b); }
inline Pair max_of(Pair a, Pair b) { return a < b ? b : a; }  // std::max's choice in each lane

template <class T>
struct Normal {  // a plane's normal in double (exact), its largest |component| and d_nearest
  T a, b, c, n, d;
};

Normal<double> normal_of(const Plane& p) {
  Normal<double> r{double(p.a), double(p.b), double(p.c), 0.0, p.d_nearest};
  r.n = std::max(std::max(std::fabs(r.a), std::fabs(r.b)), std::fabs(r.c));
  return r;
}

Normal<Pair> pair_of(const Normal<double>& u, const Normal<double>& v) {
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


// The approximations of `triples` into dest(i) (an ApproxPoint&): first the coordinates of all
// corners, two at a time, then their error bounds, then the kernel's for nearly dependent planes.
template <class Dest>
void approximate_into(const kernel::PlaneTable& planes, std::span<const PlaneTriple> triples, Dest dest) {
  std::vector<Normal<double>> normal(std::size_t(planes.size()));
  for (std::int32_t i = 0; i < planes.size(); ++i) normal[std::size_t(i)] = normal_of(planes[i]);
  auto at = [&normal](std::int32_t i) -> const Normal<double>& { return normal[std::size_t(i)]; };
  struct Bound {
    double eV, eW, aW;
  };
  const std::unique_ptr<Bound[]> bound(new Bound[triples.size()]);  // no zeroing: all written
  std::vector<std::size_t> unusable;
  std::size_t i = 0;
  for (; i + 1 < triples.size(); i += 2) {
    const PlaneTriple s = triples[i], t = triples[i + 1];
    const Approximation<Pair> a =
        approximate(pair_of(at(s.p), at(t.p)), pair_of(at(s.q), at(t.q)), pair_of(at(s.r), at(t.r)));
    dest(i) = {a.x[0], a.y[0], a.z[0], 0.0};
    dest(i + 1) = {a.x[1], a.y[1], a.z[1], 0.0};
    bound[i] = {a.eV[0], a.eW[0], a.aW[0]};
    bound[i + 1] = {a.eV[1], a.eW[1], a.aW[1]};
    if (!a.usable[0]) unusable.push_back(i);
    if (!a.usable[1]) unusable.push_back(i + 1);
  }
  if (i < triples.size()) {
    const PlaneTriple t = triples[i];
    const Approximation<double> a = approximate(at(t.p), at(t.q), at(t.r));
    dest(i) = {a.x, a.y, a.z, 0.0};
    bound[i] = {a.eV, a.eW, a.aW};
    if (!a.usable) unusable.push_back(i);
  }
  for (std::size_t k = 0; k < triples.size(); ++k) {
    ApproxPoint& o = dest(k);
    const Bound& e = bound[k];
    o.err = error_bound(o.x, o.y, o.z, e.eV, e.eW, e.aW);
  }
  for (const std::size_t k : unusable) {
    const PlaneTriple t = triples[k];
    dest(k) = kernel::approximate_vertex(planes[t.p], planes[t.q], planes[t.r]);
  }
}

}  // namespace

std::vector<ApproxPoint> approximate_vertices(const kernel::PlaneTable& planes, std::span<const PlaneTriple> triples) {
  std::vector<ApproxPoint> out(triples.size());
  approximate_into(planes, triples, [&out](std::size_t i) -> ApproxPoint& { return out[i]; });
  return out;
}

std::vector<BoundaryFragment> ring_boundary(TreeBuilder& b, const std::vector<std::int32_t>& ring,
                                            const std::vector<std::vector<std::int32_t>>& face,
                                            const std::vector<double>& scale) {
  const std::size_t r = ring.size();
  const int n = int(face[0].size());
  auto wrap = [n](int j) { return std::size_t(j < 0 ? j + n : (j >= n ? j - n : j)); };  // j in [-1, n]
  std::vector<std::int32_t> below(r - 1);  // the opposite of band k's lower ring plane
  for (std::size_t k = 0; k + 1 < r; ++k) below[k] = b.add_plane(b.planes()[ring[k]].opposite());
  const kernel::PlaneTable& planes = b.planes();  // no plane is added from here on
  // First the labels: each fragment's support, flip and corner count, each corner's triple
  // (support, previous edge, edge); then the fragments; then all approximations in one batch.
  struct Label {
    std::int32_t support;
    bool flip;
    int corners;
  };
  std::vector<Label> labels;
  labels.reserve((r - 1) * std::size_t(n) + 2);
  std::vector<PlaneTriple> triples;
  triples.reserve((r - 1) * std::size_t(n) * 4 + 2 * std::size_t(n));
  for (std::size_t k = 0; k + 1 < r; ++k) {
    const std::vector<std::int32_t>& ids = face[k];
    for (int j = 0; j < n; ++j) {
      const std::int32_t prev = ids[wrap(j - 1)], next = ids[wrap(j + 1)], id = ids[std::size_t(j)];
      const std::size_t first = triples.size();
      // Counter-clockwise seen from outside: along ring k, up, back along ring k + 1, down.
      if (scale[k] > 0) {
        triples.push_back({id, prev, below[k]});
        triples.push_back({id, below[k], next});
      } else {
        triples.push_back({id, prev, next});  // the apex
      }
      if (scale[k + 1] > 0) {
        triples.push_back({id, next, ring[k + 1]});
        triples.push_back({id, ring[k + 1], prev});
      } else {
        triples.push_back({id, next, prev});
      }
      labels.push_back({id, false, int(triples.size() - first)});
    }
  }
  for (const std::size_t k : {std::size_t(0), r - 1}) {  // caps: counter-clockwise about +z
    if (!(scale[k] > 0)) continue;
    const std::vector<std::int32_t>& ids = face[k == 0 ? 0 : r - 2];
    for (int j = 0; j < n; ++j) triples.push_back({ring[k], ids[wrap(j - 1)], ids[std::size_t(j)]});
    labels.push_back({ring[k], k == 0, n});
  }
  std::vector<BoundaryFragment> faces;
  faces.reserve(labels.size());
  std::vector<ApproxPoint*> at(triples.size());  // where each corner's approximation goes
  std::size_t c = 0;
  for (const Label& l : labels) {
    // Built in place (a polygon is 272 bytes): aggregate initialization leaves the corners' inline
    // storage untouched, where value initialization would zero it.
    faces.push_back(BoundaryFragment{.polygon = {.support = l.support, .corners = {}}, .flip = l.flip});
    auto& corners = faces.back().polygon.corners;
    corners.reserve(std::size_t(l.corners));
    for (int i = 0; i < l.corners; ++i, ++c) {
      corners.push_back({triples[c].r, triples[c].q, triples[c].r, {}});
      at[c] = &corners.back().at;
    }
  }
  approximate_into(planes, triples, [&at](std::size_t i) -> ApproxPoint& { return *at[i]; });
  return faces;
}

}  // namespace sculpt::detail
