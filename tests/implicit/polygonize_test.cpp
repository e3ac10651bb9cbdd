// Implicit solids (lib/implicit/polygonize.hpp): meshes of {f <= 0} in a box checked against the
// analytic surfaces (sphere, torus: distances in closed form, both ways), mesh invariants
// (closed, oriented, manifold, no self-intersections by our validator and by CGAL; Euler
// characteristic, components) and analytic volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <unordered_map>
#include <vector>

#include "implicit/detail/refine.hpp"
#include "implicit/detail/simplify.hpp"
#include "implicit/polygonize.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/self_intersection.hpp"
#include "support/cgal_mesh_check.hpp"
#include "support/point_triangle.hpp"
#include "support/sanitizer_share.hpp"

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;
using test_support::point_triangle_distance;
constexpr double kPi = std::numbers::pi;

Expression sphere(const Vec& c, double r) {
  ExpressionBuilder b;
  const Term d = b.add(b.add(b.pow(b.sub(b.x(), b.constant(c.x())), 2), b.pow(b.sub(b.y(), b.constant(c.y())), 2)),
                       b.pow(b.sub(b.z(), b.constant(c.z())), 2));
  return b.finish(b.sub(d, b.constant(r * r)));
}

/// (sqrt(x^2 + y^2) - R)^2 + z^2 - r^2
Expression torus(double R, double r) {
  ExpressionBuilder b;
  const Term rho = b.sqrt(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)));
  return b.finish(b.sub(b.add(b.pow(b.sub(rho, b.constant(R)), 2), b.pow(b.z(), 2)), b.constant(r * r)));
}

double torus_distance(const Vec& p, double R, double r) {
  const double rho = std::hypot(p.x(), p.y());
  return std::abs(std::hypot(rho - R, p.z()) - r);
}

Vec torus_point(double u, double v, double R, double r) {
  return {(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)};
}


/// Distance from points to a triangle mesh, by a uniform grid of triangle boxes; only distances
/// up to `reach` are exact (farther ones come back as at least `reach`).
class MeshDistance {
 public:
  MeshDistance(const PolygonMesh& m, double reach) : m_(m), cell_(reach) {
    for (int f = 0; f < int(m.faces.size()); ++f) {
      Eigen::AlignedBox3d box;
      for (int v : m.faces[f]) box.extend(m.vertices[v]);
      const auto lo = index(box.min()), hi = index(box.max());
      for (long x = lo[0]; x <= hi[0]; ++x)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long z = lo[2]; z <= hi[2]; ++z) grid_[key(x, y, z)].push_back(f);
    }
  }
  double operator()(const Vec& p) const {
    double best = cell_;
    const auto c = index(p);
    for (long x = c[0] - 1; x <= c[0] + 1; ++x)
      for (long y = c[1] - 1; y <= c[1] + 1; ++y)
        for (long z = c[2] - 1; z <= c[2] + 1; ++z) {
          const auto it = grid_.find(key(x, y, z));
          if (it == grid_.end()) continue;
          for (int f : it->second) {
            const auto& t = m_.faces[f];
            best = std::min(best, point_triangle_distance(p, m_.vertices[t[0]], m_.vertices[t[1]], m_.vertices[t[2]]));
          }
        }
    return best;
  }

 private:
  std::array<long, 3> index(const Vec& p) const {
    return {long(std::floor(p.x() / cell_)), long(std::floor(p.y() / cell_)), long(std::floor(p.z() / cell_))};
  }
  static long long key(long x, long y, long z) { return ((x + 100000LL) * 200000LL + (y + 100000LL)) * 200000LL + z; }
  const PolygonMesh& m_;
  double cell_;
  std::unordered_map<long long, std::vector<int>> grid_;
};

/// Largest analytic distance of the mesh's vertices and of points spread over each triangle.
double mesh_to_surface(const PolygonMesh& m, const std::function<double(const Vec&)>& distance) {
  double worst = 0;
  for (const Vec& v : m.vertices) worst = std::max(worst, distance(v));
  for (const auto& f : m.faces) {
    const Vec &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j) worst = std::max(worst, distance((a * (4 - i - j) + b * i + c * j) / 4.0));
  }
  return worst;
}

void expect_solid_mesh(const PolygonMesh& m, int components, int euler) {
  ASSERT_FALSE(m.faces.empty());
  for (const auto& f : m.faces) ASSERT_EQ(f.size(), 3u);
  const ValidationReport report = check_closed_manifold(m);
  EXPECT_TRUE(report.ok()) << report.summary(5);
  EXPECT_EQ(component_count(m), components);
  EXPECT_EQ(euler_characteristic(m), euler);
  EXPECT_GT(mesh_volume(m), 0.0);
  EXPECT_TRUE(checks::CleanForOtherTools(m.vertices, m.faces));
}

TEST(Polygonize, SphereIsAClosedManifoldWithinTol) {
  const double tol = 5e-3;
  const PolygonizeResult r = polygonize(sphere({0.1, -0.05, 0.02}, 1.0), {.box = {.lo = Vec(-1.5, -1.5, -1.5), .hi = Vec(1.5, 1.5, 1.5)}, .tolerance = tol});
  expect_solid_mesh(r.mesh, 1, 2);
  const auto distance = [](const Vec& p) { return std::abs((p - Vec(0.1, -0.05, 0.02)).norm() - 1.0); };
  EXPECT_LE(mesh_to_surface(r.mesh, distance), tol);
  const MeshDistance to_mesh(r.mesh, 4 * tol);
  double worst = 0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j < 400; ++j) {
      const double th = kPi * i / 200, ph = 2 * kPi * j / 400;
      worst = std::max(worst, to_mesh(Vec(0.1, -0.05, 0.02) + Vec(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th))));
    }
  EXPECT_LE(worst, tol);
  EXPECT_NEAR(mesh_volume(r.mesh), 4.0 / 3.0 * kPi, 4 * kPi * tol);
}

// The collapses on their own: the input stays as it was, the output is a closed manifold of the
// same topology whose vertices are input vertices (half-edge collapses move none), and retrying
// only vertices whose 2-ring changed gives exactly the mesh of retrying all of them every sweep.
TEST(Polygonize, SimplifyKeepsItsInputAndSkipsOnlyTriesThatFailAgain) {
  const double tol = 1e-2;
  struct Case {
    Expression f;
    Box box;
    int components, euler;
  };
  const Box torus_box{.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)};
  const Box cut_box{.lo = Vec(-0.3, -1.5, -1.5), .hi = Vec(1.5, 1.5, 1.5)};  // the sphere cut by x = -0.3
  for (const Case& c : {Case{torus(1.0, 0.4), torus_box, 1, 0}, Case{sphere({0.1, 0, 0}, 1.0), cut_box, 1, 2}}) {
    const PolygonizeResult marched = polygonize(c.f, {.box = c.box, .tolerance = tol, .simplify = false});
    const PolygonMesh before = marched.mesh;
    std::vector<bool> locked(before.vertices.size(), false);
    for (std::size_t v = 0; v < locked.size(); ++v)
      for (int a = 0; a < 3; ++a)
        locked[v] = locked[v] || before.vertices[v][a] == c.box.lo[a] || before.vertices[v][a] == c.box.hi[a];
    const detail::SimplifyResult fast = detail::simplify(marched.mesh, locked, c.f, {.tolerance = 0.7 * tol});
    const detail::SimplifyResult all = detail::simplify(marched.mesh, locked, c.f, {.tolerance = 0.7 * tol, .retry_all = true});
    EXPECT_EQ(marched.mesh.vertices, before.vertices);
    EXPECT_EQ(marched.mesh.faces, before.faces);
    expect_solid_mesh(fast.mesh, c.components, c.euler);
    EXPECT_LT(fast.mesh.faces.size(), before.faces.size() / 4);
    EXPECT_GT(fast.collapses, 0);
    std::unordered_map<double, std::vector<Vec>> by_x;  // input vertices by x, to look each output vertex up
    for (const Vec& v : before.vertices) by_x[v.x()].push_back(v);
    for (const Vec& v : fast.mesh.vertices) {
      const auto it = by_x.find(v.x());
      ASSERT_TRUE(it != by_x.end());
      EXPECT_TRUE(std::find(it->second.begin(), it->second.end(), v) != it->second.end());
    }
    EXPECT_EQ(fast.collapses, all.collapses);
    EXPECT_EQ(fast.mesh.vertices, all.mesh.vertices);
    EXPECT_EQ(fast.mesh.faces, all.mesh.faces);
  }
}

// The edge splits on their own: a coarse marched sphere (tol 5e-2) refined to 2e-3 keeps its
// vertices, stays a closed manifold sphere, puts every new vertex on the sphere, and brings
// every triangle within the bound at its centroid and edge midpoints (analytic distance, which
// for this f is within 1e-3 relative of |f| / |grad f| there) and within 1.5 times it at 15
// points per triangle; a mesh that is not closed is refused.
TEST(Polygonize, RefineSplitsTowardsTheSurface) {
  const Vec centre(0.1, -0.05, 0.02);
  const Expression f = sphere(centre, 1.0);
  const Box box{.lo = Vec(-1.5, -1.5, -1.5), .hi = Vec(1.5, 1.5, 1.5)};
  const PolygonizeResult coarse = polygonize(f, {.box = box, .tolerance = 5e-2, .simplify = false});
  PolygonMesh mesh = coarse.mesh;
  std::vector<bool> locked(mesh.vertices.size(), false);
  const double bound = 2e-3;
  const detail::RefineResult r = detail::refine(mesh, locked, f, {.tolerance = bound, .limit = bound, .min_edge = 1e-4, .max_splits = 1'000'000});
  ASSERT_TRUE(r.ok);
  EXPECT_GT(r.splits, 0);
  EXPECT_EQ(locked.size(), mesh.vertices.size());
  ASSERT_GT(mesh.vertices.size(), coarse.mesh.vertices.size());
  for (std::size_t v = 0; v < coarse.mesh.vertices.size(); ++v) EXPECT_EQ(mesh.vertices[v], coarse.mesh.vertices[v]);
  for (std::size_t v = coarse.mesh.vertices.size(); v < mesh.vertices.size(); ++v)
    EXPECT_LE(std::abs((mesh.vertices[v] - centre).norm() - 1.0), 1e-9);
  expect_solid_mesh(mesh, 1, 2);
  const auto distance = [&](const Vec& p) { return std::abs((p - centre).norm() - 1.0); };
  for (const auto& t : mesh.faces) {
    const Vec &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    for (const Vec& p : {Vec((a + b + c) / 3.0), Vec(0.5 * (a + b)), Vec(0.5 * (b + c)), Vec(0.5 * (c + a))})
      EXPECT_LE(distance(p), 1.001 * bound);
  }
  EXPECT_LE(mesh_to_surface(mesh, distance), 1.5 * bound);
  EXPECT_LT(mesh_to_surface(coarse.mesh, distance), 5e-2);
  EXPECT_GT(mesh_to_surface(coarse.mesh, distance), 4 * bound);  // the splits had work to do

  PolygonMesh open = coarse.mesh;
  open.faces.pop_back();
  std::vector<bool> open_locked(open.vertices.size(), false);
  EXPECT_FALSE(detail::refine(open, open_locked, f, {.tolerance = bound, .limit = bound, .min_edge = 1e-4, .max_splits = 1'000'000}).ok);
}

// With simplify, the torus is marched on the coarse octree and refined by edge splits: far fewer
// triangles marched than by the fine octree (the one without simplify), the same guarantees.
TEST(Polygonize, CoarseOctreeWithEdgeSplits) {
  const Box box{.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)};
  const double tol = 2e-3;
  const PolygonizeResult fine = polygonize(torus(1.0, 0.4), {.box = box, .tolerance = tol, .simplify = false});
  const PolygonizeResult r = polygonize(torus(1.0, 0.4), {.box = box, .tolerance = tol});
  EXPECT_TRUE(r.coarse);
  EXPECT_FALSE(fine.coarse);
  EXPECT_GT(r.refinements, 0);
  EXPECT_FALSE(r.simplify_rejected);
  EXPECT_LT(2 * r.marched_triangles, fine.marched_triangles);
  EXPECT_LT(10 * r.mesh.faces.size(), std::size_t(fine.marched_triangles));
  expect_solid_mesh(r.mesh, 1, 0);
  EXPECT_LE(mesh_to_surface(r.mesh, [](const Vec& p) { return torus_distance(p, 1.0, 0.4); }), tol);
}

// accept_simplified replaces the exact self-intersection test of the simplified mesh: a test
// that passes keeps the very mesh the default test keeps (the torus's is unintersecting); one that
// fails drops the simplified meshes of both octrees, and the fine octree's marched mesh, closed and
// unintersecting by construction, is returned unsimplified.
TEST(Polygonize, AcceptSimplifiedDecidesInsteadOfTheSelfIntersectionTest) {
  const Box box{.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)};
  const double tol = 4e-3;
  const PolygonizeResult plain = polygonize(torus(1.0, 0.4), {.box = box, .tolerance = tol});
  EXPECT_FALSE(plain.accepted);
  int calls = 0;
  const PolygonizeResult yes = polygonize(torus(1.0, 0.4), {.box = box, .tolerance = tol, .accept_simplified = [&](const PolygonMesh& m) {
    ++calls;
    EXPECT_TRUE(find_self_intersections(m, {.max_pairs = 1}).empty());
    return true;
  }});
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(yes.accepted);
  EXPECT_TRUE(yes.coarse);
  EXPECT_EQ(yes.mesh.faces, plain.mesh.faces);
  EXPECT_EQ(yes.mesh.vertices, plain.mesh.vertices);
  calls = 0;
  const PolygonizeResult no = polygonize(torus(1.0, 0.4), {.box = box, .tolerance = tol, .accept_simplified = [&](const PolygonMesh&) {
    ++calls;
    return false;
  }});
  EXPECT_EQ(calls, 2);  // the coarse octree's simplified mesh, then the fine one's
  EXPECT_FALSE(no.accepted);
  EXPECT_FALSE(no.coarse);
  EXPECT_TRUE(no.simplify_rejected);
  EXPECT_EQ(no.collapses, 0);
  EXPECT_EQ(long(no.mesh.faces.size()), no.marched_triangles);
  expect_solid_mesh(no.mesh, 1, 0);
  EXPECT_TRUE(find_self_intersections(no.mesh, {.max_pairs = 1}).empty());
}

TEST(Polygonize, CoarseCellsAtTheBoxWhereTheSurfaceMeetsItStayWithinTol) {
  // The unit sphere cut by the box at z = 0.3 (and its other faces far off): the cells at the
  // rim, where the surface meets the box, keep the fine criterion (their triangles at the box
  // are not split); the cells at the other faces, which the surface does not reach, are coarse.
  // Both ways within tol, on the coarse octree, against the analytic cap and disc.
  const double tol = 2e-3, cut = 0.3, rim = std::sqrt(1 - cut * cut);
  const PolygonizeResult r =
      polygonize(sphere({0, 0, 0}, 1.0), {.box = {.lo = Vec(-1.3, -1.3, cut), .hi = Vec(1.3, 1.3, 1.3)}, .tolerance = tol});
  EXPECT_TRUE(r.coarse);
  expect_solid_mesh(r.mesh, 1, 2);
  const auto distance = [&](const Vec& p) {  // to the cap (z > cut) or the disc (on the face)
    if (p.z() > cut) return std::abs(p.norm() - 1.0);
    return std::max(0.0, std::hypot(p.x(), p.y()) - rim);
  };
  EXPECT_LE(mesh_to_surface(r.mesh, distance), tol);
  const MeshDistance to_mesh(r.mesh, 4 * tol);
  double worst = 0;
  const double last = std::acos(cut);
  for (int i = 0; i <= 150; ++i)
    for (int j = 0; j < 400; ++j) {
      const double th = last * i / 150, ph = 2 * kPi * j / 400;
      worst = std::max(worst, to_mesh(Vec(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th))));
      worst = std::max(worst, to_mesh(Vec(rim * i / 150 * std::cos(ph), rim * i / 150 * std::sin(ph), cut)));
    }
  EXPECT_LE(worst, tol);
}

TEST(Polygonize, ACapPokingThroughABoxFaceStaysInTheBox) {
  // A ball mostly outside the box pokes 0.01 through its top face between lattice points: the
  // solid is the thin cap inside. Every vertex lies in the box (edge splits put no vertex
  // outside it), the mesh is closed, within tol of the sphere or the face, and its volume is
  // the cap's, pi h^2 (3 r - h) / 3, within the boundary's area times tol.
  const double tol = 2e-3, r = 1.0, h = 0.01;
  const Vec centre(0.137, 0.071, 1.0 + r - h);
  const Box box{.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)};
  const PolygonizeResult p = polygonize(sphere(centre, r), {.box = box, .tolerance = tol});
  expect_solid_mesh(p.mesh, 1, 2);
  for (const Vec& v : p.mesh.vertices) {
    EXPECT_TRUE((v.array() >= box.lo.array()).all() && (v.array() <= box.hi.array()).all()) << v.transpose();
  }
  const auto distance = [&](const Vec& q) {
    if (q.z() < 1.0) return std::abs((q - centre).norm() - r);
    return std::max(0.0, std::hypot(q.x() - centre.x(), q.y() - centre.y()) - std::sqrt(r * r - (r - h) * (r - h)));
  };
  EXPECT_LE(mesh_to_surface(p.mesh, distance), tol);
  // within tol of the surface: the volume within its area (cap 2 pi r h, disc pi a^2) times tol
  const double area = 2 * kPi * r * h + kPi * (r * r - (r - h) * (r - h));
  EXPECT_NEAR(mesh_volume(p.mesh), kPi * h * h * (3 * r - h) / 3, area * tol);
}

TEST(Polygonize, SurfaceThroughLatticePointsExactly) {
  // The box [-2, 2]^3 puts lattice points on the unit sphere (f == 0 there, counted as inside).
  const PolygonizeResult r = polygonize(sphere({0, 0, 0}, 1.0), {.box = {.lo = Vec(-2, -2, -2), .hi = Vec(2, 2, 2)}, .tolerance = 1e-2});
  expect_solid_mesh(r.mesh, 1, 2);
  EXPECT_LE(mesh_to_surface(r.mesh, [](const Vec& p) { return std::abs(p.norm() - 1.0); }), 1e-2);
}

TEST(Polygonize, TorusWithinTolBothWaysGenusOne) {
  const double R = 1.0, rr = 0.4;
  for (const double tol : {1e-2, 2e-3}) {
    SCOPED_TRACE(tol);
    const PolygonizeResult r = polygonize(torus(R, rr), {.box = {.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)}, .tolerance = tol});
    expect_solid_mesh(r.mesh, 1, 0);
    EXPECT_EQ(genus(r.mesh), 1);
    EXPECT_LE(mesh_to_surface(r.mesh, [&](const Vec& p) { return torus_distance(p, R, rr); }), tol);
    const MeshDistance to_mesh(r.mesh, 4 * tol);
    double worst = 0;
    const int n = (tol < 5e-3 ? 1200 : 500) / checks::kSanitizerStride;  // samples around the torus
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n / 2; ++j) worst = std::max(worst, to_mesh(torus_point(2 * kPi * (i + 0.37) / n, 2 * kPi * (j + 0.61) / (n / 2), R, rr)));
    EXPECT_LE(worst, tol);
  }
}

TEST(Polygonize, TorusVolumeConverges) {
  const double R = 1.0, rr = 0.4, exact = 2 * kPi * kPi * R * rr * rr, area = 4 * kPi * kPi * R * rr;
  double previous = 1e9;
  for (const double tol : {2e-2, 8e-3, 2e-3, 5e-4}) {
    SCOPED_TRACE(tol);
    const PolygonizeResult r = polygonize(torus(R, rr), {.box = {.lo = Vec(-1.5, -1.5, -0.5), .hi = Vec(1.5, 1.5, 0.5)}, .tolerance = tol});
    const double error = std::abs(mesh_volume(r.mesh) - exact);
    EXPECT_LE(error, area * tol);  // what a Hausdorff distance of tol allows
    EXPECT_LT(error, previous);
    previous = error;
  }
  EXPECT_LT(previous, 1e-3 * exact);
}

TEST(Polygonize, TwoSeparateSpheresAreTwoComponents) {
  ExpressionBuilder b;
  auto ball = [&](double cx, double r) {
    return b.sub(b.add(b.add(b.pow(b.sub(b.x(), b.constant(cx)), 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)), b.constant(r * r));
  };
  const Expression f = b.finish(b.min(ball(-0.6, 0.5), ball(0.7, 0.4)));
  const PolygonizeResult r = polygonize(f, {.box = {.lo = Vec(-1.3, -0.7, -0.7), .hi = Vec(1.3, 0.7, 0.7)}, .tolerance = 5e-3});
  expect_solid_mesh(r.mesh, 2, 4);
  EXPECT_NEAR(mesh_volume(r.mesh), 4.0 / 3.0 * kPi * (0.125 + 0.064), 0.02);
}

TEST(Polygonize, TinySphereBetweenLatticePointsIsFound) {
  // A ball of diameter 0.05 in a box of side 4 at tol 0.01: a uniform grid at the cells' size
  // where the big sphere is flat (about 0.125) steps over it; the interval search finds it.
  ExpressionBuilder b;
  auto ball = [&](const Vec& c, double r) {
    return b.sub(b.add(b.add(b.pow(b.sub(b.x(), b.constant(c.x())), 2), b.pow(b.sub(b.y(), b.constant(c.y())), 2)),
                       b.pow(b.sub(b.z(), b.constant(c.z())), 2)),
                 b.constant(r * r));
  };
  const Vec small(1.4321, 1.2345, -1.3579);
  const Expression f = b.finish(b.min(ball({0, 0, 0}, 1.0), ball(small, 0.025)));
  const PolygonizeResult r = polygonize(f, {.box = {.lo = Vec(-2, -2, -2), .hi = Vec(2, 2, 2)}, .tolerance = 1e-2});
  expect_solid_mesh(r.mesh, 2, 4);
  int near_small = 0;
  for (const Vec& v : r.mesh.vertices) {
    if ((v - small).norm() < 0.1) {
      ++near_small;
      EXPECT_NEAR((v - small).norm(), 0.025, 1e-2);
    }
  }
  EXPECT_GT(near_small, 4);
}

TEST(Polygonize, ThinShellKeepsBothSides) {
  // |(|p| - 0.3)| - 0.005 <= 0: a shell 0.01 thick, half of tol (cells where the sphere is flat
  // would be about 0.05 wide); feature_size 0.01 finds it and splits the cells it crosses twice.
  ExpressionBuilder b;
  const Term norm = b.sqrt(b.add(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)));
  const Expression f = b.finish(b.sub(b.abs(b.sub(norm, b.constant(0.3))), b.constant(0.005)));
  // One octant of it (the box's faces through the centre close the shell's piece into one solid):
  // the same cells where the shell is met, an eighth of the work.
  const Box box{.lo = Vec(0, 0, 0), .hi = Vec(0.4, 0.4, 0.4)};
  expect_solid_mesh(polygonize(f, {.box = box, .tolerance = 2e-2, .feature_size = 1e-2}).mesh, 1, 2);
  // Unsimplified, the marched shell has its volume (simplified, each sheet may move by up to tol,
  // more than the shell is thick).
  const PolygonizeResult r = polygonize(f, {.box = box, .tolerance = 2e-2, .feature_size = 1e-2, .simplify = false});
  expect_solid_mesh(r.mesh, 1, 2);
  const double exact = kPi / 6.0 * (std::pow(0.305, 3) - std::pow(0.295, 3));
  EXPECT_NEAR(mesh_volume(r.mesh), exact, 0.05 * exact);
}

TEST(Polygonize, BoxFacesCloseTheSolid) {
  // The unit sphere cut by the box at z = 0.3: a spherical cap closed by a disc on the face.
  const PolygonizeResult r = polygonize(sphere({0, 0, 0}, 1.0), {.box = {.lo = Vec(-1.2, -1.2, 0.3), .hi = Vec(1.2, 1.2, 1.2)}, .tolerance = 2e-3});
  expect_solid_mesh(r.mesh, 1, 2);
  const double h = 0.7, exact = kPi * h * h * (3 - h) / 3;
  EXPECT_NEAR(mesh_volume(r.mesh), exact, 0.01 * exact);
  // A function negative everywhere gives the box itself; positive everywhere, nothing.
  ExpressionBuilder b;
  const Expression negative = b.finish(b.sub(b.pow(b.x(), 2), b.constant(10)));
  const PolygonizeResult full = polygonize(negative, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 2, 1)}, .tolerance = 1e-2});
  expect_solid_mesh(full.mesh, 1, 2);
  EXPECT_NEAR(mesh_volume(full.mesh), 12.0, 1e-12);
  ExpressionBuilder c;
  const Expression positive = c.finish(c.add(c.pow(c.x(), 2), c.constant(1)));
  EXPECT_TRUE(polygonize(positive, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-2}).mesh.faces.empty());
}

TEST(Polygonize, AdaptiveMoreTrianglesWhereItBends) {
  // An ellipsoid with semi-axes 1, 1, 0.25: curvature 16 at its rim, 0.25 at its poles.
  ExpressionBuilder b;
  const Expression f = b.finish(b.sub(b.add(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)), b.mul(b.constant(16), b.pow(b.z(), 2))), b.constant(1)));
  const PolygonizeResult r = polygonize(f, {.box = {.lo = Vec(-1.3, -1.3, -0.4), .hi = Vec(1.3, 1.3, 0.4)}, .tolerance = 2e-3});
  expect_solid_mesh(r.mesh, 1, 2);
  double rim = 0, pole = 0;
  int rim_n = 0, pole_n = 0;
  for (const auto& t : r.mesh.faces) {
    const Vec c = (r.mesh.vertices[t[0]] + r.mesh.vertices[t[1]] + r.mesh.vertices[t[2]]) / 3;
    const double edge = (r.mesh.vertices[t[0]] - r.mesh.vertices[t[1]]).norm();
    if (std::hypot(c.x(), c.y()) > 0.97) rim += edge, ++rim_n;
    if (std::hypot(c.x(), c.y()) < 0.3) pole += edge, ++pole_n;
  }
  ASSERT_GT(rim_n, 0);
  ASSERT_GT(pole_n, 0);
  EXPECT_GT(pole / pole_n, 2.5 * rim / rim_n);
}

TEST(Polygonize, BadInput) {
  const Expression f = sphere({0, 0, 0}, 1.0);
  EXPECT_THROW((void)polygonize(f, {.box = {.lo = Vec(0, 0, 0), .hi = Vec(0, 1, 1)}}), InvalidInput);
  EXPECT_THROW((void)polygonize(f, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 0}), InvalidInput);
  EXPECT_THROW((void)polygonize(f, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-7}), InvalidInput);
  EXPECT_THROW((void)polygonize(f, {.box = {.lo = Vec(-2, -2, -2), .hi = Vec(2, 2, 2)}, .tolerance = 1e-3, .max_cells = 1000}),
               GeometryError);
  // 1 / x - 2 is not finite on the plane x = 0, which holds lattice points of this box.
  ExpressionBuilder b;
  const Expression pole = b.finish(b.sub(b.div(b.constant(1), b.x()), b.constant(2)));
  EXPECT_THROW((void)polygonize(pole, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-2}), NonFiniteValue);
}

}  // namespace
}  // namespace sculpt::implicit
