#pragma once
/// \file top_down_splitting.hpp
/// Top-down splitting methods: a segment is split into two until it is good enough.
///  - Douglas-Peucker (Ramer 1972, Douglas & Peucker 1973): split at the point farthest from the chord.
///  - Center of mass (sec. 4.3.5): split at the center of curvature c_kappa = int s kappa ds /
///    int kappa ds, approximated with chord lengths and spherical-image increments; a straight
///    piece (no curvature) is split at half its chord length.
/// Either until every segment error is <= tolerance, or, given m, by always splitting the
/// segment of largest error until there are exactly m segments.

#include <Eigen/Core>
#include <vector>

#include "curves/curve_measures.hpp"
#include "curves/linearization.hpp"

namespace sculpt::curves::detail {

enum class SplitRule { FarthestPoint, CenterOfCurvature };

struct SplitOptions {
  SplitRule rule = SplitRule::FarthestPoint;
  int segments = 0;         ///< > 0: split the worst segment until exactly this many
  double tolerance = 0.0;   ///< used when segments == 0
  Norm norm = Norm::LInf;
};

/// \pre points.size() >= 2; segments <= points.size() - 1; `measures` built from the same curve
/// (only used by CenterOfCurvature). .iterations = number of splits.
[[nodiscard]] Linearization top_down_split(const std::vector<Eigen::Vector3d>& points, const CurveMeasures& measures,
                                           const SplitOptions& options);

}  // namespace sculpt::curves::detail
