#pragma once
// Shared by the spline benchmarks: an interpolated input ellipse and its exact offset (tests/splines/analytic.hpp).
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "splines/analytic.hpp"
#include "splines/bspline.hpp"

namespace sculpt::splines::bench {
using V = Eigen::Vector3d;
namespace t = sculpt::splines::testing;
inline constexpr double kPi = std::numbers::pi;

using testing::interpolant;
// The exact offset of the ellipse (2 cos t, sin t) along the outward normal.
inline t::Curve3 ellipse_offset(double d) { return testing::ellipse_offset(2, 1, d); }

}  // namespace sculpt::splines::bench
