// Solids at other grids than the default (docs/kernel.md, "World range"): a part in millimetres
// longer than two metres, features of micrometres in a model in metres, exact volumes against
// analytic values, the exact scale equivalence to the default grid, and mixing grids as an error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/classify.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/point_classifier.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using kernel::Grid;

const Grid kMillimetres = Grid::from_shift(13);  // step 2^-13 mm, range [-4096, 4096] mm
const Grid kMetresFine = Grid::from_shift(20);   // step 2^-20 m (0.95 um), range [-32, 32] m

// The value the grid holds for v (nearest multiple of the step), computed here independently.
double snapped(double v, int shift) { return std::round(std::ldexp(v, shift)) * std::ldexp(1.0, -shift); }

TEST(WorldRange, ThreeMetrePartInMillimetres) {
  // Out of range at the default grid, and the message says which grid holds it.
  try {
    (void)box({0, 0, 0}, {3000, 400, 50});
    FAIL() << "3000 mm fits the default grid?";
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("a grid of step 2^-13 would fit coordinates up to 4096"), std::string::npos)
        << e.what();
  }
  const Solid plate = box({0, 0, 0}, {3000, 400, 50}, kMillimetres);
  const Solid rib = box({0, 0, 0}, {200, 400, 1200}, kMillimetres);
  const Solid window = box({1000, 100, -1}, {1500, 300, 51}, kMillimetres);
  const Solid part = (plate | rib) - window;
  EXPECT_EQ(part.grid(), kMillimetres);
  const PolygonMesh m = to_mesh(part);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(m));
  // 3000 x 400 x 50 + 200 x 400 x 1150 - 500 x 200 x 50, every coordinate on the grid: exact.
  EXPECT_EQ(volume(part), 3000.0 * 400 * 50 + 200.0 * 400 * 1150 - 500.0 * 200 * 50);
  EXPECT_EQ(bounding_box(part).max(), Eigen::Vector3d(3000, 400, 1200));
  EXPECT_EQ(classify(part, {2999, 1, 1}).location, Location::Inside);
  EXPECT_EQ(classify(part, {1200, 200, 25}).location, Location::Outside);  // in the window
  EXPECT_EQ(PointClassifier(part).classify({2999, 1, 1}).location, Location::Inside);
  EXPECT_THROW((void)classify(part, {5000, 0, 0}), RangeError);

  // A cylinder of radius 1400 mm and 3 m height: the prism over the regular 64-gon, whose face
  // planes are rounded (normals to 2^-26, docs/kernel.md): each side moves by at most R 2^-25.
  const int n = 64;
  const Solid c = cylinder(1400, 3000, {.segments = n, .grid = kMillimetres});
  EXPECT_EQ(c.grid(), kMillimetres);
  const double prism = n / 2.0 * 1400 * 1400 * std::sin(2 * std::numbers::pi / n) * 3000;
  const double perimeter = n * 2 * 1400 * std::sin(std::numbers::pi / n);
  EXPECT_NEAR(volume(c), prism, perimeter * 3000 * (1400 * std::ldexp(1.0, -25) + kMillimetres.step()));
  // Exactly the default grid's cylinder of a quarter of the size, scaled by 4.
  EXPECT_EQ(volume(c), 64 * volume(cylinder(350, 750, {.segments = n})));
}

TEST(WorldRange, MicrometreFeaturesInMetres) {
  // A 10 um groove in a 0.1 m plate: at the default grid (step 30 um) it snaps to nothing.
  EXPECT_THROW((void)box({0.0201, -0.001, 0.001}, {0.02011, 0.101, 0.003}), InvalidInput);
  const Solid plate = box({0, 0, 0}, {0.1, 0.1, 0.002}, kMetresFine);
  const Solid groove = box({0.0201, -0.001, 0.001}, {0.02011, 0.101, 0.003}, kMetresFine);
  const Solid grooved = plate - groove;
  EXPECT_EQ(grooved.grid(), kMetresFine);
  const double s01 = snapped(0.1, 20), s002 = snapped(0.002, 20), s001 = snapped(0.001, 20);
  const double width = snapped(0.02011, 20) - snapped(0.0201, 20);
  EXPECT_EQ(width, 11 * std::ldexp(1.0, -20));  // 10.5 um, eleven steps
  const double expected = s01 * s01 * s002 - width * s01 * (s002 - s001);
  EXPECT_NEAR(volume(grooved), expected, 1e-14 * expected);
  EXPECT_EQ(classify(grooved, {0.020105, 0.05, 0.0015}).location, Location::Outside);
  EXPECT_EQ(classify(grooved, {0.020105, 0.05, 0.0005}).location, Location::Inside);
  EXPECT_EQ(classify(grooved, {0.020095, 0.05, 0.0015}).location, Location::Inside);
  // Leaf cells (statistics) see the groove too: their volumes add up to the box's.
  const auto cells = leaf_cells(grooved, Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0.1, 0.002)));
  double total = 0, inside = 0;
  for (const LeafCell& c : cells) total += c.volume, inside += c.inside ? c.volume : 0;
  EXPECT_NEAR(total, s01 * s01 * s002, 1e-12 * s01 * s01 * s002);
  EXPECT_NEAR(inside, expected, 1e-12 * expected);
  // A ball of radius 20 um: a polyhedron inscribed in the sphere, close to it.
  const Solid ball = sphere(20e-6, {.segments = 32, .grid = Grid::from_shift(40)});
  const double v = volume(ball), ball_volume = 4.0 / 3.0 * std::numbers::pi * std::pow(20e-6, 3);
  EXPECT_LT(v, ball_volume);
  EXPECT_GT(v, 0.97 * ball_volume);
}

// The construction of a solid with a general rotation, at scale f: the same solid at the grid
// whose step is f times the default is the default one scaled by f, exactly.
Solid model(double f, const Grid& grid) {
  const Solid s = sphere(f * 1.0, {.segments = 24, .grid = grid});
  const Solid b = rotate(box(f * Eigen::Vector3d(-0.3, -0.4, -1.5), f * Eigen::Vector3d(0.5, 0.3, 1.5), grid), {1, 2, 3}, 33);
  const Solid c = translate(cylinder(f * 0.25, f * 2.0, {.segments = 16, .grid = grid}), f * Eigen::Vector3d(0.6, 0, -1));
  return (s - b) | c;
}

TEST(WorldRange, AnotherGridIsTheDefaultGridScaledExactly) {
  const Solid reference = model(1.0, Grid{});
  const PolygonMesh r = to_mesh(reference);
  const Solid reference_rebuilt = from_mesh(r);
  for (const int k : {13, 20, -3, 50}) {
    const double f = std::ldexp(1.0, 15 - k);
    const Solid scaled = model(f, Grid::from_shift(k));
    EXPECT_EQ(scaled.grid().shift(), k);
    const PolygonMesh m = to_mesh(scaled);
    ASSERT_EQ(m.vertices.size(), r.vertices.size()) << k;
    ASSERT_EQ(m.faces, r.faces) << k;
    for (std::size_t i = 0; i < m.vertices.size(); ++i) ASSERT_EQ(m.vertices[i], f * r.vertices[i]) << k << " " << i;
    EXPECT_EQ(volume(scaled), f * f * f * volume(reference)) << k;
    EXPECT_EQ(tree_stats(scaled).nodes, tree_stats(reference).nodes) << k;
    // An import at the same grid snaps the mesh's vertices as the default grid does.
    const Solid rebuilt = from_mesh(m, {.grid = scaled.grid()});
    EXPECT_EQ(rebuilt.grid(), scaled.grid());
    EXPECT_EQ(volume(rebuilt), f * f * f * volume(reference_rebuilt)) << k;
  }
}

std::string mismatch_message(const Solid& a, const Solid& b) {
  try {
    (void)(a | b);
  } catch (const GridMismatch& e) {
    return e.what();
  }
  return "no error";
}

TEST(WorldRange, MixingGridsIsAnError) {
  const Solid a = box({0, 0, 0}, {1, 1, 1});
  const Solid b = box({0, 0, 0}, {1, 1, 1}, kMillimetres);
  const std::string m = mismatch_message(a, b);
  EXPECT_NE(m.find("2^-15"), std::string::npos) << m;
  EXPECT_NE(m.find("2^-13"), std::string::npos) << m;
  EXPECT_THROW((void)(a & b), GridMismatch);
  EXPECT_THROW((void)(b - a), GridMismatch);
  EXPECT_THROW((void)(Solid(a) | b), GridMismatch);  // the in-place variant
  EXPECT_THROW((void)unite_all({a, b, a}), GridMismatch);
  EXPECT_THROW((void)unite_all({b, a}), InvalidInput);  // a GridMismatch is an InvalidInput
  // The same grid combines; leaves (no coordinates) combine with any grid and take the other's.
  EXPECT_EQ((b | translate(b, {0.5, 0, 0})).grid(), kMillimetres);
  EXPECT_EQ((Solid() | b).grid(), kMillimetres);
  EXPECT_EQ((b - Solid()).grid(), kMillimetres);
  EXPECT_EQ((Solid::leaf(true) & b).grid(), kMillimetres);
  EXPECT_EQ(volume(Solid::leaf(true) & b), 1.0);
  EXPECT_EQ(unite_all({Solid(), b, translate(b, {2, 0, 0})}).grid(), kMillimetres);
  EXPECT_EQ((b - b).grid(), kMillimetres);
}

TEST(WorldRange, OperationsKeepTheGrid) {
  const Solid b = box({0, 0, 0}, {3000, 10, 10}, kMillimetres);
  EXPECT_EQ(translate(b, {-1000, 0, 0}).grid(), kMillimetres);
  EXPECT_EQ(rotate(b, {0, 0, 1}, 90).grid(), kMillimetres);   // exact map
  EXPECT_EQ(rotate(b, {1, 1, 0}, 20).grid(), kMillimetres);   // through the boundary
  EXPECT_EQ(scale(b, {0.5, 1, 1}).grid(), kMillimetres);
  EXPECT_EQ(complement(b).grid(), kMillimetres);
  EXPECT_EQ(partition(b, kernel::make_plane(1, 0, 0, -kernel::Int128(1000) * 8192)).first.grid(), kMillimetres);
  EXPECT_EQ(volume(translate(b, {-1000, 0, 0})), 300000.0);
  EXPECT_EQ(volume(rotate(b, {0, 0, 1}, 90)), 300000.0);
  EXPECT_EQ(volume(partition(b, kernel::make_plane(1, 0, 0, -kernel::Int128(1000) * 8192)).first), 100000.0);
  // Translations beyond the range say which grid would hold them.
  try {
    (void)translate(b, {5000, 0, 0});
    FAIL();
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("a grid of step 2^-12 would fit coordinates up to 8192"), std::string::npos)
        << e.what();
  }
  const Solid p = prism({{0, 0}, {3000, 0}, {0, 2000}}, 0, 10, kMillimetres);
  EXPECT_EQ(p.grid(), kMillimetres);
  EXPECT_EQ(volume(p), 3000.0 * 2000 / 2 * 10);
  const Solid h = convex_polytope({{{1, 0, 0}, -3000}, {{-1, 0, 0}, 0}, {{0, 1, 0}, -1}, {{0, -1, 0}, 0},
                                   {{0, 0, 1}, -1}, {{0, 0, -1}, 0}}, kMillimetres);
  EXPECT_EQ(h.grid(), kMillimetres);
  EXPECT_EQ(volume(h), 3000.0);
}

}  // namespace
}  // namespace sculpt
