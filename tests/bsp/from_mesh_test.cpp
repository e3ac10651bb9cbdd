// Trees built from meshes (from_mesh, autopartition with the expected-depth score): the rebuilt
// solid is the mesh's point set (volume, point classification against an independent winding
// number on the mesh, closed boundary), its tree stays shallow on large inputs, and an
// auxiliary plane's empty side gets the right status.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/tree_arena.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/triangulate.hpp"
#include "support/bench_solids.hpp"
#include "support/mesh_checks.hpp"
#include "support/source_paths.hpp"

namespace sculpt {
namespace {

PolygonMesh bunny() { return read_mesh(sculpt::test::models_dir() + "/bunny.off"); }

// The mesh from_mesh sees: vertices snapped to the grid, faces triangulated as it does.
PolygonMesh snapped(PolygonMesh m) {
  for (Eigen::Vector3d& v : m.vertices) v = kernel::to_world(kernel::snap(v));
  return triangulate(m);
}

// Generalized winding number of a closed mesh at p (sum of the triangles' signed solid angles,
// Van Oosterom & Strackee 1983, over 4 pi), in long double: 1 inside, 0 outside. Independent of
// the BSP code: no planes, no tree.
long double winding_number(const PolygonMesh& m, const Eigen::Vector3d& p) {
  long double total = 0;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {  // triangles (a fan otherwise)
      const Eigen::Vector3d a0 = m.vertices[std::size_t(f[0])] - p, b0 = m.vertices[std::size_t(f[i])] - p,
                            c0 = m.vertices[std::size_t(f[i + 1])] - p;
      const long double a[3] = {a0.x(), a0.y(), a0.z()}, b[3] = {b0.x(), b0.y(), b0.z()}, c[3] = {c0.x(), c0.y(), c0.z()};
      auto dot = [](const long double* u, const long double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
      auto norm = [&](const long double* u) { return std::sqrt(dot(u, u)); };
      const long double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                              a[2] * (b[0] * c[1] - b[1] * c[0]);
      const long double la = norm(a), lb = norm(b), lc = norm(c);
      const long double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
      total += 2 * std::atan2(det, den);
    }
  return total / (4 * std::numbers::pi_v<long double>);
}

// Random grid points in the mesh's box (classification snaps points, so these are exact) are
// inside the solid exactly where the mesh's winding number is 1.
void expect_same_point_set(const Solid& s, const PolygonMesh& mesh, int count, unsigned seed) {
  const PolygonMesh& tri = mesh;
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) p[a] = kernel::to_world(kernel::snap(Eigen::Vector3d::Constant(box.min()[a] + u(rng) * box.sizes()[a])))[a];
    const Classification c = classify(s, p);
    if (c.location == Location::Boundary) continue;
    const long double w = winding_number(tri, p);
    ASSERT_LT(std::fabs(w - std::round(w)), 1e-6) << "winding number not near an integer at " << p.transpose();
    EXPECT_EQ(c.location == Location::Inside, std::lround(w) == 1) << "at " << p.transpose() << ", winding " << double(w);
    ++checked;
  }
  EXPECT_GT(checked, count * 9 / 10);
}

TEST(FromMesh, BunnyIsTheMeshsPointSet) {
  const PolygonMesh mesh = bunny();
  ASSERT_EQ(mesh.faces.size(), 3674u);
  const Solid s = from_mesh(mesh);
  const PolygonMesh grid_mesh = snapped(mesh);
  EXPECT_NEAR(volume(s), mesh_volume(grid_mesh), 1e-11 * mesh_volume(grid_mesh));
  const PolygonMesh back = to_mesh(s);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(back));
  EXPECT_TRUE(checks::GenusIs(back, 0));
  EXPECT_NEAR(double(checks::reference_signed_volume(back)), mesh_volume(grid_mesh), 1e-11 * mesh_volume(grid_mesh));
  expect_same_point_set(s, grid_mesh, 1000, 1);
}

TEST(FromMesh, CurvedAndPerforatedSolidsRebuildToTheSamePointSet) {
  for (const Solid& original : {sphere(1.0, {.segments = 48}), cylinder(1.0, 2.0, {.segments = 40}) - box({0, 0, -1}, {2, 2, 3}),
                                checks::menger_sponge(2)}) {
    const PolygonMesh mesh = to_mesh(original);
    const Solid s = from_mesh(mesh);
    const PolygonMesh grid_mesh = snapped(mesh);
    EXPECT_NEAR(volume(s), mesh_volume(grid_mesh), 1e-11 * std::fabs(mesh_volume(grid_mesh)));
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(s)));
    expect_same_point_set(s, grid_mesh, 600, 2);
  }
}

// Before the expected-depth score a sphere(64) mesh gave a chain of height 2946 and the bunny a
// tree of height 136 (docs/benchmarks.md, "Trees from meshes").
TEST(FromMesh, TreesOfLargeMeshesStayShallow) {
  const TreeStats sphere_tree = tree_stats(from_mesh(to_mesh(sphere(1.0, {.segments = 64}))));
  EXPECT_LE(sphere_tree.height, 300);
  const TreeStats bunny_tree = tree_stats(from_mesh(bunny()));
  EXPECT_LE(bunny_tree.height, 130);
  EXPECT_LE(bunny_tree.nodes, 7055 * 3 / 2);
  const TreeStats menger_tree = tree_stats(from_mesh(to_mesh(checks::menger_sponge(3))));
  EXPECT_LE(menger_tree.height, 40);
}

TEST(FromMesh, TheBuildIsDeterministic) {
  const PolygonMesh mesh = bunny();
  const Solid a = from_mesh(mesh), b = from_mesh(mesh);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (std::size_t i = 0; i < a.nodes().size(); ++i) {
    EXPECT_EQ(a.planes()[a.nodes()[i].plane], b.planes()[b.nodes()[i].plane]) << i;
    EXPECT_EQ(a.nodes()[i].negative, b.nodes()[i].negative) << i;
    EXPECT_EQ(a.nodes()[i].positive, b.nodes()[i].positive) << i;
  }
}

// Options that turn the auxiliary planes off, or make them nearly free (so that the planes just
// past a cell's faces, whose empty side's status is found after the build, are used often),
// give the same point set.
TEST(FromMesh, EveryOptionSettingGivesTheSamePointSet) {
  const PolygonMesh mesh = to_mesh(sphere(1.0, {.segments = 24}) | box({0.5, 0.5, 0.5}, {1.5, 1.25, 1.5}));
  const PolygonMesh grid_mesh = snapped(mesh);
  for (const FromMeshOptions& o : {FromMeshOptions{.auxiliary_planes = false}, FromMeshOptions{.auxiliary_cost = 0.0},
                                   FromMeshOptions{.candidates = 1, .sample = 1, .volume_samples = 0},
                                   FromMeshOptions{.separating_planes = true},
                                   FromMeshOptions{.volume_samples = 100000, .point_sample = 1000, .auxiliary_cost = 0.0}}) {
    const Solid s = from_mesh(mesh, o);
    EXPECT_NEAR(volume(s), mesh_volume(grid_mesh), 1e-11 * mesh_volume(grid_mesh));
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(s)));
    expect_same_point_set(s, grid_mesh, 500, 3);
  }
}

// A clean import keeps its triangles while its tree waits (DeferredTree::source_mesh): the exact
// boundary without cleaning is those triangles at their grid points, and a general rotation, which
// starts from that boundary, gives the rotated mesh's point set and volume.
TEST(FromMesh, ACleanImportKeepsItsTrianglesForItsBoundaryAndTurns) {
  const PolygonMesh mesh = bunny();
  const PolygonMesh grid_mesh = snapped(mesh);
  const Solid s = from_mesh(mesh, {.snapped_mesh_is_clean = true});
  ASSERT_TRUE(s.tree_deferred());
  const PolygonMesh boundary = to_mesh(s, {.clean = false});
  EXPECT_TRUE(s.tree_deferred());  // nothing built for it
  ASSERT_EQ(boundary.faces.size(), mesh.faces.size());
  std::set<std::array<double, 3>> expected, got;
  for (const auto& v : grid_mesh.vertices) expected.insert({v.x(), v.y(), v.z()});
  for (const auto& f : boundary.faces) {
    ASSERT_EQ(f.size(), 3u);
    for (int v : f)
      got.insert({boundary.vertices[std::size_t(v)].x(), boundary.vertices[std::size_t(v)].y(),
                  boundary.vertices[std::size_t(v)].z()});
  }
  EXPECT_EQ(got, expected);
  EXPECT_EQ(volume(s), mesh_volume(grid_mesh));
  // The turn of issue 33's benchmark: 33 degrees about (1, 1, 0) through the box centre.
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  const Eigen::Affine3d turn = Eigen::Translation3d(box.center()) *
                               Eigen::AngleAxisd(33 * std::numbers::pi / 180, Eigen::Vector3d(1, 1, 0).normalized()) *
                               Eigen::Translation3d(-box.center());
  PolygonMesh turned_mesh = grid_mesh;
  for (auto& v : turned_mesh.vertices) v = turn * v;
  const Solid turned = transform(s, turn);
  // Snapping moves each vertex by at most half a grid step's diagonal.
  EXPECT_NEAR(volume(turned), mesh_volume(turned_mesh), 1e-5 * mesh_volume(turned_mesh));
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(turned)));
  expect_same_point_set(turned, turned_mesh, 500, 4);
}

// Bernstein & Fussell 2009, sec. 3: a polygon's edge may lie on any plane through it. An import's
// triangles take the support of the triangle across each side (or its opposite) where the two are
// not nearly parallel, their own transverse plane elsewhere. By the definition, checked exactly on
// the grid points: every corner's edge plane contains the side's two ends and leaves the third
// corner strictly on its negative side, and the corner is the support ∩ p ∩ q it names (p and q
// contain it). Meshes: a faceted sphere (no coplanar neighbours: one plane per triangle, and an
// opposite for some), a box split into triangles (each face's two triangles coplanar: transverse planes
// there; supports across the convex edges), an L-shaped prism (concave edges: opposites), and the bunny.
TEST(FromMesh, TriangleSidesLieOnPlanesThroughThem) {
  PolygonMesh l_shape;  // an L-shaped prism: the extrusion of an L, two concave edges
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (double z : {0.0, 1.0})
    for (const auto& p : xy) l_shape.vertices.emplace_back(p[0], p[1], z);
  l_shape.faces.push_back({5, 4, 3, 2, 1, 0});
  l_shape.faces.push_back({6, 7, 8, 9, 10, 11});
  for (int i = 0; i < 6; ++i) l_shape.faces.push_back({i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6});
  const struct {
    std::string name;
    PolygonMesh mesh;
  } cases[] = {{"sphere", triangulate(to_mesh(sphere(1.0, {.segments = 24})))},
               {"box", triangulate(to_mesh(box({0, 0, 0}, {1, 2, 3})))},
               {"L", triangulate(l_shape)},
               {"bunny", bunny()}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const PolygonMesh grid_mesh = snapped(c.mesh);
    const Solid s = from_mesh(c.mesh, {.snapped_mesh_is_clean = true});
    bsp::detail::Arena arena;
    arena.append(s);
    const FragmentList fragments = arena.boundary_of(s);
    ASSERT_EQ(fragments.size(), grid_mesh.faces.size());
    std::set<std::int32_t> planes_used;
    for (std::size_t k = 0; k < fragments.size(); ++k) {
      const kernel::PolygonView poly = fragments[k].polygon;
      ASSERT_EQ(poly.corners.size(), 3u);
      kernel::GridPoint v[3];
      for (std::size_t i = 0; i < 3; ++i) {
        const kernel::ApproxPoint at = poly.corners[i].at();
        ASSERT_EQ(at.err, 0);  // an import's corners are its grid points
        v[i] = {std::int64_t(at.x), std::int64_t(at.y), std::int64_t(at.z)};
      }
      planes_used.insert(poly.support);
      for (std::size_t i = 0; i < 3; ++i) {
        const kernel::Corner& corner = poly.corners[i];
        const kernel::Plane& edge = arena.planes[corner.edge];
        planes_used.insert(corner.edge);
        EXPECT_EQ(arena.planes[poly.support].eval(v[i]), 0);
        EXPECT_EQ(edge.eval(v[i]), 0) << k << " " << i;
        EXPECT_EQ(edge.eval(v[(i + 1) % 3]), 0) << k << " " << i;
        EXPECT_LT(edge.eval(v[(i + 2) % 3]), 0) << k << " " << i;
        EXPECT_EQ(arena.planes[corner.p].eval(v[i]), 0) << k << " " << i;
        EXPECT_EQ(arena.planes[corner.q].eval(v[i]), 0) << k << " " << i;
        EXPECT_NE(corner.p, corner.q);
      }
    }
    // Four planes a triangle before; now the supports, some opposites and the few transverse planes.
    const std::size_t triangles = fragments.size();
    EXPECT_LE(planes_used.size(), 3 * triangles) << "planes " << planes_used.size() << ", triangles " << triangles;
    if (c.name == "sphere" || c.name == "bunny") {
      EXPECT_LE(planes_used.size(), 2 * triangles) << "planes " << planes_used.size() << ", triangles " << triangles;
    }
    EXPECT_EQ(volume(s), mesh_volume(grid_mesh));
    EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(s)));
  }
}

}  // namespace
}  // namespace sculpt
