#include "bsp/assembly/faces.hpp"

#include <algorithm>
#include <bit>

namespace sculpt::bsp::detail {

using kernel::Plane;

namespace {

std::uint64_t plane_hash(const Plane& p) {
  std::uint64_t h = std::uint64_t(p.a) * 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 29)) + std::uint64_t(p.b) * 0xC2B2AE3D27D4EB4Full;
  h = (h ^ (h >> 31)) + std::uint64_t(p.c) * 0x165667B19E3779F9ull;
  h = (h ^ (h >> 27)) + std::uint64_t(p.d) * 0x27D4EB2F165667C5ull + std::uint64_t(p.d >> 64);
  return h ^ (h >> 33);
}

}  // namespace

PlaneIds canonical_plane_ids(const kernel::PlaneTable& planes) {
  const std::size_t n = std::size_t(planes.size());
  PlaneIds r;
  r.id.resize(n);
  r.negated.resize(n);
  // Open addressing over the normalized planes (sign fixed by the first non-zero coefficient),
  // planes read in order; the probes are random, so the slot of the plane a few ahead is
  // prefetched.
  std::size_t slots = 16;
  while (slots < 2 * n) slots *= 2;
  const std::size_t mask = slots - 1;
  std::vector<std::int32_t> table(slots, -1);  // slot -> plane index of the id's representative
  auto negative = [](const Plane& p) { return p.a < 0 || (p.a == 0 && (p.b < 0 || (p.b == 0 && p.c < 0))); };
  auto home = [&](std::size_t i) {
    const Plane& p = planes[std::int32_t(i)];
    return std::size_t(plane_hash(negative(p) ? p.opposite() : p)) & mask;
  };
  constexpr std::size_t kAhead = 8;
  std::size_t homes[kAhead];
  for (std::size_t i = 0; i < std::min(n, kAhead); ++i) homes[i] = home(i);
  std::uint32_t ids = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t h = homes[i % kAhead];
    if (i + kAhead < n) {
      homes[i % kAhead] = home(i + kAhead);
      __builtin_prefetch(&table[homes[i % kAhead]]);
    }
    const Plane& p = planes[std::int32_t(i)];
    const bool neg = negative(p);
    r.negated[i] = neg ? 1 : 0;
    // Equal up to orientation: the same plane when the signs agree, else the opposite.
    auto same = [&](std::int32_t j) {
      const Plane& q = planes[j];
      return r.negated[std::size_t(j)] == r.negated[i] ? q == p
                                                        : (q.a == -p.a && q.b == -p.b && q.c == -p.c && q.d == -p.d);
    };
    while (table[h] >= 0 && !same(table[h])) h = (h + 1) & mask;
    if (table[h] < 0) {
      table[h] = std::int32_t(i);
      r.id[i] = ids++;
    } else {
      r.id[i] = r.id[std::size_t(table[h])];
    }
  }
  return r;
}

void FaceList::reserve(std::size_t faces, std::size_t corner_count) {
  start.reserve(faces + 1);
  support.reserve(faces);
  flip.reserve(faces);
  vertex.reserve(corner_count);
  line.reserve(corner_count);
}

void FaceList::open_face(std::int32_t support_plane, bool flipped) {
  support.push_back(support_plane);
  flip.push_back(flipped ? 1 : 0);
  start.push_back(int(vertex.size()));
}

void FaceList::add_corner(int v, std::int32_t edge_line) {
  vertex.push_back(v);
  line.push_back(edge_line);
  ++start.back();
}

void FaceList::drop_last_face() {
  const auto begin = std::size_t(start[start.size() - 2]);
  vertex.resize(begin);
  line.resize(begin);
  start.pop_back();
  support.pop_back();
  flip.pop_back();
}

void FaceList::copy_face(const FaceList& other, int f) {
  open_face(other.support[std::size_t(f)], other.flip[std::size_t(f)] != 0);
  const auto b = std::ptrdiff_t(other.begin(f)), e = std::ptrdiff_t(other.end(f));
  vertex.insert(vertex.end(), other.vertex.begin() + b, other.vertex.begin() + e);
  line.insert(line.end(), other.line.begin() + b, other.line.begin() + e);
  start.back() += int(e - b);
}

OutgoingEdges::OutgoingEdges(const FaceList& faces, int vertex_count)
    : start_(std::size_t(vertex_count) + 1, 0), out_(faces.vertex.size()) {
  // Counting sort; each run filled from its end (no fill array), faces backwards so that each
  // run keeps the corner order.
  for (const int v : faces.vertex) ++start_[std::size_t(v)];
  for (std::size_t v = 0; v < std::size_t(vertex_count); ++v) start_[v + 1] += start_[v];
  for (int f = faces.size() - 1; f >= 0; --f)
    for (int c = faces.end(f) - 1; c >= faces.begin(f); --c)
      out_[std::size_t(--start_[std::size_t(faces.vertex[std::size_t(c)])])] = {faces.vertex[std::size_t(faces.next(f, c))], c};
}

EdgeIndex::EdgeIndex(std::size_t values) : next_(values, -1) {
  std::size_t slots = 16;
  while (slots < 2 * values) slots *= 2;
  slots_.assign(slots, Slot{0, -1});
  shift_ = 64 - std::countr_zero(slots);
}

void EdgeIndex::insert(std::uint64_t key, int value) {
  const std::size_t mask = slots_.size() - 1;
  std::size_t h = home(key);
  while (slots_[h].head >= 0 && slots_[h].key != key) h = (h + 1) & mask;
  next_[std::size_t(value)] = slots_[h].head;
  slots_[h] = {key, value};
}

int EdgeIndex::find(std::uint64_t key) const {
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t h = home(key);; h = (h + 1) & mask) {
    if (slots_[h].head < 0) return -1;
    if (slots_[h].key == key) return slots_[h].head;
  }
}

namespace {

using Big = boost::multiprecision::int512_t;

Big big(kernel::Int128 v) {  // from 64-bit halves (portable)
  __extension__ typedef unsigned __int128 U;
  const bool neg = v < 0;
  const U m = neg ? U(0) - U(v) : U(v);
  Big r = Big(std::uint64_t(m >> 64));
  r <<= 64;
  r += Big(std::uint64_t(m));
  return neg ? Big(-r) : r;
}

// Exact homogeneous coordinate `axis` and weight of the vertex p ∩ q ∩ r (Cramer's rule, as
// kernel::exact_vertex, directly in 512 bits so that products of two of them fit).
std::pair<Big, Big> homogeneous(const Plane& p, const Plane& q, const Plane& r, int axis) {
  using kernel::Int128;
  auto cross = [axis](const Plane& x, const Plane& y) {
    return axis == 0 ? Int128(x.b) * y.c - Int128(x.c) * y.b
                     : (axis == 1 ? Int128(x.c) * y.a - Int128(x.a) * y.c : Int128(x.a) * y.b - Int128(x.b) * y.a);
  };
  const Int128 ux = Int128(q.b) * r.c - Int128(q.c) * r.b, uy = Int128(q.c) * r.a - Int128(q.a) * r.c,
               uz = Int128(q.a) * r.b - Int128(q.b) * r.a;
  const Big w = big(ux) * p.a + big(uy) * p.b + big(uz) * p.c;
  const Big x = -(big(p.d) * big(cross(q, r)) + big(q.d) * big(cross(r, p)) + big(r.d) * big(cross(p, q)));
  return {x, w};
}

}  // namespace

bool VertexGeometry::on_plane(int v, std::int32_t plane) const {
  if (std::size_t(v) < v_.on_grid.size() && v_.on_grid[std::size_t(v)] != 0) {  // exact in Int128 (kernel/plane.hpp)
    const kernel::ApproxPoint& a = v_.at[std::size_t(v)];
    return planes_[plane].eval({std::int64_t(a.x), std::int64_t(a.y), std::int64_t(a.z)}) == 0;
  }
  const std::uint32_t id = ids_.id[std::size_t(plane)];
  if (std::size_t(v) < v_.first_class.size()) {
    for (int k = v_.first_class[std::size_t(v)]; k >= 0; k = v_.class_next[std::size_t(k)]) {
      const IdTriple& t = v_.class_planes[std::size_t(k)];
      if (t[0] == id || t[1] == id || t[2] == id) return true;
    }
  }
  const PlaneTriple& t = v_.triple[std::size_t(v)];
  return kernel::orient(planes_[t.s], planes_[t.p], planes_[t.q], v_.at[std::size_t(v)], planes_[plane]) ==
         kernel::Sign::Zero;
}

int VertexGeometry::line_axis(std::int32_t support, std::int32_t edge) const {
  // The exact direction n_support x n_edge (integers below 2^107, so the double of the largest
  // component is non-zero and the comparison of magnitudes is exact enough to pick a non-zero one).
  const Plane& p = planes_[support];
  const Plane& q = planes_[edge];
  using kernel::Int128;
  const Int128 c[3] = {Int128(p.b) * q.c - Int128(p.c) * q.b, Int128(p.c) * q.a - Int128(p.a) * q.c,
                       Int128(p.a) * q.b - Int128(p.b) * q.a};
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if ((c[k] < 0 ? -c[k] : c[k]) > (c[axis] < 0 ? -c[axis] : c[axis])) axis = k;
  return axis;
}

bool VertexGeometry::less_along(int a, int b, int axis) const {
  const kernel::ApproxPoint& pa = v_.at[std::size_t(a)];
  const kernel::ApproxPoint& pb = v_.at[std::size_t(b)];
  const double xa = axis == 0 ? pa.x : (axis == 1 ? pa.y : pa.z);
  const double xb = axis == 0 ? pb.x : (axis == 1 ? pb.y : pb.z);
  if (pa.err >= 0 && pb.err >= 0) {  // the approximations decide when their error boxes are apart
    const double gap = pa.err + pb.err;
    if (xa + gap < xb) return true;
    if (xb + gap < xa) return false;
  }
  // Exact: x_a / w_a < x_b / w_b with the homogeneous coordinates (products below 2^512).
  const PlaneTriple& ta = v_.triple[std::size_t(a)];
  const PlaneTriple& tb = v_.triple[std::size_t(b)];
  const auto [ya, wa] = homogeneous(planes_[ta.s], planes_[ta.p], planes_[ta.q], axis);
  const auto [yb, wb] = homogeneous(planes_[tb.s], planes_[tb.p], planes_[tb.q], axis);
  const Big l = ya * wb, r = yb * wa;
  return (wa.sign() * wb.sign() > 0) ? l < r : l > r;
}

bool VertexGeometry::between(int u, int c, int w, int axis) const {
  return less_along(u, w, axis) ? (less_along(u, c, axis) && less_along(c, w, axis))
                                : (less_along(w, c, axis) && less_along(c, u, axis));
}

}  // namespace sculpt::bsp::detail
