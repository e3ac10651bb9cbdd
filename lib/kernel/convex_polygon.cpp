#include "kernel/convex_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace sculpt::kernel {

namespace {

constexpr double kUnit = 1.1102230246251565e-16;  // 2^-53

// The corner of the world polygon on support s where axis u is at U and axis v at V (world box
// faces, exact in double): x_k = -(s_u U + s_v V + d) / s_k. The products are exact (U, V are
// powers of two), the two sums, d_nearest and the quotient round once each.
ApproxPoint quick_world_corner(const Plane& s, int u, int v, int k, double U, double V) {
  const double n[3] = {double(s.a), double(s.b), double(s.c)};
  const double t1 = n[u] * U, t2 = n[v] * V, d = s.d_nearest;
  const double num = t1 + t2 + d;
  const double z = -num / n[k];
  const double e_num = 3.0 * kUnit * (std::fabs(t1) + std::fabs(t2) + std::fabs(d));
  double x[3];
  x[u] = U, x[v] = V, x[k] = z;
  return {x[0], x[1], x[2], 1.01 * (e_num / std::fabs(n[k]) + 2.0 * kUnit * std::fabs(z))};
}

}  // namespace

ConvexPolygon world_polygon(const PlaneTable& planes, std::int32_t support, const WorldPolygonOptions& options) {
  const Plane& s = planes[support];
  const std::int64_t n[3] = {std::abs(s.a), std::abs(s.b), std::abs(s.c)};
  const int k = n[0] >= n[1] && n[0] >= n[2] ? 0 : (n[1] >= n[2] ? 1 : 2);
  const int u = (k + 1) % 3, v = (k + 2) % 3;  // (u, v, k) right-handed
  const bool up = (k == 0 ? s.a : (k == 1 ? s.b : s.c)) > 0;
  // Square in (u, v): edges +u, +v, -u, -v, counter-clockwise about +k.
  std::int32_t edges[4] = {2 * u, 2 * v, 2 * u + 1, 2 * v + 1};
  if (!up) std::swap(edges[1], edges[3]);  // reversed cycle: +u, -v, -u, +v
  ConvexPolygon poly;
  poly.support = support;
  const double w = double(PlaneTable::kWorld);
  for (int i = 0; i < 4; ++i) {
    const std::int32_t prev = edges[(i + 3) % 4], edge = edges[i];
    if (options.quick_corners) {
      // World plane 2 a is x_a = +w, 2 a + 1 is x_a = -w; prev and edge are one u and one v plane.
      const std::int32_t pu = prev / 2 == u ? prev : edge, pv = prev / 2 == u ? edge : prev;
      poly.corners.push_back({edge, prev, edge, quick_world_corner(s, u, v, k, pu % 2 ? -w : w, pv % 2 ? -w : w)});
    } else {
      poly.corners.push_back({edge, prev, edge, approximate_vertex(s, planes[prev], planes[edge])});
    }
  }
  return poly;
}

void refresh_world_corners(const PlaneTable& planes, ConvexPolygon& poly) {
  for (Corner& c : poly.corners)
    if (c.p < kWorldPlanes && c.q < kWorldPlanes)
      c.set_at(approximate_vertex(planes[poly.support], planes[c.p], planes[c.q]));
}

CornerBox corner_box(PolygonView poly) {
  CornerBox b;
  if (poly.corners.empty()) return b;
  for (int i = 0; i < 3; ++i) b.lo[i] = 1e300, b.hi[i] = -1e300;
  for (const Corner& c : poly.corners) {
    if (c.at().err < 0) return CornerBox{};  // unknown: use the predicates
    const double v[3] = {c.at().x, c.at().y, c.at().z};
    for (int i = 0; i < 3; ++i) {
      b.lo[i] = std::min(b.lo[i], v[i] - c.at().err);
      b.hi[i] = std::max(b.hi[i], v[i] + c.at().err);
    }
  }
  b.valid = true;
  return b;
}

namespace {

Side box_side(PolygonView poly, const Plane& s) { return box_side(corner_box(poly), s); }

template <typename F>
void signs_of(const PlaneTable& planes, PolygonView poly, std::int32_t plane, F&& f) {
  const Plane& s = planes[poly.support];
  const Plane cut = planes[plane];  // a copy: f's stores may alias a reference
  std::uint64_t decided = 0;  // filter decisions inline (orient's own filter, counted at the end)
  for (const Corner& c : poly.corners) {
    const Sign quick = filtered_orient(c.at(), cut);
    if (quick != Sign::Zero) {
      ++decided;
      f(quick);
    } else {
      f(orient(s, planes[c.p], planes[c.q], c.at(), cut));
    }
  }
  predicate_counters().filtered += decided;
}

}  // namespace

Side classify(const PlaneTable& planes, PolygonView poly, std::int32_t plane) {
  const Side quick = box_side(poly, planes[plane]);
  if (quick != Side::Both) return quick;
  bool neg = false, pos = false;
  signs_of(planes, poly, plane, [&](Sign g) {
    neg |= g == Sign::Negative;
    pos |= g == Sign::Positive;
  });
  return neg ? (pos ? Side::Both : Side::Negative) : (pos ? Side::Positive : Side::On);
}

Side split(const PlaneTable& planes, PolygonView poly, std::int32_t cut, std::int32_t cut_opposite,
           ConvexPolygon& negative, ConvexPolygon& positive) {
  // No corner-box test first (classify() has one): the box costs a pass over the corners like the
  // filtered signs it would spare, and when it is undecided the signs are needed as well (5 % fewer
  // instructions for the merge of two spheres without it). The sides are the same either way.
  const std::size_t k = poly.corners.size();
  boost::container::small_vector<Sign, 8> s;
  bool neg = false, pos = false;
  signs_of(planes, poly, cut, [&](Sign g) {
    s.push_back(g);
    neg |= g == Sign::Negative;
    pos |= g == Sign::Positive;
  });
  const Side side = neg ? (pos ? Side::Both : Side::Negative) : (pos ? Side::Positive : Side::On);
  if (side != Side::Both) return side;

  negative.support = positive.support = poly.support;
  negative.corners.clear();
  positive.corners.clear();
  const Plane& support = planes[poly.support];
  for (std::size_t i = 0; i < k; ++i) {
    const Corner& c = poly.corners[i];
    const Sign si = s[i], sj = s[(i + 1) % k];
    if (si != Sign::Positive)  // corner kept in the negative part
      negative.corners.push_back(si == Sign::Zero && sj == Sign::Positive ? Corner{cut, c.p, c.q, c.at()} : c);
    if (si != Sign::Negative)
      positive.corners.push_back(si == Sign::Zero && sj == Sign::Negative ? Corner{cut_opposite, c.p, c.q, c.at()} : c);
    const bool crosses = (si == Sign::Negative && sj == Sign::Positive) ||
                         (si == Sign::Positive && sj == Sign::Negative);
    if (!crosses) continue;
    const ApproxPoint at = approximate_vertex(support, planes[c.edge], planes[cut]);
    if (si == Sign::Negative) {
      negative.corners.push_back({cut, c.edge, cut, at});
      positive.corners.push_back({c.edge, c.edge, cut, at});
    } else {
      positive.corners.push_back({cut_opposite, c.edge, cut, at});
      negative.corners.push_back({c.edge, c.edge, cut, at});
    }
  }
  return Side::Both;
}

PolygonSplit split(const PlaneTable& planes, PolygonView poly, std::int32_t cut, std::int32_t cut_opposite) {
  PolygonSplit out;
  out.side = split(planes, poly, cut, cut_opposite, out.negative, out.positive);
  return out;
}

namespace {

void extend(CornerBox& b, const ApproxPoint& at) {
  const double v[3] = {at.x, at.y, at.z};
  for (int i = 0; i < 3; ++i) {
    b.lo[i] = std::min(b.lo[i], v[i] - at.err);
    b.hi[i] = std::max(b.hi[i], v[i] + at.err);
  }
}

}  // namespace

Side clip_to_negative_exact(const PlaneTable& planes, PolygonView in, ConvexPolygon& out, CornerBox& box,
                            std::int32_t cut) {
  const Plane c = planes[cut];  // a copy: the sign stores below may alias a reference
  const std::size_t k = in.corners.size();
  boost::container::small_vector<Sign, 16> s(k);
  bool neg = false, pos = false;
  std::uint64_t decided = 0;
  const Plane& support = planes[in.support];
  for (std::size_t i = 0; i < k; ++i) {
    const Corner& corner = in.corners[i];
    Sign g = filtered_orient(corner.at(), c);
    if (g != Sign::Zero)
      ++decided;
    else
      g = orient(support, planes[corner.p], planes[corner.q], corner.at(), c);
    s[i] = g;
    neg |= g == Sign::Negative;
    pos |= g == Sign::Positive;
  }
  predicate_counters().filtered += decided;
  if (!(neg && pos)) return neg ? Side::Negative : (pos ? Side::Positive : Side::On);

  // The negative part of split(), same order and labels; the box follows the kept corners.
  out.support = in.support;
  out.corners.clear();
  CornerBox b;
  for (int i = 0; i < 3; ++i) b.lo[i] = 1e300, b.hi[i] = -1e300;
  bool valid = true;
  auto push = [&](const Corner& corner) {
    out.corners.push_back(corner);
    if (corner.at().err < 0)
      valid = false;
    else
      extend(b, corner.at());
  };
  for (std::size_t i = 0; i < k; ++i) {
    const Corner& corner = in.corners[i];
    const Sign si = s[i], sj = s[i + 1 == k ? 0 : i + 1];
    if (si != Sign::Positive)
      push(si == Sign::Zero && sj == Sign::Positive ? Corner{cut, corner.p, corner.q, corner.at()} : corner);
    if (si == Sign::Negative ? sj == Sign::Positive : (si == Sign::Positive && sj == Sign::Negative)) {
      const ApproxPoint at = approximate_vertex(support, planes[corner.edge], c);
      push(si == Sign::Negative ? Corner{cut, corner.edge, cut, at} : Corner{corner.edge, corner.edge, cut, at});
    }
  }
  b.valid = valid;
  box = valid ? b : CornerBox{};
  return Side::Both;
}

std::vector<Eigen::Vector3d> approximate_corners(PolygonView poly) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(poly.corners.size());
  for (const Corner& c : poly.corners) out.emplace_back(c.at().x, c.at().y, c.at().z);
  return out;
}

}  // namespace sculpt::kernel
