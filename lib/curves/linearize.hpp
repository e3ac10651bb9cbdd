#pragma once
/// \file linearize.hpp
/// The one public entry point of the curve layer: piecewise linear approximation of a
/// digitized curve (Ihm & Naylor 1990, sections 2-4) by any of the methods below.
///
///   auto la = linearize(curve, {.segments = 16});                        // exact optimum
///   auto la = linearize(curve, {.segments = 16, .method = Method::Iter, .alpha = 0.5});
///   auto la = linearize(curve, {.tolerance = 1e-3});                     // fewest segments
///
/// "m segments" means exactly m (Definition 2.3). An open curve of n points has at most n - 1
/// segments, a closed one n; asking for more is an InvalidInput error, never a silent clamp.

#include <optional>
#include <string>

#include "curves/digitized_curve.hpp"
#include "curves/linearization.hpp"
#include "curves/segment_error.hpp"

namespace sculpt::curves {

enum class Method {
  Automatic,       ///< Optimal for .segments, MinCount for .tolerance
  Length,          ///< Alg. 4.1: equal chord length (segments)
  Image,           ///< Alg. 4.2: equal spherical-image length (segments)
  Init,            ///< Alg. 4.3: weighted by alpha (segments)
  Iter,            ///< Alg. 4.4: INIT then iterative refinement (segments)
  Dynamic,         ///< Alg. 3.2-3.3: the paper's O(n^3 log m) dynamic program (segments, n <= ~1500)
  Optimal,         ///< exact min-error for exactly m segments, far faster than Dynamic (segments)
  Fast,            ///< near-optimal for very large inputs; exact below a size threshold (segments)
  MinCount,        ///< exact fewest segments with error <= tolerance (tolerance)
  CenterOfMass,    ///< sec. 4.3.5: bisection at the center of curvature (tolerance or segments)
  DouglasPeucker,  ///< split at the farthest point (tolerance or segments)
};

struct LinearizeOptions {
  int segments = 0;                ///< m >= 1; 0 = not given
  std::optional<double> tolerance = std::nullopt; ///< epsilon >= 0 for tolerance-driven methods
  Method method = Method::Automatic;
  double alpha = 0.5;              ///< INIT/ITER weight of chord length vs. spherical image, in [0, 1]
  Norm norm = Norm::LInf;
  int max_iterations = 10000;      ///< ITER sweep limit
};

/// Linearizes `curve`. Exactly one of .segments / .tolerance must be given, matching the method.
/// \throw InvalidInput for an empty or one-point curve, m < 1, m above the segment count possible,
///        a negative or non-finite tolerance, alpha outside [0, 1], or a method/parameter mismatch.
[[nodiscard]] Linearization linearize(const DigitizedCurve& curve, const LinearizeOptions& options);

/// Method by name, case-insensitive: "length", "image", "init", "iter", "dynamic", "optimal",
/// "fast", "mincount", "center", "douglas-peucker" (also "dp"). std::nullopt if unknown.
[[nodiscard]] std::optional<Method> method_from_name(const std::string& name);
[[nodiscard]] std::string method_name(Method method);

}  // namespace sculpt::curves
