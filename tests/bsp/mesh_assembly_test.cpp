// Mesh assembly (lib/bsp/mesh_assembly.hpp and its stages): the exact shortcuts checked against
// brute-force references computed here with unbounded integers.
#include "bsp/assembly/mesh_assembly.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/multiprecision/cpp_int.hpp>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>
#include <set>

#include "bsp/assembly/faces.hpp"
#include "bsp/assembly/junction_removal.hpp"
#include "bsp/assembly/sheets.hpp"
#include "bsp/assembly/vertex_equality.hpp"
#include "bsp/assembly/vertex_merge.hpp"
#include "bsp/boundary.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/boundary_fragments.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using Big = boost::multiprecision::cpp_int;
using kernel::Plane;

Big big(kernel::Int128 v) { return Big(v); }  // Boost converts __int128 itself

// The vertex p ∩ q ∩ r by Cramer's rule in unbounded integers: (x, y, z) / w (w = 0: none).
struct Homogeneous {
  Big x, y, z, w;
  friend bool operator==(const Homogeneous& a, const Homogeneous& b) {
    return a.x * b.w == b.x * a.w && a.y * b.w == b.y * a.w && a.z * b.w == b.z * a.w;
  }
  Eigen::Vector3d world() const {
    const double dw = w.convert_to<double>();
    return Eigen::Vector3d(x.convert_to<double>() / dw, y.convert_to<double>() / dw, z.convert_to<double>() / dw) *
           kernel::kGridStep;
  }
};

Big det3(const Big m[3][3]) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Homogeneous cramer(const Plane& p, const Plane& q, const Plane& r) {
  const Plane* rows[3] = {&p, &q, &r};
  Big a[3][3], col[3];
  for (int i = 0; i < 3; ++i) {
    a[i][0] = rows[i]->a, a[i][1] = rows[i]->b, a[i][2] = rows[i]->c;
    col[i] = -big(rows[i]->d);
  }
  Homogeneous h;
  h.w = det3(a);
  Big* out[3] = {&h.x, &h.y, &h.z};
  for (int k = 0; k < 3; ++k) {
    Big m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == k ? col[i] : a[i][j];
    *out[k] = det3(m);
  }
  return h;
}

// Sign of plane s at the vertex h (exact).
int side(const Homogeneous& h, const Plane& s) {
  const Big v = s.a * h.x + s.b * h.y + s.c * h.z + big(s.d) * h.w;
  return v.sign() * h.w.sign();
}

// Vertices of the convex polytope ∩ {s <= 0}, by brute force over all plane triples.
std::vector<Homogeneous> polytope_vertices(const std::vector<Plane>& planes) {
  std::vector<Homogeneous> out;
  const std::size_t n = planes.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Homogeneous h = cramer(planes[i], planes[j], planes[k]);
        if (h.w == 0) continue;
        if (std::any_of(planes.begin(), planes.end(), [&](const Plane& s) { return side(h, s) > 0; })) continue;
        if (std::find(out.begin(), out.end(), h) == out.end()) out.push_back(h);
      }
  return out;
}

std::vector<Plane> kernel_planes(const std::vector<HalfSpace>& half_spaces) {
  std::vector<Plane> planes;
  for (const HalfSpace& h : half_spaces) planes.push_back(kernel::plane_from_normal(h.normal, h.offset));
  return planes;
}

// The assembled mesh has exactly the polytope's vertices: as many, each within 1e-9 of one.
void expect_polytope_vertices(const PolygonMesh& mesh, const std::vector<Homogeneous>& reference) {
  EXPECT_EQ(mesh.vertices.size(), reference.size());
  for (const Eigen::Vector3d& v : mesh.vertices) {
    double best = INFINITY;
    for (const Homogeneous& h : reference) best = std::min(best, (h.world() - v).norm());
    EXPECT_LT(best, 1e-9) << v.transpose();
  }
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(mesh));
  EXPECT_TRUE(checks::EulerCharacteristicIs(mesh, 2));
}

// Largest number of different plane triples (as sets of planes up to orientation) among the
// fragments' corners at one point: > 1 means the exact comparison across triples is exercised.
int most_triples_at_one_point(const bsp::detail::Fragments& f) {
  struct Corner {
    Homogeneous at;
    std::set<int> planes;  // one representative index per plane up to orientation
  };
  auto representative = [&](std::int32_t i) {
    for (std::int32_t j = 0; j <= i; ++j)
      if (kernel::same_or_opposite(f.planes[j], f.planes[i])) return int(j);
    return int(i);
  };
  std::vector<Corner> corners;
  for (const auto& fr : f.fragments)
    for (const auto& c : fr.polygon.corners)
      corners.push_back({cramer(f.planes[fr.polygon.support], f.planes[c.p], f.planes[c.q]),
                         {representative(fr.polygon.support), representative(c.p), representative(c.q)}});
  int most = 0;
  for (const Corner& a : corners) {
    std::set<std::set<int>> triples;
    for (const Corner& b : corners)
      if (b.at == a.at) triples.insert(b.planes);
    most = std::max(most, int(triples.size()));
  }
  return most;
}

// vertex_on_plane (vertex_equality.hpp) against the sign of plane s at Cramer's vertex in
// unbounded integers, and against kernel::orient: random planes of every size up to the bit
// budget (normals to 2^50, offsets to 2^77, both sides of the 2^72 fast-path limit), planes
// through the vertex (integer combinations of its three), planes off it by one unit of d
// (det = W: never zero), axis planes (sphere rings), and nearly dependent triples.
TEST(MeshAssembly, VertexOnPlaneZeroTestMatchesUnboundedArithmetic) {
  std::mt19937_64 rng(20261122);
  auto coefficient = [&](int bits) {
    return std::int64_t(rng() % ((std::uint64_t(1) << bits) + 1)) * ((rng() & 1) != 0 ? 1 : -1);
  };
  auto offset = [&](int bits) {
    const kernel::Int128 high = bits > 60 ? kernel::Int128(coefficient(bits - 60)) : 0;
    return high * (kernel::Int128(1) << 60) + coefficient(std::min(bits, 60));
  };
  const int normal_bits[] = {1, 20, 37, 50};
  const int offset_bits[] = {10, 52, 71, 77};
  int zeros = 0, nonzeros = 0, large = 0, nearly_dependent = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int nb = normal_bits[trial % 4], db = offset_bits[(trial / 4) % 4];
    auto random_plane = [&] { return Plane(coefficient(nb), coefficient(nb), coefficient(nb), offset(db)); };
    Plane p = random_plane(), q = random_plane(), r = random_plane();
    if (trial % 7 == 0) p = Plane(0, 0, 1, offset(db));  // a ring plane of a sphere
    if (trial % 5 == 0) {  // nearly dependent: r almost p + q
      r = Plane(p.a + q.a + 1, p.b + q.b, p.c + q.c, p.d + q.d);
      ++nearly_dependent;
    }
    const Homogeneous h = cramer(p, q, r);
    if (h.w == 0) continue;
    const kernel::ApproxPoint at = kernel::approximate_vertex(p, q, r);
    const bsp::detail::VertexMinors minors = bsp::detail::vertex_minors(p, q, r, at);
    std::vector<Plane> tests = {random_plane(), p.opposite(), q};
    for (int k = 0; k < 3; ++k) {  // through the vertex: alpha p + beta q + gamma r
      const std::int64_t al = std::int64_t(rng() % 5) - 2, be = std::int64_t(rng() % 5) - 2, ga = std::int64_t(rng() % 5) - 2;
      const Plane s(al * p.a + be * q.a + ga * r.a, al * p.b + be * q.b + ga * r.b, al * p.c + be * q.c + ga * r.c,
                    al * p.d + be * q.d + ga * r.d);
      if (s.a == 0 && s.b == 0 && s.c == 0) continue;
      tests.push_back(s);
      tests.push_back(Plane(s.a, s.b, s.c, s.d + ((rng() & 1) != 0 ? 1 : -1)));  // off by one unit
    }
    for (const Plane& s : tests) {
      const bool on = side(h, s) == 0;
      ASSERT_EQ(bsp::detail::vertex_on_plane(minors, s), on) << "trial " << trial;
      ASSERT_EQ(kernel::orient(p, q, r, at, s) == kernel::Sign::Zero, on) << "trial " << trial;
      (on ? zeros : nonzeros) += 1;
      const bool large_d = s.d >= kernel::Int128(1) << 72 || s.d <= -(kernel::Int128(1) << 72);
      large += !minors.small || large_d ? 1 : 0;  // vertex_on_plane's general path
    }
  }
  EXPECT_GT(zeros, 8000);
  EXPECT_GT(nonzeros, 8000);
  EXPECT_GT(large, 1000);  // the general path (some |d| >= 2^72) ran too
  EXPECT_GT(nearly_dependent, 500);
}

TEST(MeshAssembly, EqualPointsFromDifferentPlaneTriplesAreOneVertex) {
  // Octahedron |x| + |y| + |z| <= 1: four face planes meet exactly at each vertex, so corners of
  // one vertex come with different plane triples and are merged by the exact test only.
  std::vector<HalfSpace> hs;
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2)
      for (int sz = -1; sz <= 1; sz += 2) hs.push_back({Eigen::Vector3d(sx, sy, sz), -1.0});
  const Solid s = convex_polytope(hs);
  const bsp::detail::Fragments f = bsp::detail::boundary_fragments(s);
  ASSERT_GE(most_triples_at_one_point(f), 2);
  const std::vector<Homogeneous> reference = polytope_vertices(kernel_planes(hs));
  ASSERT_EQ(reference.size(), 6u);
  const PolygonMesh mesh = bsp::detail::assemble_mesh(f, {});
  expect_polytope_vertices(mesh, reference);
  EXPECT_EQ(mesh.faces.size(), 8u);
  EXPECT_TRUE(checks::VolumeNear(mesh, 4.0 / 3.0, 1e-12));
}

TEST(MeshAssembly, FivePlanesThroughOneApexGiveOneVertex) {
  // Pentagonal pyramid: the normals (cos, sin, 1) are rounded, but c = 2^52 and d = -2^67 stay
  // exact, so all five side planes pass exactly through the apex (0, 0, 1).
  std::vector<HalfSpace> hs = {{Eigen::Vector3d(0, 0, -1), 0.0}};
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * std::numbers::pi * k / 5 + 0.1;
    hs.push_back({Eigen::Vector3d(std::cos(a), std::sin(a), 1.0), -1.0});
  }
  const std::vector<Homogeneous> reference = polytope_vertices(kernel_planes(hs));
  ASSERT_EQ(reference.size(), 6u);
  const Solid s = convex_polytope(hs);
  const bsp::detail::Fragments f = bsp::detail::boundary_fragments(s);
  ASSERT_GE(most_triples_at_one_point(f), 2);
  expect_polytope_vertices(bsp::detail::assemble_mesh(f, {}), reference);
}

TEST(MeshAssembly, NearlyCoincidentDistinctVerticesStayApart) {
  // Side planes through a nominal apex at height 0.7 whose rounded coefficients miss it by
  // less than 1e-12: the planes meet in a cluster of distinct vertices far closer than the
  // vertex merge's grid cell; each must stay a vertex of its own.
  std::vector<HalfSpace> hs = {{Eigen::Vector3d(0, 0, -1), 0.0}};
  for (int k = 0; k < 7; ++k) {
    const double a = 2 * std::numbers::pi * k / 7 + 0.3;
    const Eigen::Vector3d n(std::cos(a), std::sin(a), 0.7 + 0.01 * k);
    hs.push_back({n, -n.z() * 0.7});  // n . (0, 0, 0.7) + offset = 0 before rounding
  }
  const std::vector<Homogeneous> reference = polytope_vertices(kernel_planes(hs));
  int near_apex = 0;
  for (const Homogeneous& h : reference) near_apex += (h.world() - Eigen::Vector3d(0, 0, 0.7)).norm() < 1e-9;
  ASSERT_GE(near_apex, 2) << "the rounded planes met in one point: the case is not exercised";
  const PolygonMesh mesh = to_mesh(convex_polytope(hs));
  expect_polytope_vertices(mesh, reference);
}

// The carried fragments of a solid, or those extracted from its tree.
bsp::detail::Fragments fragments_of(const Solid& s, bool carried) {
  return carried ? bsp::detail::Fragments{s.planes(), s.boundary()} : bsp::detail::boundary_fragments(s);
}

// The fragments with every third corner's approximation taken away (its error bound unknown):
// such a corner has no cells, so the merge compares it with every earlier class and every later
// class with it.
bsp::detail::Fragments without_some_approximations(const bsp::detail::Fragments& f) {
  bsp::detail::Fragments g{f.planes, {}};
  int n = 0;
  for (const FragmentRef fr : f.fragments) {
    kernel::ConvexPolygon poly;
    poly.support = fr.polygon.support;
    for (kernel::Corner c : fr.polygon.corners) {
      if (n++ % 3 == 0) c.set_at({c.at().x, c.at().y, c.at().z, -1});
      poly.corners.push_back(c);
    }
    g.fragments.push_back(poly, fr.flip);
  }
  return g;
}

TEST(MeshAssembly, VertexMergeMatchesPairwiseExactEquality) {
  // merge_vertices finds each corner's class in its grid cells and each class's earlier equal
  // one among the classes entered there before it; the reference compares every pair of corners by Cramer's rule in
  // unbounded integers. Two corners share a vertex iff their points are equal; vertices are numbered by first corner,
  // each with its first corner's triple; the faces reverse flipped fragments.
  std::vector<Solid> solids;
  solids.push_back(sphere(1.0, {.segments = 12}) - box({0, 0, 0}, {1, 1, 1}));
  solids.push_back(box({0, 0, 0}, {2, 2, 2}) | box({1, 1, 1}, {3, 3, 3}) | box({0.5, -1, 0.5}, {1.5, 4, 1.5}));
  {
    std::vector<HalfSpace> hs;  // octahedron: four planes through each vertex
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        for (int sz = -1; sz <= 1; sz += 2) hs.push_back({Eigen::Vector3d(sx, sy, sz), -1.0});
    solids.push_back(convex_polytope(hs) - box({0, 0, 0}, {1, 1, 1}));
  }
  {
    // An imported icosahedron (its vertices snap to grid points, five faces at each) united with
    // a turned copy: corners at grid points merged by their integers, the seams' corners exactly.
    const double t = (1 + std::sqrt(5.0)) / 2;
    PolygonMesh ico;
    ico.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    ico.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    const Solid m = from_mesh(ico);
    // A corner of a box (a grid point) and the apex of a tetrahedron 0.006 grid units beyond
    // it (not a grid point): two vertices in one cell of the merge.
    const double e = 1e-7;
    solids.push_back(box({0, 0, 0}, {1, 1, 1}) | convex_polytope({{Eigen::Vector3d(-1, 0, 0), 1 + e},
                                                                  {Eigen::Vector3d(0, -1, 0), 1 + e},
                                                                  {Eigen::Vector3d(0, 0, -1), 1 + e},
                                                                  {Eigen::Vector3d(1, 1, 1), -3.5}}));
    solids.push_back(m | transform(m, Eigen::Affine3d(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()))));
  }
  for (std::size_t i = 0; i < solids.size(); ++i) {
    SCOPED_TRACE(i);
    for (const int variant : {0, 1, 2}) {
      const bool carried = variant == 1;
      if (carried && !solids[i].has_boundary()) continue;
      SCOPED_TRACE(variant);
      const bsp::detail::Fragments f = variant == 2
                                           ? without_some_approximations(bsp::detail::boundary_fragments(solids[i]))
                                           : fragments_of(solids[i], carried);
      const bsp::detail::MergedFragments merged = bsp::detail::merge_vertices(f);
      std::vector<Homogeneous> point;
      std::vector<int> vertex;  // of each corner, in fragment order
      std::vector<bsp::detail::PlaneTriple> triple;
      for (std::size_t k = 0; k < f.fragments.size(); ++k) {
        const auto& fr = f.fragments[k];
        const int m = int(fr.polygon.corners.size());
        ASSERT_EQ(merged.faces.count(int(k)), m);
        for (int j = 0; j < m; ++j) {
          const auto& c = fr.polygon.corners[std::size_t(j)];
          point.push_back(cramer(f.planes[fr.polygon.support], f.planes[c.p], f.planes[c.q]));
          vertex.push_back(merged.faces.vertex[std::size_t(merged.faces.begin(int(k)) + (fr.flip ? m - 1 - j : j))]);
          triple.push_back({fr.polygon.support, c.p, c.q});
        }
      }
      int next = 0;
      for (std::size_t a = 0; a < point.size(); ++a) {
        if (vertex[a] == next) {  // first corner of a new vertex
          const bsp::detail::PlaneTriple& t = merged.vertices.triple[std::size_t(next)];
          EXPECT_TRUE(t.s == triple[a].s && t.p == triple[a].p && t.q == triple[a].q);
          ++next;
        }
        ASSERT_LT(vertex[a], next) << "vertices are numbered by first corner";
        for (std::size_t b = 0; b < a; ++b) ASSERT_EQ(vertex[a] == vertex[b], point[a] == point[b]) << a << " " << b;
      }
      EXPECT_EQ(next, merged.vertices.size());
    }
  }
}

TEST(MeshAssembly, LooseCornersAtAFineSpheresCapsMergeByExactEquality) {
  // sphere(1, 512): the last rings snap to the poles' heights and become caps, whose corners meet
  // the almost flat fans in nearly dependent planes; their approximations are loose (an error
  // bound of a grid unit or more), and the merge resolves them from the exact vertex rounded
  // (vertex_merge.cpp, tight_approximation). Checked near the caps (|z| > 0.99) against Cramer's
  // rule: the corners of a vertex are one point, and vertices closer than 1e-9 are different
  // points.
  const Solid ball = sphere(1.0, {.segments = 512});
  ASSERT_TRUE(ball.has_boundary());
  const bsp::detail::Fragments f = fragments_of(ball, true);
  const bsp::detail::MergedFragments merged = bsp::detail::merge_vertices(f);
  std::map<int, Homogeneous> point_of_vertex;
  int loose = 0, corners = 0;
  for (std::size_t k = 0; k < f.fragments.size(); ++k) {
    const auto& fr = f.fragments[k];
    const int m = int(fr.polygon.corners.size());
    for (int j = 0; j < m; ++j) {
      const auto& c = fr.polygon.corners[std::size_t(j)];
      if (!(std::fabs(c.at().z) * kernel::kGridStep > 0.99)) continue;
      ++corners;
      loose += c.at().err >= 0.25;
      const Homogeneous h = cramer(f.planes[fr.polygon.support], f.planes[c.p], f.planes[c.q]);
      const int v = merged.faces.vertex[std::size_t(merged.faces.begin(int(k)) + (fr.flip ? m - 1 - j : j))];
      const auto [at, added] = point_of_vertex.emplace(v, h);
      if (!added) {
        ASSERT_TRUE(at->second == h) << "a vertex's corners are one point: vertex " << v;
      }
    }
  }
  ASSERT_GE(loose, 512) << "no loose corners: the case is not exercised";
  std::vector<std::pair<Eigen::Vector3d, int>> vertices;
  for (const auto& [v, h] : point_of_vertex) vertices.emplace_back(h.world(), v);
  std::sort(vertices.begin(), vertices.end(), [](const auto& a, const auto& b) { return a.first.x() < b.first.x(); });
  int close_pairs = 0;
  for (std::size_t a = 0; a < vertices.size(); ++a)
    for (std::size_t b = a + 1; b < vertices.size() && vertices[b].first.x() - vertices[a].first.x() < 1e-9; ++b)
      if ((vertices[b].first - vertices[a].first).norm() < 1e-9) {
        ++close_pairs;
        EXPECT_FALSE(point_of_vertex.at(vertices[a].second) == point_of_vertex.at(vertices[b].second))
            << "vertices " << vertices[a].second << " and " << vertices[b].second << " are one point";
      }
  std::printf("%d corners near the caps (%d loose), %zu vertices, %d pairs closer than 1e-9\n", corners, loose,
              vertices.size(), close_pairs);
}

TEST(MeshAssembly, KnownPlanesOfVerticesAndOnPlaneMatchExactIncidence) {
  // Each merged vertex lists the canonical ids of its corner classes' planes (first_class /
  // class_next, linked as the merge makes classes): every corner's three planes are listed for
  // its vertex unless the vertex is a grid point (on_grid: its corners take the class of the
  // first one there, and `at` is the point exactly), every listed plane passes through the
  // vertex (Cramer's rule in unbounded integers), and VertexGeometry::on_plane (the list or the
  // grid point first, else exact) agrees with the exact side for every vertex and every plane of
  // the table. The second solid's vertices are all grid points, the first's partly.
  std::vector<Solid> solids;
  solids.push_back(sphere(1.0, {.segments = 10}) - box({0, 0, 0}, {1, 1, 1}));
  solids.push_back(box({0, 0, 0}, {2, 2, 2}) | box({1, 1, 1}, {3, 3, 3}));
  for (std::size_t i = 0; i < solids.size(); ++i) {
    SCOPED_TRACE(i);
    for (const int variant : {0, 1, 2}) {
      const bool carried = variant == 1;
      if (carried && !solids[i].has_boundary()) continue;
      SCOPED_TRACE(variant);
      const bsp::detail::Fragments f = variant == 2
                                           ? without_some_approximations(bsp::detail::boundary_fragments(solids[i]))
                                           : fragments_of(solids[i], carried);
      const bsp::detail::MergedFragments merged = bsp::detail::merge_vertices(f);
      const bsp::detail::AssemblyVertices& v = merged.vertices;
      ASSERT_EQ(v.first_class.size(), std::size_t(v.size()));
      auto listed = [&](int u) {
        std::set<std::uint32_t> ids;
        int steps = 0;
        for (int k = v.first_class[std::size_t(u)]; k >= 0; k = v.class_next[std::size_t(k)], ++steps) {
          EXPECT_LT(steps, int(v.class_planes.size())) << "the class list of vertex " << u << " does not end";
          if (steps >= int(v.class_planes.size())) break;
          ids.insert(v.class_planes[std::size_t(k)].begin(), v.class_planes[std::size_t(k)].end());
        }
        return ids;
      };
      std::vector<Homogeneous> at;
      for (int u = 0; u < v.size(); ++u) {
        const bsp::detail::PlaneTriple& t = v.triple[std::size_t(u)];
        at.push_back(cramer(f.planes[t.s], f.planes[t.p], f.planes[t.q]));
      }
      ASSERT_EQ(v.on_grid.size(), std::size_t(v.size()));
      int grid_vertices = 0;
      for (int u = 0; u < v.size(); ++u) {
        if (v.on_grid[std::size_t(u)] == 0) continue;
        ++grid_vertices;
        const kernel::ApproxPoint& a = v.at[std::size_t(u)];
        EXPECT_EQ(a.err, 0.0);
        const Homogeneous g{Big(std::int64_t(a.x)), Big(std::int64_t(a.y)), Big(std::int64_t(a.z)), Big(1)};
        EXPECT_TRUE(a.x == std::floor(a.x) && a.y == std::floor(a.y) && a.z == std::floor(a.z)) << u;
        EXPECT_TRUE(at[std::size_t(u)] == g) << "vertex " << u << " is not the grid point it is said to be";
      }
      if (i == 1 && variant != 2) {
        EXPECT_EQ(grid_vertices, v.size());
      }
      std::vector<std::set<std::uint32_t>> known(static_cast<std::size_t>(v.size()));
      for (int u = 0; u < v.size(); ++u) known[std::size_t(u)] = listed(u);
      for (std::size_t k = 0; k < f.fragments.size(); ++k) {
        const auto& fr = f.fragments[k];
        const int m = int(fr.polygon.corners.size());
        for (int j = 0; j < m; ++j) {
          const auto& c = fr.polygon.corners[std::size_t(j)];
          const int u = merged.faces.vertex[std::size_t(merged.faces.begin(int(k)) + (fr.flip ? m - 1 - j : j))];
          if (v.on_grid[std::size_t(u)] != 0) continue;
          for (const std::int32_t plane : {fr.polygon.support, c.p, c.q})
            EXPECT_TRUE(known[std::size_t(u)].count(merged.ids.id[std::size_t(plane)]) == 1) << "corner plane not listed";
        }
      }
      const bsp::detail::VertexGeometry geometry(f.planes, merged.ids, v);
      int on = 0;
      for (int u = 0; u < v.size(); ++u)
        for (std::int32_t plane = 0; plane < f.planes.size(); ++plane) {
          const bool exact = side(at[std::size_t(u)], f.planes[plane]) == 0;
          if (known[std::size_t(u)].count(merged.ids.id[std::size_t(plane)]) == 1) {
            EXPECT_TRUE(exact) << u << " " << plane;
          }
          ASSERT_EQ(geometry.on_plane(u, plane), exact) << "vertex " << u << " plane " << plane;
          on += exact ? 1 : 0;
        }
      EXPECT_GT(on, 3 * v.size());  // (the test sees incidences, not only misses)
    }
  }
}

// After T-junction removal every half-edge u -> w has a half-edge w -> u, as many times.
::testing::AssertionResult EveryHalfEdgeHasAnOpposite(const bsp::detail::FaceList& faces) {
  std::map<std::pair<int, int>, int> count;
  for (int f = 0; f < faces.size(); ++f)
    for (int c = faces.begin(f); c < faces.end(f); ++c)
      ++count[{faces.vertex[std::size_t(c)], faces.vertex[std::size_t(faces.next(f, c))]}];
  for (const auto& [edge, n] : count) {
    const auto it = count.find({edge.second, edge.first});
    if (it == count.end() || it->second != n)
      return ::testing::AssertionFailure() << "half-edge " << edge.first << " -> " << edge.second << " unmatched";
  }
  return ::testing::AssertionSuccess();
}

TEST(MeshAssembly, JunctionRemovalByLinesAndBySearchAgree) {
  // Boundaries with many T-junctions; the line groups and the spatial search (two independent
  // ways to find the vertices inside an edge) must insert the same vertices in the same order.
  std::vector<Solid> solids;
  solids.push_back(sphere(1.0, {.segments = 24}) - box({0, 0, 0}, {1, 1, 1}));
  {
    Solid u;
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> d(0, 40);
    for (int k = 0; k < 25; ++k) {
      const Eigen::Vector3d lo(d(rng) / 16.0, d(rng) / 16.0, d(rng) / 16.0);
      u = std::move(u) | box(lo, lo + Eigen::Vector3d(0.5 + d(rng) / 64.0, 0.5 + d(rng) / 64.0, 0.5 + d(rng) / 64.0));
    }
    solids.push_back(std::move(u));
  }
  solids.push_back(box({0, 0, 0}, {3, 3, 3}) - box({1, -1, 1}, {2, 4, 2}) - box({-1, 1, 1}, {4, 2, 2}));
  for (std::size_t i = 0; i < solids.size(); ++i) {
    SCOPED_TRACE(i);
    const bsp::detail::Fragments f = bsp::detail::boundary_fragments(solids[i]);
    const bsp::detail::MergedFragments merged = bsp::detail::merge_vertices(f);
    const bsp::detail::PlaneIds& ids = merged.ids;
    const bsp::detail::VertexGeometry geometry(f.planes, ids, merged.vertices);
    const bsp::detail::FaceList& faces = merged.faces;
    const bsp::detail::JunctionResult by_lines = bsp::detail::remove_t_junctions(faces, geometry, ids);
    const bsp::detail::JunctionResult by_search = bsp::detail::remove_t_junctions(faces, geometry, ids, {.group_by_lines = false});
    EXPECT_GT(by_lines.open, 0);
    EXPECT_GT(by_lines.by_lines, 0);
    EXPECT_EQ(by_search.by_search, by_search.open);
    EXPECT_TRUE(EveryHalfEdgeHasAnOpposite(by_lines.faces));
    EXPECT_TRUE(EveryHalfEdgeHasAnOpposite(by_search.faces));
    EXPECT_EQ(by_lines.faces.vertex, by_search.faces.vertex);
    EXPECT_EQ(by_lines.faces.start, by_search.faces.start);
  }
}

TEST(MeshAssembly, CanonicalPlaneIdsMatchEqualOrOppositePlanes) {
  const Solid s = sphere(1.0, {.segments = 12}) - box({0, 0, 0}, {1, 1, 1});
  const bsp::detail::Fragments f = bsp::detail::boundary_fragments(s);
  const bsp::detail::PlaneIds ids = bsp::detail::canonical_plane_ids(f.planes);
  ASSERT_EQ(ids.id.size(), std::size_t(f.planes.size()));
  for (std::int32_t i = 0; i < f.planes.size(); ++i)
    for (std::int32_t j = 0; j < f.planes.size(); ++j) {
      const bool same = f.planes[i] == f.planes[j], opposite = f.planes[i] == f.planes[j].opposite();
      ASSERT_EQ(ids.id[std::size_t(i)] == ids.id[std::size_t(j)], same || opposite) << i << " " << j;
      if (same || opposite) {
        ASSERT_EQ(ids.negated[std::size_t(i)] == ids.negated[std::size_t(j)], same) << i << " " << j;
      }
    }
}

TEST(MeshAssembly, HalfEdgeIndexesFindEveryEdgeAndNoOther) {
  // A small random face list against a plain multimap.
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> vertex(0, 29), size(3, 6);
  bsp::detail::FaceList faces;
  for (int f = 0; f < 200; ++f) {
    faces.open_face(0, false);
    for (int k = size(rng); k > 0; --k) faces.add_corner(vertex(rng), 0);
  }
  std::multimap<std::pair<int, int>, int> reference;
  for (int f = 0; f < faces.size(); ++f)
    for (int c = faces.begin(f); c < faces.end(f); ++c)
      reference.insert({{faces.vertex[std::size_t(c)], faces.vertex[std::size_t(faces.next(f, c))]}, c});
  const bsp::detail::OutgoingEdges out(faces, 30);
  bsp::detail::EdgeIndex index(std::size_t(faces.corners()));
  for (const auto& [edge, c] : reference) index.insert(bsp::detail::edge_key(edge.first, edge.second), c);
  for (int u = 0; u < 30; ++u)
    for (int w = 0; w < 30; ++w) {
      std::multiset<int> expected, by_vertex, by_hash;
      for (auto [it, end] = reference.equal_range({u, w}); it != end; ++it) expected.insert(it->second);
      out.for_each(u, w, [&](int c) { by_vertex.insert(c); });
      for (int c = index.find(bsp::detail::edge_key(u, w)); c >= 0; c = index.next(c)) by_hash.insert(c);
      ASSERT_EQ(by_vertex, expected) << u << " -> " << w;
      ASSERT_EQ(by_hash, expected) << u << " -> " << w;
      ASSERT_EQ(out.find(u, w) >= 0, !expected.empty());
    }
}


// exactly_represented (the marks of to_mesh's cheaper clean check): against Cramer's rule in
// unbounded integers. Vertices at grid points (three random planes through a random grid point)
// are all found exact; a `true` is always right (the coordinates times w are the numerators); the
// same planes with one offset moved by 1 (a vertex next to the grid point) are not exact.
TEST(MeshAssembly, ExactlyRepresentedVerticesAreExact) {
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<std::int64_t> coord(-(1 << 25), 1 << 25), normal(-(1 << 20), 1 << 20);
  int found = 0, near = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const kernel::GridPoint g{.x = coord(rng), .y = coord(rng), .z = coord(rng)};
    Plane planes[3];
    for (Plane& p : planes) {
      const std::int64_t a = normal(rng), b = normal(rng), c = trial % 3 == 0 && &p == &planes[0] ? 0 : normal(rng);
      p = kernel::make_plane(a, b, c == 0 && a == 0 && b == 0 ? 1 : c, 0);
      p = kernel::make_plane(p.a, p.b, p.c, -(kernel::Int128(p.a) * g.x + kernel::Int128(p.b) * g.y + kernel::Int128(p.c) * g.z));
    }
    if (!kernel::independent(planes[0], planes[1], planes[2])) continue;
    auto check = [&](const Plane& p, const Plane& q, const Plane& r) {
      const Eigen::Vector3d at = kernel::rounded_vertex(p, q, r, kernel::approximate_vertex(p, q, r));
      const bool exact = bsp::detail::exactly_represented(p, q, r, at);
      if (exact) {
        const Homogeneous h = cramer(p, q, r);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(std::floor(at[k]), at[k]);
        EXPECT_EQ(h.x, Big(std::int64_t(at.x())) * h.w);
        EXPECT_EQ(h.y, Big(std::int64_t(at.y())) * h.w);
        EXPECT_EQ(h.z, Big(std::int64_t(at.z())) * h.w);
      }
      return exact;
    };
    EXPECT_TRUE(check(planes[0], planes[1], planes[2]));
    ++found;
    const Plane moved = kernel::make_plane(planes[0].a, planes[0].b, planes[0].c, planes[0].d + 1);
    if (kernel::independent(moved, planes[1], planes[2])) {
      const Homogeneous h = cramer(moved, planes[1], planes[2]);
      const bool grid_point = h.x % h.w == 0 && h.y % h.w == 0 && h.z % h.w == 0;  // |w| = 1 can happen
      EXPECT_EQ(check(moved, planes[1], planes[2]), grid_point);
      near += grid_point ? 0 : 1;
    }
    // Random offsets: whatever the answer, a `true` must be right (checked inside).
    const Plane loose = kernel::make_plane(planes[2].a, planes[2].b, planes[2].c, planes[2].d + coord(rng));
    if (kernel::independent(planes[0], planes[1], loose)) (void)check(planes[0], planes[1], loose);
  }
  EXPECT_GT(found, 2900);
  EXPECT_GT(near, 2000);
}

// The top face of a plate drilled nine times is one union of fragments with nine holes: not one
// simple polygon, but a few (disks grown through it). Before, it stayed in its convex fragments,
// which the drilling's extended face planes had cut (some 30 per hole), with corners where those
// planes cross inside the face; those are not grid points, and the output check then searched
// the face's long fan triangles against each other (most of drilled_plate's time).
TEST(MeshAssembly, AFaceWithHolesJoinsIntoFewSimpleFacesWithoutInteriorCuts) {
  const int holes = 9;
  Solid plate = box({0, 0, 0}, {10, 10, 1});
  const Solid hole = cylinder(0.3, 2.0, {.segments = 32});
  for (int i = 0; i < holes; ++i) plate = std::move(plate) - translate(hole, {i % 3 + 0.5, i / 3 + 0.5, -0.5});
  const PolygonMesh mesh = to_mesh(plate);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(mesh));
  EXPECT_TRUE(checks::VerticesManifold(mesh));
  EXPECT_TRUE(checks::GenusIs(mesh, holes));
  EXPECT_TRUE(check_closed_manifold(mesh).ok());  // faces simple and planar too
  EXPECT_TRUE(checks::VolumeNear(mesh, 100 - holes * mesh_volume(to_mesh(hole)) / 2, 1e-12));
  int top = 0, largest = 0;
  std::set<int> off_grid;  // corners on the top that are not grid points
  const double step = plate.grid().step();
  for (const auto& f : mesh.faces) {
    if (!std::all_of(f.begin(), f.end(), [&](int v) { return mesh.vertices[std::size_t(v)].z() == 1; })) continue;
    ++top;
    largest = std::max(largest, int(f.size()));
    for (const int v : f)
      for (int k = 0; k < 2; ++k)
        if (std::round(mesh.vertices[std::size_t(v)][k] / step) * step != mesh.vertices[std::size_t(v)][k])
          off_grid.insert(v);
  }
  // Nine holes of 32 corners: at least three faces of at most 128 corners; the cuts left
  // between them (slits) end at a few corners off the grid.
  EXPECT_GE(top, 3);
  EXPECT_LE(top, holes + 1);
  EXPECT_LE(largest, 128);
  EXPECT_LE(int(off_grid.size()), 4 * holes);
}

}  // namespace
}  // namespace sculpt
