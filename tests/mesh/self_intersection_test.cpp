// The self-intersection search against independent references: the triangle-pair decision
// against segment-triangle tests in rational arithmetic (on lattice triangles, many of them
// coplanar or touching), and the grid broad phase against all pairs of faces.
#include "mesh/self_intersection.hpp"

#include <gtest/gtest.h>

#include "support/rational_orientation.hpp"

#include <algorithm>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <numeric>
#include <random>
#include <set>

#include "base/parallel.hpp"
#include "mesh/detail/box_grid.hpp"
#include "mesh/detail/point_copies.hpp"
#include "mesh/triangulate.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

using boost::multiprecision::cpp_rational;
using Eigen::Vector3d;
using Triangle = std::array<Vector3d, 3>;

int sign3(const Vector3d& a, const Vector3d& b, const Vector3d& c, const Vector3d& d) { return checks::rational_orient3d(a, b, c, d); }

/// Rational point of a segment and a closed triangle (any position), by the parameter of the
/// segment: the closed segment meets the triangle iff some point s0 + t (s1 - s0), t in [0, 1],
/// lies in it. Coplanar case: the segment meets the triangle iff an endpoint is inside or it
/// crosses an edge; decided by 2D orientations on the exact rational projection.
struct Q3 {
  cpp_rational x[3];
};
Q3 q(const Vector3d& v) { return {{v.x(), v.y(), v.z()}}; }
int sign2(const Q3& a, const Q3& b, const Q3& c, int u, int v) {
  const cpp_rational det = (b.x[u] - a.x[u]) * (c.x[v] - a.x[v]) - (b.x[v] - a.x[v]) * (c.x[u] - a.x[u]);
  return det.sign();
}
bool on_segment_2d(const Q3& a, const Q3& b, const Q3& p, int u, int v) {
  return sign2(a, b, p, u, v) == 0 && std::min(a.x[u], b.x[u]) <= p.x[u] && p.x[u] <= std::max(a.x[u], b.x[u]) &&
         std::min(a.x[v], b.x[v]) <= p.x[v] && p.x[v] <= std::max(a.x[v], b.x[v]);
}
bool segments_meet_2d(const Q3& a, const Q3& b, const Q3& c, const Q3& d, int u, int v) {
  const int o1 = sign2(a, b, c, u, v), o2 = sign2(a, b, d, u, v), o3 = sign2(c, d, a, u, v), o4 = sign2(c, d, b, u, v);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return on_segment_2d(a, b, c, u, v) || on_segment_2d(a, b, d, u, v) || on_segment_2d(c, d, a, u, v) ||
         on_segment_2d(c, d, b, u, v);
}
bool in_triangle_2d(const Q3& p, const Triangle& t, int u, int v) {
  const int a = sign2(q(t[0]), q(t[1]), p, u, v), b = sign2(q(t[1]), q(t[2]), p, u, v), c = sign2(q(t[2]), q(t[0]), p, u, v);
  return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
}
int projection(const Triangle& t) {
  for (int axis = 0; axis < 3; ++axis)
    if (sign2(q(t[0]), q(t[1]), q(t[2]), (axis + 1) % 3, (axis + 2) % 3) != 0) return axis;
  return -1;
}
bool segment_meets_triangle(const Vector3d& s0, const Vector3d& s1, const Triangle& t) {
  const int o0 = sign3(t[0], t[1], t[2], s0), o1 = sign3(t[0], t[1], t[2], s1);
  if (o0 * o1 > 0) return false;
  const int axis = projection(t), u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (o0 == 0 && o1 == 0)
    return in_triangle_2d(q(s0), t, u, v) || in_triangle_2d(q(s1), t, u, v) ||
           segments_meet_2d(q(s0), q(s1), q(t[0]), q(t[1]), u, v) || segments_meet_2d(q(s0), q(s1), q(t[1]), q(t[2]), u, v) ||
           segments_meet_2d(q(s0), q(s1), q(t[2]), q(t[0]), u, v);
  // The point where the segment reaches the plane, exactly, then inside the triangle there.
  const Q3 a = q(s0), b = q(s1);
  // Signed volumes are linear along the segment: t* = o(s0) / (o(s0) - o(s1)) with exact volumes.
  auto volume = [&](const Q3& p) -> cpp_rational {
    cpp_rational m[3][3];
    for (int k = 0; k < 3; ++k) {
      m[0][k] = cpp_rational(t[1][k]) - t[0][k];
      m[1][k] = cpp_rational(t[2][k]) - t[0][k];
      m[2][k] = p.x[k] - t[0][k];
    }
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const cpp_rational va = volume(a), vb = volume(b);
  const cpp_rational s = va / (va - vb);
  Q3 p;
  for (int k = 0; k < 3; ++k) p.x[k] = a.x[k] + s * (b.x[k] - a.x[k]);
  return in_triangle_2d(p, t, u, v);
}
bool reference_meet(const Triangle& a, const Triangle& b) {
  for (int k = 0; k < 3; ++k)
    if (segment_meets_triangle(a[k], a[(k + 1) % 3], b) || segment_meets_triangle(b[k], b[(k + 1) % 3], a)) return true;
  return false;
}

TEST(SelfIntersection, TrianglePairsWithoutSharedCornersAgreeWithRationals) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> coord(0, 4), pick(0, 4);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Vector3d origin(0.3, -0.7, 0.1), e1 = Vector3d(1, 0.37, -0.21) / 3, e2 = Vector3d(-0.13, 1, 0.29) / 3;
  int met = 0, apart = 0, coplanar = 0, near_plane = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const int mode = pick(rng);
    auto point = [&] {  // mode 4: rounded points of a tilted plane (nearly coplanar)
      return mode == 4 ? Vector3d(origin + unit(rng) * e1 + unit(rng) * e2) : Vector3d(coord(rng), coord(rng), coord(rng));
    };
    Triangle a = {point(), point(), point()}, b = {point(), point(), point()};
    if (mode == 0) for (auto* t : {&a, &b}) for (auto& p : *t) p.z() = 1;  // both in the plane z = 1
    if (mode == 1)  // b in a's (tilted) plane: lattice combinations of a's corners
      for (auto& p : b) p = a[0] + (coord(rng) - 2) * (a[1] - a[0]) / 2 + (coord(rng) - 2) * (a[2] - a[0]) / 2;
    if (projection(a) < 0 || projection(b) < 0) continue;  // degenerate triangles are not judged
    bool shared = false;
    for (const auto& p : a)
      for (const auto& r : b) shared = shared || p == r;
    if (shared) continue;  // corners at one point are the same corner: another branch
    const bool expected = reference_meet(a, b);
    const bool got = triangles_meet({0, 1, 2}, a, {3, 4, 5}, b);
    ASSERT_EQ(got, expected) << trial << ": " << a[0].transpose() << " | " << a[1].transpose() << " | "
                             << a[2].transpose() << " vs " << b[0].transpose() << " | " << b[1].transpose() << " | "
                             << b[2].transpose();
    (got ? met : apart)++;
    near_plane += mode == 4 ? 1 : 0;
    coplanar += sign3(a[0], a[1], a[2], b[0]) == 0 && sign3(a[0], a[1], a[2], b[1]) == 0 &&
                sign3(a[0], a[1], a[2], b[2]) == 0;
  }
  EXPECT_GT(met, 800);
  EXPECT_GT(apart, 800);
  EXPECT_GT(coplanar, 800);
  EXPECT_GT(near_plane, 1500);
}

// Triangle pairs with one common corner p, or a common edge, against the rational reference:
// beyond p, two triangles meet iff the edge opposite p in one meets the other (the ray from p
// through a common point leaves the shorter of the two through its opposite edge, inside the
// other); beyond a common edge pq, iff they are coplanar with the third corners on one side. The
// corners are lattice points (many coplanar) or points of a tilted plane rounded to doubles
// (nearly coplanar: where the floating-point filter cannot decide and triangles_meet first tries
// projections that separate the triangles).
TEST(SelfIntersection, TrianglePairsWithSharedCornersAgreeWithRationals) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> coord(0, 4), pick(0, 2);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Vector3d origin(0.3, -0.7, 0.1), e1 = Vector3d(1, 0.37, -0.21) / 3, e2 = Vector3d(-0.13, 1, 0.29) / 3;
  int met[2] = {0, 0}, apart[2] = {0, 0}, near_plane = 0;
  for (int trial = 0; trial < 16000; ++trial) {
    const int mode = pick(rng);
    auto point = [&]() -> Vector3d {
      if (mode == 0) return Vector3d(coord(rng), coord(rng), coord(rng));
      if (mode == 1) return Vector3d(coord(rng), coord(rng), 1);  // all in the plane z = 1
      return origin + unit(rng) * e1 + unit(rng) * e2;   // rounded points of a tilted plane
    };
    const bool edge = trial % 2 == 1;
    const Vector3d p = point(), r = point(), a1 = point(), a2 = point(), b2 = point();
    Triangle a, b;
    std::array<int, 3> ia, ib;
    if (edge) {  // s = (p, r, a1), t = (r, p, b2): common edge pr
      a = {p, r, a1}, b = {r, p, b2}, ia = {0, 1, 2}, ib = {1, 0, 3};
    } else {  // s = (p, a1, a2), t = (p, r, b2): common corner p
      a = {p, a1, a2}, b = {p, r, b2}, ia = {0, 1, 2}, ib = {0, 3, 4};
    }
    if (projection(a) < 0 || projection(b) < 0) continue;  // degenerate triangles are not judged
    int coincident = 0;  // corners at one point are one corner: only the ones given as shared
    for (const auto& x : a)
      for (const auto& y : b) coincident += x == y ? 1 : 0;
    if (coincident != (edge ? 2 : 1)) continue;
    bool expected = false;
    if (edge) {
      const int ua = projection(a), u = (ua + 1) % 3, v = (ua + 2) % 3;
      expected = sign3(p, r, a1, b2) == 0 && sign2(q(p), q(r), q(a1), u, v) == sign2(q(p), q(r), q(b2), u, v);
    } else {
      expected = segment_meets_triangle(a[1], a[2], b) || segment_meets_triangle(b[1], b[2], a);
    }
    const bool got = triangles_meet(ia, a, ib, b);
    ASSERT_EQ(got, expected) << trial << (edge ? " edge: " : " corner: ") << a[0].transpose() << " | "
                             << a[1].transpose() << " | " << a[2].transpose() << " vs " << b[0].transpose() << " | "
                             << b[1].transpose() << " | " << b[2].transpose();
    (got ? met : apart)[edge ? 1 : 0]++;
    near_plane += mode == 2 ? 1 : 0;
  }
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(met[k], 300) << k;
    EXPECT_GT(apart[k], 1000) << k;
  }
  EXPECT_GT(near_plane, 3000);
}

/// All pairs of faces that meet, by every pair of their triangles (no broad phase).
std::set<std::pair<int, int>> all_pairs(const PolygonMesh& m) {
  std::vector<std::vector<IndexTriangle>> tris;
  for (const auto& f : m.faces) {
    tris.push_back({});
    for (const IndexTriangle& t : triangulate_polygon(m.vertices, f))  // degenerate ones left out
      if (projection({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]}) >= 0) tris.back().push_back(t);
  }
  std::set<std::pair<int, int>> out;
  for (size_t i = 0; i < m.faces.size(); ++i)
    for (size_t j = i + 1; j < m.faces.size(); ++j)
      for (const auto& s : tris[i])
        for (const auto& t : tris[j]) {
          const Triangle a = {m.vertices[s[0]], m.vertices[s[1]], m.vertices[s[2]]};
          const Triangle b = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
          if (triangles_meet({s[0], s[1], s[2]}, a, {t[0], t[1], t[2]}, b)) out.insert({int(i), int(j)});
        }
  return out;
}

TEST(SelfIntersection, GridBroadPhaseFindsEveryPair) {
  // Overlapping spheres and tori of very different triangle sizes, and a long thin box through them.
  std::vector<PolygonMesh> cases;
  PolygonMesh s = test_shapes::uv_sphere(12);
  PolygonMesh t = test_shapes::torus(16, 6, 1.2, 0.3);
  for (auto& p : t.vertices) p += Vector3d(0.5, 0.25, 0.125);
  cases.push_back(test_shapes::merged(s, t));
  cases.push_back(test_shapes::merged(test_shapes::merged(s, t), test_shapes::box({-3, -0.1, -0.1}, {3, 0.1, 0.1})));
  PolygonMesh big = test_shapes::uv_sphere(6, 5);
  PolygonMesh small = test_shapes::uv_sphere(16, 0.5);
  for (auto& p : small.vertices) p += Vector3d(4.75, 0.125, 0);  // through the big sphere's surface
  cases.push_back(test_shapes::merged(big, small));
  for (const PolygonMesh& m : cases) {
    const std::set<std::pair<int, int>> expected = all_pairs(m);
    const SelfIntersectionSearch search = search_self_intersections(m, {.max_pairs = 1u << 30});
    EXPECT_TRUE(search.complete);
    std::set<std::pair<int, int>> got;
    for (const FacePair& p : search.pairs) got.insert(std::minmax(p.face_a, p.face_b));
    EXPECT_EQ(got, expected);
    EXPECT_FALSE(expected.empty());
    // The caller's promise of distinct vertices (no sort for copies) changes nothing where it holds.
    std::set<std::array<double, 3>> points;
    for (const Vector3d& v : m.vertices) points.insert({v.x(), v.y(), v.z()});
    ASSERT_EQ(points.size(), m.vertices.size());
    got.clear();
    for (const FacePair& p : search_self_intersections(m, {.max_pairs = 1u << 30, .distinct_vertices = true}).pairs)
      got.insert(std::minmax(p.face_a, p.face_b));
    EXPECT_EQ(got, expected);
  }
}


/// The pairs search_self_intersections reports, both with and without the promise of distinct
/// vertices (which must hold).
std::set<std::pair<int, int>> searched_pairs(const PolygonMesh& m, bool distinct) {
  const SelfIntersectionSearch search = search_self_intersections(m, {.max_pairs = 1u << 30, .distinct_vertices = distinct});
  EXPECT_TRUE(search.complete);
  std::set<std::pair<int, int>> got;
  for (const FacePair& p : search.pairs) got.insert(std::minmax(p.face_a, p.face_b));
  return got;
}

/// m with every face replaced by its triangles (so that any triangulation is this one).
PolygonMesh triangulated(const PolygonMesh& m) {
  PolygonMesh out;
  out.vertices = m.vertices;
  for (const auto& f : m.faces)
    for (const IndexTriangle& t : triangulate_polygon(m.vertices, f)) out.faces.push_back({t[0], t[1], t[2]});
  return out;
}

// The scan runs over runs of cells in parallel (base/parallel.hpp): on meshes large enough for
// many runs it finds every pair (against all pairs whose boxes overlap, tested one by one), and
// the same pairs with one thread as with every thread, also when it stops at max_pairs.
TEST(SelfIntersection, ParallelRunsFindEveryPairForAnyThreadCount) {
  PolygonMesh small = test_shapes::uv_sphere(64, 0.7);
  for (auto& p : small.vertices) p += Vector3d(0.5, 0.2, 0.1);
  const PolygonMesh m = triangulated(test_shapes::merged(test_shapes::uv_sphere(96), small));
  ASSERT_GT(m.faces.size(), 10000u);
  std::vector<Eigen::AlignedBox3d> boxes;
  for (const auto& f : m.faces) {
    Eigen::AlignedBox3d b;
    for (int v : f) b.extend(m.vertices[size_t(v)]);
    boxes.push_back(b);
  }
  std::set<std::pair<int, int>> expected;
  for (size_t i = 0; i < m.faces.size(); ++i)
    for (size_t j = i + 1; j < m.faces.size(); ++j) {
      if (!boxes[i].intersects(boxes[j])) continue;
      const auto& s = m.faces[i];
      const auto& t = m.faces[j];
      if (triangles_meet({s[0], s[1], s[2]}, {m.vertices[s[0]], m.vertices[s[1]], m.vertices[s[2]]}, {t[0], t[1], t[2]},
                         {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]}))
        expected.insert({int(i), int(j)});
    }
  ASSERT_GT(expected.size(), 200u);
  auto pairs = [&](size_t max_pairs) {
    std::vector<std::pair<int, int>> out;
    for (const FacePair& p : search_self_intersections(m, {.max_pairs = max_pairs}).pairs)
      out.push_back({p.face_a, p.face_b});
    return out;
  };
  const std::vector<std::pair<int, int>> all = pairs(1u << 30), first = pairs(3);
  EXPECT_EQ((std::set<std::pair<int, int>>(all.begin(), all.end())), expected);
  ASSERT_EQ(first.size(), 3u);
  {
    const ThreadLimit one(1);
    EXPECT_EQ(pairs(1u << 30), all);
    EXPECT_EQ(pairs(3), first);
  }
}

// Pairs that share a vertex whose star is certified are not examined (the star projects along an
// axis to sectors that turn one way and wind once). Stars that fold or wind twice must not be
// certified: on closed meshes shaken until their stars fold, on a sphere with a corner pulled through
// the centre and out, and on flat fans that wind twice or turn back, the pairs found are
// those of all pairs of faces.
TEST(SelfIntersection, FoldedStarsAreStillSearched) {
  std::vector<PolygonMesh> cases;
  std::mt19937 rng(17);
  for (double amplitude : {0.02, 0.1, 0.25, 0.5})
    for (const PolygonMesh& shape : {test_shapes::uv_sphere(12), test_shapes::torus(12, 8, 1.2, 0.4)}) {
      PolygonMesh m = triangulated(shape);
      std::uniform_real_distribution<double> shake(-amplitude, amplitude);
      for (Vector3d& p : m.vertices) p += Vector3d(shake(rng), shake(rng), shake(rng));
      cases.push_back(m);
    }
  PolygonMesh pushed = triangulated(test_shapes::uv_sphere(12));
  pushed.vertices[30] = -1.25 * pushed.vertices[30];  // a corner through the centre and out
  cases.push_back(pushed);
  // Flat fans round the origin: 7 sectors of 4 pi / 7 each (all turning left, winding twice),
  // and 6 sectors of which one turns back over its neighbours.
  PolygonMesh twice;
  twice.vertices.push_back(Vector3d::Zero());
  for (int j = 0; j < 7; ++j) {
    const double angle = 4 * std::numbers::pi * j / 7;
    twice.vertices.emplace_back(std::cos(angle), std::sin(angle), 0);
  }
  for (int j = 0; j < 7; ++j) twice.faces.push_back({0, 1 + j, 1 + (j + 1) % 7});
  cases.push_back(twice);
  PolygonMesh back;
  back.vertices = {Vector3d::Zero(), {1, 0, 0}, {0.5, 0.8, 0}, {-0.5, 0.8, 0}, {0.9, 0.3, 0}, {-0.5, -0.8, 0}, {0.5, -0.8, 0}};
  for (int j = 1; j <= 6; ++j) back.faces.push_back({0, j, j % 6 + 1});
  cases.push_back(back);
  size_t index = 0;
  for (const PolygonMesh& m : cases) {
    SCOPED_TRACE(index++);
    const std::set<std::pair<int, int>> expected = all_pairs(m);
    EXPECT_EQ(searched_pairs(m, false), expected);
    EXPECT_EQ(searched_pairs(m, true), expected);
  }
  EXPECT_FALSE(all_pairs(twice).empty());
  EXPECT_FALSE(all_pairs(back).empty());
  EXPECT_FALSE(all_pairs(pushed).empty());
}

// Strips of triangles that all project the same way along one axis but overlap themselves in
// that projection: certified_patches must not certify them (most of their stars are certified,
// so patches are looked for). A ramp of one and a half turns
// whose upper turn comes down through the lower one (one boundary loop, which is not simple),
// and an annulus covered twice, z = sin(theta / 2) (two loops); each along every axis, and
// mirrored (the other sign). The search must find what all pairs of faces find.
TEST(SelfIntersection, PatchesOverlappingInProjectionAreStillSearched) {
  // A strip between radii 4 and 5 (11 rows, so that most stars are inner ones, certified) over
  // the angles theta(k), k = 0..steps (closed: k mod steps).
  auto strip = [](int steps, bool closed, auto&& theta, auto&& height) {
    constexpr int kRows = 11;
    PolygonMesh m;
    const int rings = closed ? steps : steps + 1;
    for (int k = 0; k < rings; ++k)
      for (int row = 0; row < kRows; ++row) {
        const double r = 4 + 0.1 * row;
        m.vertices.emplace_back(r * std::cos(theta(k)), r * std::sin(theta(k)), height(theta(k)));
      }
    for (int k = 0; k < steps; ++k)
      for (int row = 0; row + 1 < kRows; ++row) {
        const int in = kRows * k + row, out = in + 1, next_in = kRows * ((k + 1) % rings) + row, next_out = next_in + 1;
        m.faces.push_back({in, out, next_out});
        m.faces.push_back({in, next_out, next_in});
      }
    return m;
  };
  const double pi = std::numbers::pi;
  const PolygonMesh ramp = strip(48, false, [&](int k) { return 3 * pi * k / 48; }, [&](double t) {
    return t <= 2 * pi ? 0.2 * t : 0.4 * pi - 0.5 * (t - 2 * pi);
  });
  const PolygonMesh twice = strip(64, true, [&](int k) { return 4 * pi * (k + 0.5) / 64; },
                                  [](double t) { return 0.5 * std::sin(t / 2); });
  for (const PolygonMesh& shape : {ramp, twice}) {
    ASSERT_FALSE(all_pairs(shape).empty());
    for (int axis = 0; axis < 3; ++axis)
      for (const double mirror : {1.0, -1.0}) {
        SCOPED_TRACE(testing::Message() << "axis " << axis << " mirror " << mirror);
        PolygonMesh m = shape;
        for (Vector3d& p : m.vertices) p = Vector3d(p[(3 - axis) % 3], p[(4 - axis) % 3], mirror * p[(5 - axis) % 3]);
        const std::set<std::pair<int, int>> expected = all_pairs(m);
        EXPECT_EQ(searched_pairs(m, false), expected);
        EXPECT_EQ(searched_pairs(m, true), expected);
      }
  }
}

// The scan compares boxes rounded to floats: triangles that only touch, where the boxes' common
// side is a double between two floats (0.1 scaled by powers of two from 2^-1060 to 2^200, beyond
// float's range), are still found, and triangles a double apart are not reported.
TEST(SelfIntersection, TouchingAtCoordinatesBetweenFloats) {
  for (int exponent : {-1060, -200, -140, -30, 0, 30, 120, 200}) {
    SCOPED_TRACE(exponent);
    const double x = std::ldexp(0.1, exponent), y = std::ldexp(0.3, exponent), z = std::ldexp(0.7, exponent);
    PolygonMesh m;
    // A triangle in the plane X = x, and one whose corner is on it, the rest at larger X.
    m.vertices = {{x, 0, 0}, {x, 2 * y, 0}, {x, 0, 2 * z}, {x, y / 2, z / 2}, {3 * x, y, 0}, {3 * x, 0, z}};
    m.faces = {{0, 1, 2}, {3, 4, 5}};
    EXPECT_EQ(searched_pairs(m, true), (std::set<std::pair<int, int>>{{0, 1}}));
    m.vertices[3].x() = std::nextafter(x, 2 * x);  // a double apart: they do not meet
    EXPECT_TRUE(searched_pairs(m, true).empty());
    m.vertices[3].x() = x;
    for (Vector3d& p : m.vertices) p = -p;  // the same below zero
    EXPECT_EQ(searched_pairs(m, true), (std::set<std::pair<int, int>>{{0, 1}}));
  }
}

// Exact-vertex marks (SelfIntersectionOptions::exact_vertices) skip only pairs of faces whose
// corners are all marked: on meshes with many crossings and random marks, the pairs found are
// exactly all pairs (brute force) less those of two all-marked faces, so no crossing that involves
// a face with an unmarked corner is hidden.
TEST(SelfIntersection, ExactMarksSkipOnlyPairsOfMarkedFaces) {
  PolygonMesh s = test_shapes::uv_sphere(12);
  PolygonMesh t = test_shapes::torus(16, 6, 1.2, 0.3);
  for (auto& p : t.vertices) p += Vector3d(0.5, 0.25, 0.125);
  const PolygonMesh m = test_shapes::merged(test_shapes::merged(s, t), test_shapes::box({-3, -0.1, -0.1}, {3, 0.1, 0.1}));
  const std::set<std::pair<int, int>> all = all_pairs(m);
  std::mt19937 rng(14);
  for (double fraction : {0.0, 0.5, 0.9, 0.97, 1.0}) {
    SCOPED_TRACE(fraction);
    std::bernoulli_distribution marked(fraction);
    std::vector<char> exact(m.vertices.size());
    for (char& e : exact) e = marked(rng) ? 1 : 0;
    auto all_marked = [&](int f) {
      for (int v : m.faces[size_t(f)])
        if (exact[size_t(v)] == 0) return false;
      return true;
    };
    std::set<std::pair<int, int>> expected;
    for (const auto& [a, b] : all)
      if (!all_marked(a) || !all_marked(b)) expected.insert({a, b});
    const SelfIntersectionSearch search = search_self_intersections(m, {.max_pairs = 1u << 30, .exact_vertices = exact});
    EXPECT_TRUE(search.complete);
    std::set<std::pair<int, int>> got;
    for (const FacePair& p : search.pairs) got.insert(std::minmax(p.face_a, p.face_b));
    EXPECT_EQ(got, expected);
    if (fraction < 1) EXPECT_FALSE(expected.empty());
    else EXPECT_TRUE(expected.empty());
  }
  // Marks of the wrong count are ignored (every pair found).
  const std::vector<char> short_marks(m.vertices.size() - 1, 1);
  const SelfIntersectionSearch search = search_self_intersections(m, {.max_pairs = 1u << 30, .exact_vertices = short_marks});
  EXPECT_EQ(search.pairs.size(), all.size());
}

// A clean pair of boxes, all marked but one corner of the second, which is moved into the first:
// the crossings of that corner's faces with the first box's (all-marked) faces are still reported.
TEST(SelfIntersection, MovedCornerCrossingAnExactFaceIsFound) {
  PolygonMesh a = test_shapes::box({0, 0, 0}, {1, 1, 1});
  const PolygonMesh b = test_shapes::box({2, 0, 0}, {3, 1, 1});
  PolygonMesh m = test_shapes::merged(a, b);
  std::vector<char> exact(m.vertices.size(), 1);
  EXPECT_TRUE(search_self_intersections(m, {.exact_vertices = exact}).pairs.empty());
  EXPECT_TRUE(search_self_intersections(m).pairs.empty());
  const int moved = 8;  // b's corner (2, 0, 0)
  ASSERT_EQ(m.vertices[moved], Vector3d(2, 0, 0));
  m.vertices[moved] = Vector3d(0.5, 0.25, 0.25);  // inside a: b's faces at it cross a's faces
  exact[moved] = 0;
  const SelfIntersectionSearch search = search_self_intersections(m, {.max_pairs = 100, .exact_vertices = exact});
  ASSERT_FALSE(search.pairs.empty());
  const std::set<std::pair<int, int>> all = all_pairs(m);
  std::set<std::pair<int, int>> got;
  for (const FacePair& p : search.pairs) got.insert(std::minmax(p.face_a, p.face_b));
  EXPECT_EQ(got, all);  // every pair involves one of b's faces at the moved corner
  for (const auto& [f, g] : got) EXPECT_TRUE(f < 6 && g >= 6);
}

// The broad phase: every pair of overlapping boxes (closed, so touching counts) is owned by
// exactly one cell that lists both, and no other pair is; against brute force, with boxes of very
// different sizes (long boxes coarsen the grid), flat boxes and repeated boxes.
TEST(BoxGrid, EveryOverlappingPairIsOwnedByExactlyOneCell) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> at(-10, 10), size(0, 1);
  for (int round = 0; round < 20; ++round) {
    std::vector<Eigen::AlignedBox3d> boxes;
    for (int i = 0; i < 300; ++i) {
      const Vector3d lo(at(rng), at(rng), at(rng));
      Vector3d extent(size(rng), size(rng), size(rng));
      if (i % 17 == 0) extent *= 15;         // long ones
      if (i % 11 == 0) extent.z() = 0;       // flat ones
      boxes.emplace_back(lo, lo + extent);
      if (i % 29 == 0) boxes.push_back(boxes.back());  // the same box twice
    }
    const mesh::detail::BoxGrid grid(boxes);
    std::map<std::pair<int, int>, int> owned;
    for (size_t k = 0; k < grid.cells(); ++k) {
      const auto cell = grid.cell(k);
      for (size_t i = 0; i < cell.size(); ++i)
        for (size_t j = i + 1; j < cell.size(); ++j)
          if (boxes[size_t(cell[i])].intersects(boxes[size_t(cell[j])])) {
            // The first-cell masks say the same as owns().
            const auto masks = grid.first_cell_masks(k);
            EXPECT_EQ((masks[i] | masks[j]) == 7, grid.owns(k, cell[i], cell[j]));
            if (grid.owns(k, cell[i], cell[j])) ++owned[std::minmax(cell[i], cell[j])];
          }
    }
    size_t expected = 0;
    for (size_t a = 0; a < boxes.size(); ++a)
      for (size_t b = a + 1; b < boxes.size(); ++b)
        if (boxes[a].intersects(boxes[b])) {
          ++expected;
          EXPECT_EQ(owned[std::pair(int(a), int(b))], 1) << "boxes " << a << " and " << b;
        }
    size_t found = 0;
    for (const auto& [pair, count] : owned) found += count > 0 ? 1 : 0;
    EXPECT_EQ(found, expected);
  }
}

// The same on tens of thousands of boxes: in a solid cube (cells numbered densely, a counting sort)
// and on a sphere's shell (cells sorted by key), the owned pairs against a sweep along x, each
// cell's boxes in ascending order, and the cells, their members and masks the same with one thread
// as with all.
TEST(BoxGrid, LargeGridsOwnEveryPairOnceForAnyThreadCount) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(-1, 1), size(0, 0.6);
  for (const bool shell : {false, true}) {
    SCOPED_TRACE(shell);
    std::vector<Eigen::AlignedBox3d> boxes;
    while (boxes.size() < 40000) {
      Vector3d lo(unit(rng), unit(rng), unit(rng));
      if (shell) {
        if (lo.norm() < 0.1) continue;
        lo = lo.normalized() * 40;
      } else {
        lo *= 12;
      }
      boxes.emplace_back(lo, lo + Vector3d(size(rng), size(rng), size(rng)));
    }
    const mesh::detail::BoxGrid grid(boxes);
    std::vector<std::pair<int, int>> owned;
    for (size_t k = 0; k < grid.cells(); ++k) {
      const auto cell = grid.cell(k);
      ASSERT_TRUE(std::adjacent_find(cell.begin(), cell.end(), std::greater_equal<int>()) == cell.end())
          << "cell " << k << "'s boxes are not in ascending order";
      for (size_t i = 0; i < cell.size(); ++i)
        for (size_t j = i + 1; j < cell.size(); ++j)
          if (boxes[size_t(cell[i])].intersects(boxes[size_t(cell[j])]) && grid.owns(k, cell[i], cell[j]))
            owned.push_back(std::minmax(cell[i], cell[j]));
    }
    std::sort(owned.begin(), owned.end());
    std::vector<int> order(boxes.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return boxes[size_t(a)].min().x() < boxes[size_t(b)].min().x(); });
    std::vector<std::pair<int, int>> expected;
    for (size_t a = 0; a < order.size(); ++a)
      for (size_t b = a + 1; b < order.size() && boxes[size_t(order[b])].min().x() <= boxes[size_t(order[a])].max().x();
           ++b)
        if (boxes[size_t(order[a])].intersects(boxes[size_t(order[b])]))
          expected.push_back(std::minmax(order[a], order[b]));
    std::sort(expected.begin(), expected.end());
    ASSERT_GT(expected.size(), 1000u);
    EXPECT_EQ(owned, expected);
    const ThreadLimit one(1);
    const mesh::detail::BoxGrid serial(boxes);
    ASSERT_EQ(serial.cells(), grid.cells());
    for (size_t k = 0; k < grid.cells(); ++k) {
      const auto a = grid.cell(k), b = serial.cell(k);
      ASSERT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "cell " << k;
      const auto ma = grid.first_cell_masks(k), mb = serial.first_cell_masks(k);
      ASSERT_TRUE(std::equal(ma.begin(), ma.end(), mb.begin(), mb.end())) << "cell " << k;
    }
  }
}

// first_copies against the definition by brute force: points drawn from a small set (many
// copies), with -0 beside +0, infinities and NaN (never matched), and points left out by `take`.
TEST(PointCopies, FirstCopiesAreTheSmallestIndexAtEachPoint) {
  std::mt19937 rng(41);
  const std::array<double, 7> values = {0.0, -0.0, 1.0, -2.5, 0x1p-1070, std::numeric_limits<double>::infinity(),
                                        std::numeric_limits<double>::quiet_NaN()};
  for (int round = 0; round < 200; ++round) {
    const size_t n = 1 + rng() % 60;
    std::vector<Eigen::Vector3d> points(n);
    std::vector<char> take(n);
    for (size_t v = 0; v < n; ++v) {
      for (int k = 0; k < 3; ++k) points[v][k] = values[rng() % (round % 2 ? 7 : 4)];
      take[v] = rng() % 4 != 0;
    }
    const bool with_take = round % 3 != 0;
    const std::vector<int> got = mesh::detail::first_copies(points, with_take ? std::span<const char>(take) : std::span<const char>());
    ASSERT_EQ(got.size(), n);
    for (size_t v = 0; v < n; ++v) {
      auto taken = [&](size_t u) { return (!with_take || take[u] != 0) && points[u].allFinite(); };
      int expected = int(v);
      if (taken(v))
        for (size_t u = 0; u < v; ++u)
          if (taken(u) && points[u] == points[v]) {
            expected = int(u);
            break;
          }
      ASSERT_EQ(got[v], expected) << "round " << round << " point " << v;
    }
  }
}

}  // namespace
}  // namespace sculpt
