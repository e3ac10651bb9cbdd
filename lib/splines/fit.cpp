#include "splines/fit.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "splines/detail/distance_models.hpp"
#include "splines/detail/fit_loop.hpp"
#include "splines/detail/foot_point_search.hpp"
#include "splines/detail/normal_equations.hpp"

namespace sculpt::splines {

Method method_from_name(const std::string& name) {
  std::string s;
  for (char c : name) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (s == "sdm") return Method::SDM;
  if (s == "pdm") return Method::PDM;
  if (s == "tdm") return Method::TDM;
  throw InvalidInput("unknown fitting method '" + name + "' (expected sdm, pdm or tdm)");
}

std::string method_name(Method method) {
  switch (method) {
    case Method::SDM: return "sdm";
    case Method::PDM: return "pdm";
    case Method::TDM: return "tdm";
  }
  return "?";
}

namespace {

int detect_dimension(const std::vector<Eigen::Vector3d>& points, int requested) {
  bool planar = true;
  for (const auto& p : points) planar = planar && p.z() == 0.0;
  if (requested == 0) return planar ? 2 : 3;
  if (requested != 2 && requested != 3) throw InvalidInput("fit: dimension must be 0, 2 or 3");
  if (requested == 2 && !planar) throw InvalidInput("fit: dimension 2 asked for points with nonzero z");
  return requested;
}

void validate_points(const std::vector<Eigen::Vector3d>& points, int controls, int degree) {
  if (degree < 1) throw InvalidInput("fit: degree must be at least 1, got " + std::to_string(degree));
  if (controls < degree + 1)
    throw InvalidInput("fit: degree " + std::to_string(degree) + " needs at least " + std::to_string(degree + 1) +
                       " control points, got " + std::to_string(controls));
  if (static_cast<int>(points.size()) < controls)
    throw InvalidInput("fit: " + std::to_string(controls) + " control points need at least as many data points, got " +
                       std::to_string(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput("fit: data point " + std::to_string(i) + " is not finite");
  std::vector<Eigen::Vector3d> sorted = points;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  const int distinct = static_cast<int>(std::unique(sorted.begin(), sorted.end()) - sorted.begin());
  if (distinct < 2) throw InvalidInput("fit: all data points coincide");
  if (distinct < degree + 1)
    throw InvalidInput("fit: " + std::to_string(distinct) + " distinct data points cannot determine a curve of degree " +
                       std::to_string(degree));
}

}  // namespace

BSpline initial_curve(const std::vector<Eigen::Vector3d>& points, int controls, int degree, bool closed, int dimension) {
  validate_points(points, controls, degree);
  dimension = detect_dimension(points, dimension);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  cov /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = eig.eigenvectors().col(1);
  std::vector<Eigen::Vector3d> c(controls);
  if (closed) {
    const double r1 = std::sqrt(2.0 * std::max(eig.eigenvalues()[2], 0.0));
    const double r2 = std::max(std::sqrt(2.0 * std::max(eig.eigenvalues()[1], 0.0)), 0.05 * r1);
    for (int i = 0; i < controls; ++i) {
      const double a = 2.0 * std::numbers::pi * i / controls;
      c[i] = std::cos(a) * e1 + std::sin(a) * e2;
    }
    // Scale so the curve (not its control polygon) has the mean radius of the unit-circle net's curve.
    const BSpline unit = BSpline::periodic(degree, c, 3);
    double mean_radius = 0.0;
    const int m = 16 * controls;
    for (int i = 0; i < m; ++i) mean_radius += unit.point(static_cast<double>(controls) * i / m).norm();
    mean_radius /= m;
    for (int i = 0; i < controls; ++i) {
      const double a = 2.0 * std::numbers::pi * i / controls;
      c[i] = mean + (r1 * std::cos(a) * e1 + r2 * std::sin(a) * e2) / mean_radius;
      if (dimension == 2) c[i].z() = 0.0;
    }
    return BSpline::periodic(degree, c, dimension);
  }
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : points) {
    lo = std::min(lo, (p - mean).dot(e1));
    hi = std::max(hi, (p - mean).dot(e1));
  }
  for (int i = 0; i < controls; ++i) {
    c[i] = mean + (lo + (hi - lo) * i / (controls - 1)) * e1;
    if (dimension == 2) c[i].z() = 0.0;
  }
  return BSpline::clamped(degree, c, dimension);
}

FitResult fit_curve(const std::vector<Eigen::Vector3d>& points, const FitOptions& options) {
  const int controls = options.controls > 0 ? options.controls : options.start ? options.start->control_count() : 0;
  const int degree = options.start ? options.start->degree() : options.degree;
  if (controls <= 0) throw InvalidInput("fit: give a control point count or a start curve");
  validate_points(points, controls, degree);
  const int dimension = detect_dimension(points, options.dimension);
  if (options.iterations < 0) throw InvalidInput("fit: iterations must be >= 0");
  if (!(options.smoothing >= 0) || !std::isfinite(options.smoothing) || !(options.smoothing_decay >= 0) ||
      !(options.smoothing_decay <= 1) || !(options.tolerance >= 0) || !(options.noise_smoothing >= 0) ||
      !std::isfinite(options.noise_smoothing))
    throw InvalidInput("fit: smoothing must be >= 0, smoothing_decay in [0, 1], tolerance >= 0");
  BSpline start = options.start ? *options.start : initial_curve(points, controls, degree, options.closed, dimension);
  if (options.start) {
    if (start.control_count() != controls)
      throw InvalidInput("fit: the start curve has " + std::to_string(start.control_count()) + " control points, not " +
                         std::to_string(controls));
    if (start.closed() != options.closed)
      throw InvalidInput(std::string("fit: the start curve is ") + (start.closed() ? "closed" : "open") + " but a " +
                         (options.closed ? "closed" : "open") + " fit was asked for");
    if (start.dimension() < dimension) throw InvalidInput("fit: a 2D start curve for 3D data");
  }
  detail::LoopOptions loop{.model = static_cast<detail::Model>(options.method),
                           .iterations = options.iterations,
                           .smoothing = options.smoothing,
                           .smoothing_decay = options.smoothing_decay,
                           .tolerance = options.tolerance,
                           .fixed = options.fixed,
                           .line_search = options.method != Method::PDM,
                           .noise_smoothing = options.noise_smoothing,
                           .second_order = options.second_order && options.method == Method::SDM && options.closed};
  return detail::fit_points(points, start, loop);
}

}  // namespace sculpt::splines
