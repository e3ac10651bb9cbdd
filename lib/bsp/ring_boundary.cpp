#include "bsp/ring_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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
  constexpr std::int64_t kMagnitude = std::numeric_limits<std::int64_t>::max();
  return Pair(PairMask(v) & PairMask{kMagnitude, kMagnitude});
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

// Approximations of vertices given as triples of one plane table's planes: the normals are
// converted once; each call takes blocks small enough to stay in the L1 cache, first the
// coordinates of the block's corners, two at a time, then their error bounds, and at the end the
// kernel's approximation where planes are nearly dependent.
class Approximator {
 public:
  explicit Approximator(const kernel::PlaneTable& planes) : planes_(planes), normal_(std::size_t(planes.size())) {
    for (std::int32_t i = 0; i < planes.size(); ++i) normal_[std::size_t(i)] = normal_of(planes[i]);
  }

  void operator()(std::span<const PlaneTriple> triples, std::span<ApproxPoint> out) {
    unusable_.clear();
    for (std::size_t first = 0; first < triples.size(); first += kBlock) {
      const std::size_t end = std::min(triples.size(), first + kBlock);
      std::size_t i = first;
      for (; i + 1 < end; i += 2) {
        const PlaneTriple s = triples[i], t = triples[i + 1];
        const Approximation<Pair> a =
            approximate(pair_of(at(s.p), at(t.p)), pair_of(at(s.q), at(t.q)), pair_of(at(s.r), at(t.r)));
        out[i] = {a.x[0], a.y[0], a.z[0], 0.0};
        out[i + 1] = {a.x[1], a.y[1], a.z[1], 0.0};
        bound_[i - first] = {a.eV[0], a.eW[0], a.aW[0]};
        bound_[i + 1 - first] = {a.eV[1], a.eW[1], a.aW[1]};
        if (!a.usable[0]) unusable_.push_back(i);
        if (!a.usable[1]) unusable_.push_back(i + 1);
      }
      if (i < end) {
        const PlaneTriple t = triples[i];
        const Approximation<double> a = approximate(at(t.p), at(t.q), at(t.r));
        out[i] = {a.x, a.y, a.z, 0.0};
        bound_[i - first] = {a.eV, a.eW, a.aW};
        if (!a.usable) unusable_.push_back(i);
      }
      for (std::size_t k = first; k < end; ++k) {
        ApproxPoint& o = out[k];
        const Bound& e = bound_[k - first];
        o.err = error_bound(o.x, o.y, o.z, e.eV, e.eW, e.aW);
      }
    }
    for (const std::size_t k : unusable_) {
      const PlaneTriple t = triples[k];
      out[k] = kernel::approximate_vertex(planes_[t.p], planes_[t.q], planes_[t.r]);
    }
  }

 private:
  static constexpr std::size_t kBlock = 128;  // even: pairs never straddle two blocks
  struct Bound {
    double eV, eW, aW;
  };
  const Normal<double>& at(std::int32_t i) const { return normal_[std::size_t(i)]; }

  const kernel::PlaneTable& planes_;
  std::vector<Normal<double>> normal_;
  Bound bound_[kBlock];
  std::vector<std::size_t> unusable_;
};

}  // namespace

std::vector<ApproxPoint> approximate_vertices(const kernel::PlaneTable& planes, std::span<const PlaneTriple> triples) {
  std::vector<ApproxPoint> out(triples.size());
  Approximator approximate(planes);
  approximate(triples, out);
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
  // Band by band (and cap by cap): each corner's triple (support, previous edge, edge), their
  // approximations in one batch, then the band's fragments, each written once.
  Approximator approximate(planes);
  std::vector<PlaneTriple> triples;
  std::vector<ApproxPoint> at;
  std::vector<BoundaryFragment> faces;
  faces.reserve((r - 1) * std::size_t(n) + 2);
  auto fragments = [&](std::int32_t support, bool flip, std::size_t corners) {  // `corners` triples each
    at.resize(triples.size());
    approximate(triples, at);
    for (std::size_t c = 0; c < triples.size();) {
      // Built in place (a polygon is 272 bytes): aggregate initialization leaves the corners'
      // inline storage untouched, where value initialization would zero it.
      faces.push_back(BoundaryFragment{.polygon = {.support = support < 0 ? triples[c].p : support, .corners = {}},
                                       .flip = flip});
      auto& poly = faces.back().polygon.corners;
      poly.reserve(corners);
      for (const std::size_t end = c + corners; c < end; ++c)
        poly.push_back({triples[c].r, triples[c].q, triples[c].r, at[c]});  // edge, p, q, approximation
    }
  };
  for (std::size_t k = 0; k + 1 < r; ++k) {
    const std::vector<std::int32_t>& ids = face[k];
    triples.clear();
    for (int j = 0; j < n; ++j) {
      const std::int32_t prev = ids[wrap(j - 1)], next = ids[wrap(j + 1)], id = ids[std::size_t(j)];
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
    }
    fragments(-1, false, triples.size() / std::size_t(n));  // each face's own plane
  }
  for (const std::size_t k : {std::size_t(0), r - 1}) {  // caps: counter-clockwise about +z
    if (!(scale[k] > 0)) continue;
    const std::vector<std::int32_t>& ids = face[k == 0 ? 0 : r - 2];
    triples.clear();
    for (int j = 0; j < n; ++j) triples.push_back({ring[k], ids[wrap(j - 1)], ids[std::size_t(j)]});
    fragments(ring[k], k == 0, std::size_t(n));
  }
  return faces;
}

}  // namespace sculpt::detail
