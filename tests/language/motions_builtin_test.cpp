// geodesic, surface_spline, motion and sweeping along a motion from scripts: results checked by
// analytic references (a quarter great circle, a quarter turn), bad input as errors at the
// argument (never a crash).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;

TEST(MotionsBuiltin, GeodesicOnASphereIsAQuarterGreatCircle) {
  const auto r = run_script(R"(
g = geodesic(sphere_surface([0, 0, 0], 2), [2, 0, 0], [0, 2, 0], segments=32)
ps = points(sample(g, 101))
worst = 0
for p in ps { worst = max(worst, abs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 2)) }
print(worst < 1e-4, abs(ps[50][0] - sqrt(2)) < 1e-6, abs(ps[50][2]) < 1e-9)
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true true true\n");
}

TEST(MotionsBuiltin, ImplicitFunctionsAreSurfaces) {
  const auto r = run_script(R"(
fn cyl(x, y, z) { x * x + y * y - 1 }
s = surface_spline(cyl, [[1, 0, 0], [0, 1, 0.5], [-1, 0, 1]])
worst = 0
for p in points(sample(s, 200)) { worst = max(worst, abs(sqrt(p[0] * p[0] + p[1] * p[1]) - 1)) }
print(worst < 1e-4)
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true\n");
}

TEST(MotionsBuiltin, AQuarterTurnMotionMeetsItsPosesAndSweeps) {
  const auto r = run_script(R"(
m = motion([[[0, 0, 0], [0, 0, 1, 0]], [[0, 0, 0], [0, 0, 1, 45]], [[0, 0, 0], [0, 0, 1, 90]]])
p = pose(m, 2)
print(abs(p[0][0]) < 1e-12, abs(p[0][1] + 1) < 1e-12, abs(p[1][0] - 1) < 1e-12)
bar = box([0, -0.25, -0.25], [2, 0.25, 0.25])
s = sweep(bar, m, tol=0.05)
print(volume(s))
)");
  ASSERT_EQ(r.error, "");
  std::istringstream lines(r.out);
  std::string first, second;
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(first, "true true true");
  // The bar [0, 2] x [-w, w] turning by 90 degrees about z: quarter disk of radius sqrt(4 + w^2)
  // plus two strips of width w inside that radius, times the height 2 w (w = 0.25); within tol times the area (below 2 * (area / height + perimeter)).
  const double w = 0.25, R2 = 4 + w * w, strip = 0.5 * (w * 2 + R2 * std::asin(w / std::sqrt(R2)));
  const double exact = 2 * w * (std::numbers::pi * R2 / 4 + 2 * strip);
  EXPECT_NEAR(std::stod(second), exact, 0.05 * 2 * (exact / (2 * w) + 6));
}

TEST(MotionsBuiltin, BadInputIsAnErrorAtTheArgument) {
  EXPECT_NE(run_script("motion([[[0, 0, 0], [0, 0, 1, 0]]])").error.find("at least two poses"), std::string::npos);
  EXPECT_NE(run_script("motion([[[0, 0, 0], [0, 0, 0, 10]], [[1, 0, 0], [0, 0, 1, 0]]])").error.find("axis must not be zero"),
            std::string::npos);
  EXPECT_NE(run_script("motion([[[0, 0, 0], [[2, 0, 0], [0, 1, 0], [0, 0, 1]]], [[1, 0, 0], [0, 0, 1, 0]]])")
                .error.find("not a rotation"),
            std::string::npos);
  EXPECT_NE(run_script("geodesic(3, [1, 0, 0], [0, 1, 0])").error.find("must be a surface"), std::string::npos);
  EXPECT_NE(run_script("geodesic(sphere_surface([0, 0, 0], 1), [1, 0, 0], [2, 0, 0])").error.find("same point"),
            std::string::npos);
  EXPECT_NE(run_script("torus_surface([0, 0, 0], [0, 0, 1], 1, 2)").error.find("below R"), std::string::npos);
  EXPECT_NE(run_script("sweep(box([0,0,0],[1,1,1]), motion([[[0,0,0],[0,0,1,0]],[[1,0,0],[0,0,1,0]]]), tol=-1)")
                .error.find("argument 'tol' must be a finite number > 0, got -1"),
            std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
