// positive_winding_solid: the solid of a closed mesh that intersects itself is where its winding
// number is positive. References independent of the tree: volumes computed by hand (overlapping
// boxes, a box inside another facing either way), exact set operations on the separate shells
// (the bunny and a turned copy written as one mesh), the mesh's signed volume where the overlap is
// small, and the winding number at random grid points as a sum of solid angles (Van Oosterom &
// Strackee 1983) against classify.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/winding_solid.hpp"
#include "kernel/grid.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/shapes.hpp"
#include "support/source_paths.hpp"

namespace sculpt {
namespace {

using test_shapes::box;
using test_shapes::merged;

PolygonMesh reversed(PolygonMesh m) {
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  return m;
}

PolygonMesh moved(PolygonMesh m, const Eigen::Affine3d& t) {
  for (Eigen::Vector3d& v : m.vertices) v = t * v;
  return m;
}

// The winding number of a closed mesh at p: the sum of its triangles' (fans') signed solid angles
// over 4 pi, in long double. No planes, no tree.
long double solid_angle_winding(const PolygonMesh& m, const Eigen::Vector3d& p) {
  long double total = 0;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Eigen::Vector3d a0 = m.vertices[std::size_t(f[0])] - p, b0 = m.vertices[std::size_t(f[i])] - p,
                            c0 = m.vertices[std::size_t(f[i + 1])] - p;
      const long double a[3] = {a0.x(), a0.y(), a0.z()}, b[3] = {b0.x(), b0.y(), b0.z()},
                        c[3] = {c0.x(), c0.y(), c0.z()};
      auto dot = [](const long double* u, const long double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
      const long double det =
          a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
      const long double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
      total += 2 * std::atan2(det, la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb);
    }
  return total / (4 * std::numbers::pi_v<long double>);
}

// At random grid points of the mesh's box (classify snaps points; these are grid points already),
// classify says in exactly where the solid-angle winding number is positive. Returns how many
// points were compared (points on the boundary, or where the sum is not near an integer, are not).
int expect_classify_agrees(const Solid& s, const PolygonMesh& mesh, int count, unsigned seed) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  int checked = 0;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) p[a] = box.min()[a] + u(rng) * box.sizes()[a];
    p = kernel::to_world(kernel::snap(p));
    const Classification c = classify(s, p);
    if (c.location == Location::Boundary) continue;
    const long double w = solid_angle_winding(mesh, p);
    if (std::fabs(w - std::round(w)) > 1e-6) continue;
    EXPECT_EQ(c.location == Location::Inside, std::lround(w) > 0)
        << "at " << p.transpose() << ", winding " << double(w);
    ++checked;
  }
  return checked;
}

TEST(WindingSolid, TwoOverlappingBoxesAsOneMeshGiveTheirUnion) {
  const PolygonMesh mesh = merged(box({0, 0, 0}, {2, 2, 2}), box({1, 1, 1}, {3, 4, 2.5}));
  const WindingSolid w = positive_winding_solid(mesh);
  EXPECT_NEAR(volume(w.solid), 8 + 2 * 3 * 1.5 - 1 * 1 * 1, 1e-12);
  EXPECT_EQ(w.negative_cells, 0u);
  EXPECT_GT(w.multiple_cells, 0u);  // the overlap has winding number 2
  EXPECT_GT(expect_classify_agrees(w.solid, mesh, 400, 1), 300);
}

TEST(WindingSolid, DoublyCoveredPartsCountAsInside) {
  // A box inside another, both facing outwards: winding number 2 inside the small one.
  const WindingSolid nested = positive_winding_solid(merged(box({0, 0, 0}, {4, 4, 4}), box({1, 1, 1}, {2, 3, 2})));
  EXPECT_NEAR(volume(nested.solid), 64, 1e-12);
  EXPECT_GT(nested.multiple_cells, 0u);
  // The same box twice: every face covered twice (coincident faces), winding number 2 inside.
  const WindingSolid twice = positive_winding_solid(merged(box({0, 0, 0}, {1, 2, 3}), box({0, 0, 0}, {1, 2, 3})));
  EXPECT_NEAR(volume(twice.solid), 6, 1e-12);
  // A box and its copy split into triangles the other way round: coincident faces whose pieces differ.
  PolygonMesh a = box({0, 0, 0}, {1, 2, 3}), b = a;
  for (auto& f : b.faces) f = {f[1], f[2], f[3], f[0]};  // the fan starts at another corner
  EXPECT_NEAR(volume(positive_winding_solid(merged(a, b)).solid), 6, 1e-12);
}

TEST(WindingSolid, InvertedInnerShellIsAHole) {
  const PolygonMesh mesh = merged(box({0, 0, 0}, {4, 4, 4}), reversed(box({1, 1, 1}, {2, 3, 2})));
  const WindingSolid w = positive_winding_solid(mesh);
  EXPECT_NEAR(volume(w.solid), 64 - 2, 1e-12);
  EXPECT_EQ(w.negative_cells, 0u);
  // Turned inwards and reaching outside the box: winding -1 out there, 0 in the overlap.
  const WindingSolid out =
      positive_winding_solid(merged(box({0, 0, 0}, {4, 4, 4}), reversed(box({3, 1, 1}, {5, 2, 2}))));
  EXPECT_NEAR(volume(out.solid), 64 - 1, 1e-12);
  EXPECT_GT(out.negative_cells, 0u);
}

TEST(WindingSolid, FacesSharedTheOtherWayCancel) {
  // Two boxes that share the face x = 1 (written once each way), and two that share an edge only
  // (four faces on it: a non-manifold edge).
  PolygonMesh faces = merged(box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {2, 1, 1}));
  EXPECT_NEAR(volume(positive_winding_solid(faces).solid), 2, 1e-12);
  PolygonMesh edge = merged(box({0, 0, 0}, {1, 1, 1}), box({1, 1, 0}, {2, 2, 1}));
  EXPECT_NEAR(volume(positive_winding_solid(edge).solid), 2, 1e-12);
}

TEST(WindingSolid, SmallOverlapKeepsTheSignedVolume) {
  // Two spheres that overlap in a thin lens, and a torus whose tube passes through a box.
  const PolygonMesh spheres =
      merged(test_shapes::uv_sphere(48),
             moved(test_shapes::uv_sphere(48), Eigen::Affine3d(Eigen::Translation3d(1.95, 0.1, 0))));
  const WindingSolid w = positive_winding_solid(spheres);
  const double signed_volume = mesh_volume(spheres), v = volume(w.solid);
  EXPECT_LT(v, signed_volume);
  EXPECT_NEAR(v, signed_volume, 0.02 * signed_volume);
  EXPECT_GT(expect_classify_agrees(w.solid, spheres, 300, 2), 250);
  const PolygonMesh ring = merged(test_shapes::torus(48, 16), box({1.6, -0.1, -0.1}, {2.4, 0.1, 0.1}));
  const WindingSolid t = positive_winding_solid(ring);
  EXPECT_NEAR(volume(t.solid), mesh_volume(ring), 0.02 * mesh_volume(ring));
  EXPECT_GT(expect_classify_agrees(t.solid, ring, 300, 3), 250);
}

// The bunny and a turned copy of it written as one mesh (7348 triangles, many crossing pairs):
// the same solid as the union of the two imported separately, and classify agrees with the
// solid-angle winding number.
TEST(WindingSolid, BunnyAndTurnedCopyAsOneMeshIsTheirUnion) {
  const PolygonMesh bunny = read_mesh(sculpt::test::models_dir() + "/bunny.off");
  const Eigen::Affine3d turn(Eigen::Translation3d(1.5, 0.5, 0) *
                             Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()));
  const PolygonMesh copy = moved(bunny, turn);
  for (const Eigen::Vector3d& v : copy.vertices) ASSERT_TRUE(v.allFinite());
  const PolygonMesh both = merged(bunny, copy);
  const auto started = std::chrono::steady_clock::now();
  const WindingSolid w = positive_winding_solid(both);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::cout << "[ info ] bunny + turned copy, " << both.faces.size() << " faces: " << w.cells << " cells, "
            << w.inside_cells << " inside (" << w.multiple_cells << " twice), " << seconds << " s\n";
  // The reference snaps each shell as from_mesh does; positive_winding_solid snaps the same points.
  const double reference = volume(unite(from_mesh(bunny), from_mesh(copy)));
  EXPECT_NEAR(volume(w.solid), reference, 1e-9 * reference);
  EXPECT_GT(expect_classify_agrees(w.solid, both, 200, 4), 150);
}

TEST(WindingSolid, OpenMeshIsRefusedWithItsOpenEdges) {
  PolygonMesh open = box({0, 0, 0}, {1, 1, 1});
  open.faces.pop_back();
  try {
    (void)positive_winding_solid(open);
    FAIL() << "an open mesh was accepted";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("not closed: 4 edges"), std::string::npos) << e.what();
  }
  PolygonMesh bad = box({0, 0, 0}, {1, 1, 1});
  bad.faces[0][0] = 17;
  EXPECT_THROW((void)positive_winding_solid(bad), InvalidInput);
}

}  // namespace
}  // namespace sculpt
