#include "bsp/rings/ring_boundary.hpp"

#include "base/cancel.hpp"

#include "kernel/vertex_approximation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sculpt::bsp::detail {

using kernel::ApproxPoint;
using kernel::Plane;

namespace {

// The arithmetic of approximate_vertex, for doubles and for pairs of doubles (the same bits).
using namespace kernel::approximation;

// Approximations of vertices given as triples of one plane table's planes: the normals are
// converted once; each call takes blocks small enough to stay in the L1 cache, first the
// coordinates of the block's corners, two at a time, then their error bounds, and at the end the
// kernel's approximation where planes are nearly dependent.
class Approximator {
 public:
  explicit Approximator(const kernel::PlaneTable& planes) : planes_(planes), normal_(std::size_t(planes.size())) {
    for (std::int32_t i = 0; i < planes.size(); ++i) normal_[std::size_t(i)] = normal_of(planes[i]);
  }

  void operator()(std::span<const VertexPlanes> triples, std::span<ApproxPoint> out) {
    unusable_.clear();
    for (std::size_t first = 0; first < triples.size(); first += kBlock) {
      const std::size_t end = std::min(triples.size(), first + kBlock);
      std::size_t i = first;
      for (; i + 1 < end; i += 2) {
        const VertexPlanes s = triples[i], t = triples[i + 1];
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
        const VertexPlanes t = triples[i];
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
      const VertexPlanes t = triples[k];
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

std::vector<ApproxPoint> approximate_vertices(const kernel::PlaneTable& planes, std::span<const VertexPlanes> triples) {
  std::vector<ApproxPoint> out(triples.size());
  Approximator approximate(planes);
  approximate(triples, out);
  return out;
}

FragmentList ring_boundary(TreeBuilder& b, const std::vector<std::int32_t>& ring,
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
  std::vector<VertexPlanes> triples;
  std::vector<ApproxPoint> at;
  FragmentList faces;
  faces.reserve((r - 1) * std::size_t(n) + 2);
  kernel::ConvexPolygon poly;  // scratch: each fragment is copied into the list's compact storage
  auto fragments = [&](std::int32_t support, bool flip, std::size_t corners) {  // `corners` triples each
    at.resize(triples.size());
    approximate(triples, at);
    for (std::size_t c = 0; c < triples.size();) {
      poly.support = support < 0 ? triples[c].p : support;
      poly.corners.clear();
      for (const std::size_t end = c + corners; c < end; ++c)
        poly.corners.push_back({triples[c].r, triples[c].q, triples[c].r, at[c]});  // edge, p, q, approximation
      faces.push_back(poly, flip);
    }
  };
  CancelPoll poll;  // Ctrl-C and the memory limit (base/cancel.hpp): a fine revolution's bands are many
  for (std::size_t k = 0; k + 1 < r; ++k) {
    poll.tick(std::uint32_t(n));
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

}  // namespace sculpt::bsp::detail
