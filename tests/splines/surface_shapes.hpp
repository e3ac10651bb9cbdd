#pragma once
// Surfaces with closed forms shared by the surface tests.
#include <vector>

#include "splines/bspline_surface.hpp"
#include "test_names.hpp"

// z = x^2 + y^2 over [-1, 1]^2 as a biquadratic Bezier patch, x = 2u - 1, y = 2v - 1: x is linear
// (controls -1, 0, 1) and x^2 = (2u - 1)^2 has Bernstein coefficients 1, -1, 1.
inline BSplineSurface paraboloid() {
  const double x[3] = {-1, 0, 1}, sq[3] = {1, -1, 1};
  std::vector<V> P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P.emplace_back(x[i], x[j], sq[i] + sq[j]);
  return BSplineSurface::uniform({2, 2}, 3, 3, P);
}
