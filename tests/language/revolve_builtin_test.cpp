// revolve() from scripts: closed profiles (closed=true, a repeated first point, a closed curve)
// and partial revolutions (angle=), volumes against Pappus's theorem for the polygonal path
// (V = 2 area(path) ∫∫ r dr dz over the profile's region, written out below), and bad input as
// errors at the call or the argument.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::first_error_line;
using testing::numbers;
using testing::run_script;

// A square path of dyadic vertices (area 2) and the square torus profile [1, 2] x [0, 1]:
// ∫∫ r dr dz = 1.5, so V = 2 * 2 * 1.5 = 6.
const std::string kSquare = "p = convex_path([[1, 0], [0, 1], [-1, 0], [0, -1]])\n";

TEST(RevolveBuiltin, ClosedProfilesRevolveTheRegionTheyEnclose) {
  const auto v = numbers(kSquare +
                         "print(volume(revolve([[1, 0], [2, 0], [2, 1], [1, 1]], p, closed=true)))\n"
                         "print(volume(revolve([[1, 0], [2, 0], [2, 1], [1, 1], [1, 0]], p)))\n"
                         "print(volume(revolve(curve([[1, 0], [2, 0], [2, 1], [1, 1]], closed=true), p)))\n"
                         "print(volume(revolve([[1, 0], [2, 0], [2, 1], [1, 1]], p)))\n");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_NEAR(v[0], 6, 1e-12);
  EXPECT_NEAR(v[1], 6, 1e-12);
  EXPECT_NEAR(v[2], 6, 1e-12);
  EXPECT_NEAR(v[3], 2 * 4, 1e-12);  // open and monotone: the solid cylinder of radius 2
}

TEST(RevolveBuiltin, AngleKeepsAWedgeCounterClockwiseFromX) {
  // Quarter turns of the square path are the path itself: angle a keeps a/360 of the volume.
  const auto v = numbers(kSquare +
                         "t = [[1, 0], [2, 0], [2, 1], [1, 1]]\n"
                         "for a in [90, 180, 270, 360] { print(volume(revolve(t, p, closed=true, angle=a))) }\n");
  ASSERT_EQ(v.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(v[k], 6 * (k + 1) / 4.0, 1e-12) << k;
  // The quarter lies in x >= 0, y >= 0.
  const auto r = run_script(kSquare +
                            "q = revolve([[1, 0], [2, 0], [2, 1], [1, 1]], p, closed=true, angle=90)\n"
                            "b = bounds(q)\nprint(b[0][0] >= 0, b[0][1] >= 0, b[1][0], b[1][1])\n");
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.out, "true true 2 2\n");
}

TEST(RevolveBuiltin, BadProfilesAndAnglesAreErrorsThatSayWhere) {
  EXPECT_EQ(first_error_line("s = revolve([[1, 0], [2, 1], [2, 0], [1, 1]], circle(8), closed=true)"),
            "t.bsp:1:5: error: revolve: invalid input: closed profile is not a simple polygon: the edge from "
            "point 0 to point 1 and the edge from point 2 to point 3 cross or touch at (r, z) = (1.5, 0.5) "
            "(after snapping to the grid of step 2^-15)");
  EXPECT_EQ(first_error_line("s = revolve([[1, 0], [2, 0], [-1, 1], [1, 0]], circle(8))"),
            "t.bsp:1:5: error: revolve: invalid input: profile point 2 has r = -1.000000 < 0 (profiles live in "
            "the half-plane r >= 0)");
  EXPECT_EQ(first_error_line("s = revolve([[1, 0], [2, 0], [2, 1]], circle(8), angle=400)"),
            "t.bsp:1:50: error: revolve: argument 'angle' must be a finite number > 0 and <= 360, got 400");
  EXPECT_EQ(first_error_line("s = revolve([[1, 0], [2, 0], [2, 1]], circle(8), angle=0)"),
            "t.bsp:1:50: error: revolve: argument 'angle' must be a finite number > 0 and <= 360, got 0");
  const std::string turns = first_error_line("s = revolve([[1, 0], [2, 1], [1, 0.5]], circle(8))");
  EXPECT_NE(turns.find("closed=true"), std::string::npos) << turns;
}

}  // namespace
}  // namespace sculpt::language
