#pragma once
/// \file degree_reduction.hpp
/// Degree reduction of Bezier curves with the end points kept:
/// - reduce_degree: the active-curve method (Pottmann, Leopoldseder & Hofer 2002, sec. 3.1): the
///   control points of the degree-k curve start on the target (Fig. 6) and move under the
///   target's squared distance function, so the curves come close as point sets;
/// - reduce_degree_l2: Eck's best constrained L2 approximation (Eck 1995): minimizes
///   integral |b(t) - r(t)|^2 dt over the degree-k curves r with r(0) = b(0), r(1) = b(1), the
///   difference as functions of t.

#include "splines/approximate.hpp"
#include "splines/bspline.hpp"

namespace sculpt::splines {

/// \pre `bezier.is_bezier()`, 1 <= k < degree. \throw InvalidInput otherwise.
[[nodiscard]] FitResult reduce_degree(const BSpline& bezier, int k, const ApproximateOptions& options = {});

/// Eck's constrained L2 reduction to degree k in one step (exact Bernstein Gram matrices).
/// \pre as reduce_degree.
[[nodiscard]] BSpline reduce_degree_l2(const BSpline& bezier, int k);

}  // namespace sculpt::splines
