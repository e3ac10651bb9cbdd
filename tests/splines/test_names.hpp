#pragma once
// The names every spline test file uses (test sources only: a using-directive in a header).
#include <Eigen/Core>
#include <numbers>

#include "splines/analytic.hpp"

using namespace sculpt;
using namespace sculpt::splines;
using V = Eigen::Vector3d;
namespace t = sculpt::splines::testing;
inline constexpr double kPi = std::numbers::pi;
