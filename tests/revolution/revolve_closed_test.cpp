// Closed profiles and partial revolutions (revolve.hpp, trees/profile_pieces.hpp). Volumes are
// checked against Pappus's theorem for a polygonal path: the cross-section at height z of a region
// R revolved along a convex path P around the axis is the annulus b(z) P minus a(z) P, of area
// area(P) (b^2 - a^2), so V = 2 area(P) ∫∫_R r dr dz; over the part of P between the rays at 0
// and a degrees, area(P) becomes that part's area. Both factors are computed here with shoelace
// formulas and polygon clipping, independently of the library.
#include "revolution/revolve.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/set_operations.hpp"
#include "curves/profiles.hpp"
#include "revolution/revolve_boundary.hpp"
#include "revolution/trees/profile_pieces.hpp"
#include "support/mesh_checks.hpp"

using namespace sculpt;
using namespace sculpt::revolution;

namespace {

using Polygon = std::vector<Eigen::Vector2d>;

double signed_area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &u = p[i], &v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return a / 2;
}

/// ∫∫_R r dr dz = area(R) centroid_r(R) = 1/6 Σ (r_i + r_j)(r_i z_j - r_j z_i), made positive.
double r_moment(const Polygon& p) {
  double m = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &u = p[i], &v = p[(i + 1) % p.size()];
    m += (u.x() + v.x()) * (u.x() * v.y() - v.x() * u.y()) / 6;
  }
  return signed_area(p) < 0 ? -m : m;
}

/// The part of a convex polygon where n.x <= 0 (Sutherland-Hodgman).
Polygon clip(const Polygon& p, const Eigen::Vector2d& n) {
  Polygon out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d &u = p[i], &v = p[(i + 1) % p.size()];
    const double fu = n.dot(u), fv = n.dot(v);
    if (fu <= 0) out.push_back(u);
    if ((fu < 0 && fv > 0) || (fu > 0 && fv < 0)) out.push_back(u + (v - u) * (fu / (fu - fv)));
  }
  return out;
}

/// Area of the part of the path between the rays at 0 and `degrees`, counter-clockwise.
double wedge_area(const Polygon& path, double degrees) {
  const double t = degrees * std::numbers::pi / 180, c = std::cos(t), s = std::sin(t);
  if (degrees == 360) return signed_area(path);
  if (degrees <= 180) return signed_area(clip(clip(path, {0, -1}), {-s, c}));
  return signed_area(path) - signed_area(clip(clip(path, {0, 1}), {s, -c}));
}

double pappus(const Polygon& region, const Polygon& path, double degrees = 360) {
  return 2 * wedge_area(path, degrees) * r_moment(region);
}

/// A strictly convex octagon with dyadic vertices (on every lattice revolve() snaps to, so the
/// path is revolved as given), symmetric under quarter turns; area 2.5.
const Polygon kOctagon{{1, 0},  {0.625, 0.625},   {0, 1},  {-0.625, 0.625},
                       {-1, 0}, {-0.625, -0.625}, {0, -1}, {0.625, -0.625}};

struct Case {
  std::string name;
  Polygon region;  // (r, z), dyadic, not closed by repeating the first point
  int genus;       // of the full revolution's boundary; -1: not checked
};

std::vector<Case> cases() {
  Polygon torus;  // a 16-gon about (2, 0.5) of radius 0.5, rounded to 1/256: off the axis
  for (int k = 0; k < 16; ++k) {
    const double t = 2 * std::numbers::pi * k / 16;
    torus.emplace_back(std::round((2 + 0.5 * std::cos(t)) * 256) / 256,
                       std::round((0.5 + 0.5 * std::sin(t)) * 256) / 256);
  }
  Polygon comb{{0, 0}, {10, 0}, {10, 1}};  // a disc on the axis with 20 concentric walls on it
  for (int k = 19; k >= 0; --k) {
    comb.emplace_back(0.5 * k + 0.25, 1);
    comb.emplace_back(0.5 * k + 0.25, 2 + 0.125 * k);
    comb.emplace_back(0.5 * k, 2 + 0.125 * k);
    if (k > 0) comb.emplace_back(0.5 * k, 1);
  }
  return {
      {"square torus", {{1, 0}, {2, 0}, {2, 1}, {1, 1}}, 1},
      {"polygonal torus", torus, 1},
      {"L-shaped overhang", {{0.5, 0}, {1, 0}, {1, 1.5}, {2.5, 1.5}, {2.5, 2}, {0.5, 2}}, 1},
      {"hollow vase wall", {{0, 0}, {2, 0}, {2.5, 1.5}, {2.25, 3}, {2, 3}, {2.25, 1.5}, {1.75, 0.25}, {0, 0.25}}, 0},
      {"curl open to the axis", {{1, 0}, {3, 0}, {3, 3}, {1, 3}, {1, 2.5}, {2.5, 2.5}, {2.5, 0.5}, {1, 0.5}}, 1},
      {"channel open upwards", {{1, 0}, {3, 0}, {3, 2}, {2.5, 2}, {2.5, 0.5}, {1.5, 0.5}, {1.5, 2}, {1, 2}}, 1},
      {"notch beside an edge on the axis", {{0, 0}, {2, 0}, {2, 2}, {1, 2}, {1, 1}, {0.5, 1}, {0.5, 3}, {0, 3}}, 0},
      {"comb of 20 pieces", comb, 0},
      {"diamond touching the axis at a point", {{0, 1}, {1, 0}, {2, 1}, {1, 2}}, -1},
  };
}

/// The solid's boundary is closed and clean: every edge used once each way, one fan per vertex,
/// the expected genus and one component, output rounding that found nothing to repair (except,
/// where the solid touches itself in a point, genus < 0, separating that point's copies), and the
/// mesh's own volume. Returns the solid's volume.
double check_clean(const Solid& s, int genus, double expected) {
  OutputRoundingReport report;
  const PolygonMesh mesh = to_mesh(s, {.report = &report});
  EXPECT_TRUE(report.clean) << report.problem;
  EXPECT_EQ(report.collapsed_edges + report.flipped_edges + report.nudged_vertices, 0);
  if (genus >= 0) {
    EXPECT_FALSE(report.changed) << report.separated_vertices << " vertices separated";
  } else {
    EXPECT_EQ(report.separated_vertices, 1);
  }
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(mesh));
  EXPECT_TRUE(checks::VerticesManifold(mesh));
  if (genus >= 0) {
    EXPECT_TRUE(checks::GenusIs(mesh, genus));
  }
  EXPECT_TRUE(checks::VolumeNear(mesh, expected, 1e-9));
  return volume(s);
}

}  // namespace

TEST(RevolveClosed, VolumesFollowPappusAndTheSolidsAreClean) {
  const ConvexPath path = polygon_path(kOctagon);
  ASSERT_EQ(signed_area(kOctagon), 2.5);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const double expected = pappus(c.region, kOctagon);
    const Solid s = revolve(c.region, path, {.closed = true});
    EXPECT_NEAR(check_clean(s, c.genus, expected), expected, 1e-9 * expected);
  }
}

TEST(RevolveClosed, AlongACircleTheVolumeIsPappusOfTheSnappedPath) {
  // circle(48)'s vertices are snapped to a dyadic lattice (snap_revolution): Pappus holds exactly
  // for the snapped path, and within the snapping for the inscribed 48-gon.
  const ConvexPath path = circular_path(48);
  const double inscribed = 24 * std::sin(2 * std::numbers::pi / 48);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const SnappedRevolution snapped = snap_revolution(c.region, path, {.closed = true});
    const double expected = pappus(c.region, snapped.path.vertices);
    const double v = volume(revolve(c.region, path, {.closed = true}));
    EXPECT_NEAR(v, expected, 1e-9 * expected);
    EXPECT_NEAR(v, 2 * inscribed * r_moment(c.region), 1e-5 * expected);
  }
}

// Random star-shaped polygons (simple by construction, dyadic points, often several pieces per
// slab: overhangs and notches everywhere), full and quarter revolutions.
TEST(RevolveClosed, RandomStarShapedProfilesFollowPappus) {
  const ConvexPath path = polygon_path(kOctagon);
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> unit(0, 1);
  std::size_t pieces = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 5 + int(unit(rng) * 26);
    const Eigen::Vector2d centre(1.5 + 1.5 * unit(rng), 2 * unit(rng));
    Polygon p;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * std::numbers::pi * (k + 0.8 * unit(rng)) / n, radius = 0.2 + 1.2 * unit(rng);
      const Eigen::Vector2d q = centre + radius * Eigen::Vector2d(std::cos(t), std::sin(t));
      p.emplace_back(std::round(q.x() * 64) / 64, std::round(q.y() * 64) / 64);
    }
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", " << n << " points");
    pieces += revolution::detail::monotone_pieces(revolution::detail::closed_profile(p, {}), {}).size();
    for (const double angle : {90.0, 360.0}) {
      const double expected = pappus(p, kOctagon, angle);
      const Solid s = revolve(p, path, {.closed = true, .angle = angle});
      EXPECT_NEAR(volume(s), expected, 1e-9 * expected);
      check_clean(s, angle == 360 ? 1 : 0, expected);
    }
  }
  EXPECT_GT(pieces, 80u);  // most of them need several pieces
}

TEST(RevolveClosed, ARepeatedFirstPointClosesTheProfile) {
  const Polygon open{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  Polygon closed = open;
  closed.push_back(open.front());
  const ConvexPath path = polygon_path(kOctagon);
  EXPECT_TRUE(is_closed_profile(closed));
  EXPECT_FALSE(is_closed_profile(open));
  const double ring = pappus(open, kOctagon);  // 2 * 2.5 * 1.5
  EXPECT_EQ(ring, 7.5);
  EXPECT_NEAR(volume(revolve(closed, path)), ring, 1e-12 * ring);
  EXPECT_NEAR(volume(revolve(closed, path, {.closed = true})), ring, 1e-12 * ring);
  // The same points read as an open profile (z never decreases) are a solid cylinder of radius 2.
  EXPECT_NEAR(volume(revolve(open, path)), 2.5 * 4, 1e-12);
}

TEST(RevolveClosed, PartialRevolutionsCutAtExactPlanes) {
  const ConvexPath path = polygon_path(kOctagon);
  for (const Case& c : cases()) {
    if (c.genus < 0) continue;  // touching the axis at a point: the wedge pieces meet there only
    for (const double angle : {45.0, 90.0, 100.0, 180.0, 270.0, 315.0, 360.0}) {
      SCOPED_TRACE(c.name + ", angle " + std::to_string(angle));
      const double expected = pappus(c.region, kOctagon, angle);
      const Solid s = revolve(c.region, path, {.closed = true, .angle = angle});
      // At 100 degrees no path vertex lies on the cut: its direction is rounded to 2^-30 (the
      // volume moves by less than 1e-9 relative here; the bound allows for that rounding).
      const double tolerance = angle == 100 ? 1e-7 : 1e-9;
      EXPECT_NEAR(volume(s), expected, tolerance * expected);
      check_clean(s, angle == 360 ? c.genus : 0, expected);
      // A quarter turn of this path is the same path: the volume is a fraction of the full one.
      if (std::fmod(angle, 90) == 0) {
        EXPECT_NEAR(volume(s), angle / 360 * pappus(c.region, kOctagon), 1e-9 * expected);
      }
    }
  }
}

TEST(RevolveClosed, TheWedgeRunsCounterClockwiseFromThePositiveXAxis) {
  // Volumes cannot tell a wedge from its mirror image on a symmetric path: points can. The square
  // torus's ring at r = 1.35 (between 1 P and 2 P along every direction of the octagon) is inside
  // in the middle of the kept wedge and outside in the middle of the removed one.
  const ConvexPath path = polygon_path(kOctagon);
  const Polygon square{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  auto at = [](double degrees) {
    const double t = degrees * std::numbers::pi / 180;
    return Eigen::Vector3d(1.35 * std::cos(t), 1.35 * std::sin(t), 0.5);
  };
  for (const double angle : {30.0, 90.0, 100.0, 180.0, 200.0, 270.0, 345.0}) {
    SCOPED_TRACE(angle);
    const Solid s = revolve(square, path, {.closed = true, .angle = angle});
    EXPECT_EQ(classify(s, at(angle / 2)).location, Location::Inside);
    EXPECT_EQ(classify(s, at((angle + 360) / 2)).location, Location::Outside);
    EXPECT_EQ(classify(s, at(angle + 1)).location, Location::Outside);
    EXPECT_EQ(classify(s, at(angle - 1)).location, Location::Inside);
    EXPECT_EQ(classify(s, at(0)).location, Location::Boundary);
  }
}

TEST(RevolveClosed, PartialRevolutionsAlongACircleAreFractionsAtMultiplesOfTheEdgeAngle) {
  // circle(12): at multiples of 30 degrees the cut runs through the path's (snapped) vertices.
  const ConvexPath path = circular_path(12);
  const Polygon region{{1, 0}, {2, 0}, {2.5, 1.5}, {1.5, 1}, {1, 2}};
  const SnappedRevolution snapped = snap_revolution(region, path, {.closed = true});
  const double full = pappus(region, snapped.path.vertices);
  for (const double angle : {30.0, 90.0, 150.0, 180.0, 210.0, 270.0, 330.0, 360.0}) {
    SCOPED_TRACE(angle);
    // The wedge of the snapped 12-gon: whole triangles (origin, vertex k, vertex k + 1).
    double wedge = 0;
    for (int k = 0; k < int(angle / 30 + 0.5); ++k) {
      const Eigen::Vector2d &u = snapped.path.vertices[k], &v = snapped.path.vertices[(k + 1) % 12];
      wedge += (u.x() * v.y() - v.x() * u.y()) / 2;
    }
    const double expected = 2 * wedge * r_moment(region);
    const Solid s = revolve(region, path, {.closed = true, .angle = angle});
    EXPECT_NEAR(volume(s), expected, 1e-9 * expected);
    EXPECT_NEAR(volume(s), angle / 360 * full, 1e-6 * full);  // the snapped 12-gon is regular to 1e-6
    check_clean(s, angle == 360 ? 1 : 0, expected);
  }
}

TEST(RevolveClosed, OpenProfilesRevolvePartially) {
  // The Figure 11 goblet's outer profile over a quarter and three quarters of circle(32).
  const Polygon goblet = curves::planar_points(curves::sample_profile(curves::goblet_profile(), {.points = 21}).points);
  const ConvexPath path = circular_path(32);
  const SnappedRevolution snapped = snap_revolution(goblet, path);
  const double full = revolved_volume(snapped.profile, snapped.path);
  const double area = signed_area(snapped.path.vertices);
  for (const double angle : {90.0, 270.0}) {
    SCOPED_TRACE(angle);
    const double expected = full * wedge_area(snapped.path.vertices, angle) / area;
    const Solid s = revolve(goblet, path, {.angle = angle});
    EXPECT_NEAR(volume(s), expected, 1e-9 * expected);
    check_clean(s, 0, expected);
  }
}

// Open monotone profiles are the paper's case: their trees must stay the section 6 trees. The
// figures are those of docs/revolution.md (the Figure 11 goblet) and of the step profile of
// revolve_test.cpp, as the revolution layer built them before closed profiles existed.
TEST(RevolveClosed, OpenMonotoneProfilesKeepTheirTrees) {
  const Polygon goblet = curves::planar_points(curves::sample_profile(curves::goblet_profile(), {.points = 21}).points);
  for (const RevolveOptions& options : {RevolveOptions{}, RevolveOptions{.angle = 360}}) {
    const TreeStats g = tree_stats(revolve(goblet, circular_path(32), options));
    EXPECT_EQ(g.nodes, 901);
    EXPECT_EQ(g.in_leaves + g.out_leaves, 902);
    EXPECT_EQ(g.in_leaves, 260);
    EXPECT_EQ(g.height, 15);
  }
  const Polygon steps{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {1.5, 2}, {1.5, 3}, {0, 3.5}};
  const TreeStats s = tree_stats(revolve(steps, circular_path(12)));
  EXPECT_EQ(s.nodes, 69);
  EXPECT_EQ(s.in_leaves + s.out_leaves, 70);
  EXPECT_EQ(s.in_leaves, 20);
  EXPECT_EQ(s.height, 10);
}

TEST(RevolveClosed, ReportsBadInput) {
  const ConvexPath path = circular_path(8);
  auto message = [&path](const Polygon& p, const RevolveOptions& options) -> std::string {
    try {
      (void)revolve(p, path, options);
    } catch (const InvalidInput& e) {
      return e.what();
    }
    return "no InvalidInput";
  };
  const Polygon square{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const std::string crossing = message({{1, 0}, {2, 1}, {2, 0}, {1, 1}}, {.closed = true});
  EXPECT_NE(crossing.find("not a simple polygon"), std::string::npos) << crossing;
  EXPECT_NE(crossing.find("(1.5, 0.5)"), std::string::npos) << crossing;
  const std::string negative = message({{1, 0}, {2, 0}, {2, 1}, {-1, 1}}, {.closed = true});
  EXPECT_NE(negative.find("point 3 has r = -1"), std::string::npos) << negative;
  for (const double angle : {0.0, -90.0, 360.5, double(NAN)}) {
    const std::string bad = message(square, {.closed = true, .angle = angle});
    EXPECT_NE(bad.find("angle must be in (0, 360]"), std::string::npos) << angle << ": " << bad;
  }
  // Away from the axis, b(z) P minus a(z) P is the swept region only if P contains the axis.
  const ConvexPath off_axis = polygon_path({{1, 1}, {2, 1}, {2, 2}});
  EXPECT_THROW((void)revolve(square, off_axis, {.closed = true}), InvalidInput);
  EXPECT_NO_THROW((void)revolve({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, off_axis, {.closed = true}));  // on the axis
  // An open profile that turns says how to close it.
  const std::string turns = message({{1, 0}, {2, 1}, {1, 2}, {0.5, 1}}, {});
  EXPECT_NE(turns.find("closed=true"), std::string::npos) << turns;
}
