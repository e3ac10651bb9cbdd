#include "curves/linearize.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/errors.hpp"
#include "curves/curve_measures.hpp"
#include "curves/methods/dynamic_programming.hpp"
#include "curves/methods/fast_linearization.hpp"
#include "curves/methods/heuristic_subdivision.hpp"
#include "curves/methods/top_down_splitting.hpp"
#include "curves/optimal/optimal_linearization.hpp"

namespace sculpt::curves {
namespace {

struct NamedMethod {
  Method method;
  const char* name;
};
constexpr NamedMethod kNames[] = {
    {Method::Automatic, "automatic"}, {Method::Length, "length"},
    {Method::Image, "image"},         {Method::Init, "init"},
    {Method::Iter, "iter"},           {Method::Dynamic, "dynamic"},
    {Method::Optimal, "optimal"},     {Method::Fast, "fast"},
    {Method::MinCount, "mincount"},   {Method::CenterOfMass, "center"},
    {Method::DouglasPeucker, "douglas-peucker"},
};

bool needs_segments(Method method) {
  switch (method) {
    case Method::Length:
    case Method::Image:
    case Method::Init:
    case Method::Iter:
    case Method::Dynamic:
    case Method::Optimal:
    case Method::Fast:
      return true;
    default:
      return false;
  }
}

std::string curve_label(const DigitizedCurve& curve) { return curve.name.empty() ? "curve" : "curve '" + curve.name + "'"; }

}  // namespace

std::optional<Method> method_from_name(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == "dp" || lower == "douglas_peucker" || lower == "douglaspeucker") return Method::DouglasPeucker;
  if (lower == "min-count" || lower == "min_count" || lower == "mincount") return Method::MinCount;
  if (lower == "center-of-mass" || lower == "centerofmass" || lower == "center_of_mass") return Method::CenterOfMass;
  for (const NamedMethod& entry : kNames)
    if (lower == entry.name) return entry.method;
  return std::nullopt;
}

std::string method_name(Method method) {
  for (const NamedMethod& entry : kNames)
    if (entry.method == method) return entry.name;
  return "unknown";
}

Linearization linearize(const DigitizedCurve& curve, const LinearizeOptions& options) {
  validate(curve);
  const std::string label = curve_label(curve);
  if (curve.points.empty()) throw InvalidInput(label + " is empty: nothing to linearize");
  if (curve.points.size() == 1) throw InvalidInput(label + " has a single point: no segment can be formed");
  if (curve.closed && curve.points.size() < 3) throw InvalidInput(label + ": a closed curve needs at least 3 points");
  const std::vector<Eigen::Vector3d> points = path_points(curve);
  const int possible = static_cast<int>(points.size()) - 1;

  const bool has_segments = options.segments != 0;
  const bool has_tolerance = options.tolerance.has_value();
  if (has_segments && has_tolerance) throw InvalidInput("give either a segment count or a tolerance, not both");
  if (!has_segments && !has_tolerance) throw InvalidInput("give a segment count (m >= 1) or a tolerance");
  Method method = options.method;
  if (method == Method::Automatic) method = has_segments ? Method::Optimal : Method::MinCount;
  if (needs_segments(method) && !has_segments)
    throw InvalidInput("method " + method_name(method) + " needs a segment count, not a tolerance");
  if (method == Method::MinCount && !has_tolerance)
    throw InvalidInput("method mincount needs a tolerance, not a segment count");
  if (has_segments) {
    if (options.segments < 1)
      throw InvalidInput("segment count must be at least 1, got " + std::to_string(options.segments));
    if (options.segments > possible)
      throw InvalidInput(label + " has " + std::to_string(curve.points.size()) + " points and allows at most " +
                         std::to_string(possible) + " segments, " + std::to_string(options.segments) + " requested");
  }
  if (has_tolerance && !(std::isfinite(*options.tolerance) && *options.tolerance >= 0.0))
    throw InvalidInput("tolerance must be a finite value >= 0");
  if (!(options.alpha >= 0.0 && options.alpha <= 1.0)) throw InvalidInput("alpha must lie in [0, 1]");
  if (options.max_iterations < 0) throw InvalidInput("max_iterations must be >= 0");

  const int m = options.segments;
  const Norm norm = options.norm;
  switch (method) {
    case Method::Length:
    case Method::Image:
    case Method::Init:
    case Method::Iter: {
      const CurveMeasures measures(curve);
      const double alpha = method == Method::Length ? 1.0 : method == Method::Image ? 0.0 : options.alpha;
      Linearization init = detail::weighted_subdivision(points, measures, m, alpha, norm);
      if (method != Method::Iter) return init;
      return detail::iterative_refinement(points, std::move(init), norm, options.max_iterations);
    }
    case Method::Dynamic:
      return detail::dynamic_linearization(points, m, norm);
    case Method::Optimal:
      return detail::optimal_min_error(points, m, norm);
    case Method::Fast:
      return detail::fast_linearization(points, m, norm);
    case Method::MinCount:
      return detail::optimal_min_count(points, *options.tolerance, norm);
    case Method::CenterOfMass:
    case Method::DouglasPeucker: {
      const CurveMeasures measures(curve);
      return detail::top_down_split(points, measures,
                                    {.rule = method == Method::DouglasPeucker ? detail::SplitRule::FarthestPoint
                                                                              : detail::SplitRule::CenterOfCurvature,
                                     .segments = has_segments ? m : 0,
                                     .tolerance = has_tolerance ? *options.tolerance : 0.0,
                                     .norm = norm});
    }
    case Method::Automatic:
      break;
  }
  throw InvalidInput("unknown linearization method");
}

}  // namespace sculpt::curves
