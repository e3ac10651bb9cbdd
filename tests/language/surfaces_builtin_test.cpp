// The surfaces built-ins (builtins_surfaces.cpp) from scripts: a fit, a thickened flat patch
// against area * t, a torus-like surface as a solid, meshes, and bad input as errors at the call.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::run_script;

double number_of(const std::string& text) { return std::stod(text); }

TEST(SurfacesBuiltin, FitOfAWaveGetsClose) {
  const auto r = run_script(R"(
pts = []
for i in range(0, 20) {
  for j in range(0, 20) {
    x = -1 + 2 * i / 19
    y = -1 + 2 * j / 19
    pts = append(pts, [x, y, 0.3 * sin(2 * x) * cos(3 * y)])
  }
}
s = fit_surface(pts, controls=8, iterations=7)
h = surface_history(s)
print(len(h) - 1 <= 7, h[0][1] > 0.1, h[len(h) - 1][1] < 2e-3)
print(abs(surface_distance(s, pts)[0] - h[len(h) - 1][1]) < 1e-12)
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true true true\ntrue\n");
}

TEST(SurfacesBuiltin, ThickenedFlatPatchHasVolumeAreaTimesThickness) {
  // A 2 x 1 rectangle (bilinear) and a 3 x 2 parallelogram-free bicubic plane: volume = area * t
  // up to the kernel grid's rounding of the offset sheets (2^-15 per coordinate).
  const auto r = run_script(R"(
flat = bspline_surface([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], degree=1)
print(volume(thicken(flat, 0.25)))
rows = []
for i in range(0, 4) {
  row = []
  for j in range(0, 4) { row = append(row, [i, 2 * j / 3, 0.5]) }
  rows = append(rows, row)
}
print(volume(thicken(bspline_surface(rows), 0.5)))
)");
  ASSERT_EQ(r.error, "");
  std::istringstream lines(r.out);
  std::string line;
  const double step = std::ldexp(1.0, -15);
  std::getline(lines, line);
  EXPECT_NEAR(number_of(line), 2 * 0.25, 2 * 2 * step);
  std::getline(lines, line);
  EXPECT_NEAR(number_of(line), 3 * 2 * 0.5, 6 * 2 * step);
}

TEST(SurfacesBuiltin, TorusLikeSurfaceIsASolid) {
  // Control points on a torus (R = 3, r = 1), closed both ways: the solid's volume lies between
  // the solid tori through the innermost and outermost surface points (a loose, independent check:
  // the spline lies inside the control net's tube).
  const auto r = run_script(R"(
rows = []
for i in range(0, 12) {
  row = []
  a = 2 * pi * i / 12
  for j in range(0, 8) {
    b = 2 * pi * j / 8
    row = append(row, [(3 + cos(b)) * cos(a), (3 + cos(b)) * sin(a), sin(b)])
  }
  rows = append(rows, row)
}
s = bspline_surface(rows, closed=true)
t = surface_solid(s, tol=1e-2)
print(volume(t))
print(classify(t, [3, 0, 0]), classify(t, [0, 0, 0]), classify(t, [4.5, 0, 0]))
)");
  ASSERT_EQ(r.error, "");
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  const double v = number_of(line), pi = std::numbers::pi;
  EXPECT_GT(v, 2 * pi * pi * 3 * 0.6 * 0.6);
  EXPECT_LT(v, 2 * pi * pi * 3 * 1.0 * 1.0);
  std::getline(lines, line);
  EXPECT_EQ(line, "in out out");
}

TEST(SurfacesBuiltin, BadInputIsAnErrorAtTheCall) {
  EXPECT_NE(run_script("bspline_surface([[[0, 0, 0]]])").error.find("t.bsp:1:1: error:"), std::string::npos);
  EXPECT_NE(run_script("bspline_surface([[[0, 0, 0], [1, 0, 0]], [[0, 1, 0]]], degree=1)").error.find("same length"),
            std::string::npos);
  EXPECT_NE(run_script("fit_surface([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]])").error.find("points"), std::string::npos);
  EXPECT_NE(run_script("s = bspline_surface([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], degree=1)\nsurface_solid(s)")
                .error.find("closed in both directions"),
            std::string::npos);
  EXPECT_NE(
      run_script("s = bspline_surface([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], degree=1)\nthicken(s, -1)")
          .error.find("argument 't' must be a finite number > 0, got -1"),
      std::string::npos);
  EXPECT_NE(run_script("s = bspline_surface([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], degree=1)\nsurface_history(s)")
                .error.find("not made by fit_surface"),
            std::string::npos);
  EXPECT_NE(run_script("s = bspline_surface([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], degree=1)\nsurface_mesh(s, tol=0)")
                .error.find("tol"),
            std::string::npos);
}

}  // namespace
}  // namespace sculpt::language
