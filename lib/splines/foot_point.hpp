#pragma once
/// \file foot_point.hpp
/// Foot points (closest points) on a B-spline curve, distances from point sets to a curve, and
/// sampling. The foot point of x minimizes |c(t) - x|^2 over the domain: the curve is sampled on
/// every knot span, each local minimum of the sampled distance is refined by a safeguarded Newton
/// iteration on (c(t) - x) . c'(t) = 0 inside its bracket, and for an open curve the end points
/// are candidates too (Pottmann, Leopoldseder & Hofer 2002, sec. 2: the "normal foot point").

#include <Eigen/Core>
#include <vector>

#include "splines/bspline.hpp"

namespace sculpt::splines {

struct FootPoint {
  double parameter = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// The closest point of the curve to x. \throw InvalidInput if x is not finite.
[[nodiscard]] FootPoint closest_point(const BSpline& curve, const Eigen::Vector3d& x);

/// closest_point for every point, sharing one sampling of the curve.
[[nodiscard]] std::vector<FootPoint> closest_points(const BSpline& curve, const std::vector<Eigen::Vector3d>& points);

/// Largest and root-mean-square distance of a point set to a curve.
struct DistanceSummary {
  double max = 0.0;
  double rms = 0.0;
};

/// Distances from `points` to the curve (exact foot points). \throw InvalidInput for an empty set or a non-finite point.
[[nodiscard]] DistanceSummary distance(const BSpline& curve, const std::vector<Eigen::Vector3d>& points);

/// n points at uniform parameters: an open curve from its start to its end (n >= 2), a closed
/// curve once around without repeating the first point (n >= 1). \throw InvalidInput otherwise.
[[nodiscard]] std::vector<Eigen::Vector3d> sample(const BSpline& curve, int n);

}  // namespace sculpt::splines
