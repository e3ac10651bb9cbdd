#include "reports/query_cost.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "reports/range_query_tree.hpp"

namespace sculpt::reports {
namespace {

double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// Two-sided normal quantile z with P(|Z| < z) = confidence, by bisection on erf.
double normal_quantile(double confidence) {
  double lo = 0, hi = 10;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erf(mid / std::numbers::sqrt2) < confidence ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Partitioning nodes and leaves visited by a query whose extent on each plane is the range
/// [f(centre) - reach(plane), f(centre) + reach(plane)]; explicit stack.
template <class Reach>
std::pair<int, int> visit(const RangeQueryTree& tree, const Eigen::Vector3d& centre, Reach reach,
                          std::vector<std::int32_t>& stack) {
  int nodes = 0, leaves = 0;
  stack.assign(1, tree.root());
  while (!stack.empty()) {
    const std::int32_t k = stack.back();
    stack.pop_back();
    if (k < 0) {
      ++leaves;
      continue;
    }
    ++nodes;
    const auto& n = tree.nodes()[static_cast<std::size_t>(k)];
    const double f = n.a * centre.x() + n.b * centre.y() + n.c * centre.z() + n.d;
    const double r = reach(n);
    if (f - r <= 0.0) stack.push_back(n.child[0]);
    if (f + r > 0.0) stack.push_back(n.child[1]);
  }
  return {nodes, leaves};
}

}  // namespace

std::string query_shape_name(QueryShape shape) {
  switch (shape) {
    case QueryShape::Point: return "point";
    case QueryShape::Segment: return "segment";
    case QueryShape::Box: return "box";
  }
  return "?";
}

QueryCost query_cost(const Solid& solid, const QueryCostOptions& options) {
  if (options.samples < 2) throw InvalidInput("query cost: samples must be >= 2");
  if (!(options.confidence > 0.0 && options.confidence < 1.0))
    throw InvalidInput("query cost: confidence must lie strictly between 0 and 1");
  if (!(options.size >= 0.0) || !std::isfinite(options.size)) throw InvalidInput("query cost: size must be >= 0");
  Eigen::AlignedBox3d box;
  if (options.sample_box) {
    box = *options.sample_box;
  } else {
    if (solid.is_empty() || solid.root() == kIn)
      throw InvalidInput("query cost: an empty or unbounded solid has no bounding box; give a sample box");
    box = bounding_box(solid);
  }
  if (box.isEmpty() || !(box.sizes().minCoeff() > 0.0) || !box.sizes().allFinite())
    throw InvalidInput("query cost: the sample box must have positive, finite extent in x, y and z");

  QueryCost out;
  out.shape = options.shape;
  out.size = options.shape == QueryShape::Point ? 0.0 : (options.size > 0 ? options.size : 0.1 * box.diagonal().norm());
  out.samples = options.samples;
  out.confidence = options.confidence;

  const RangeQueryTree tree(solid);
  std::mt19937_64 rng(options.seed);
  std::vector<std::int32_t> stack;
  double sum = 0, sum_sq = 0, leaf_sum = 0;
  const double half = 0.5 * out.size;
  CancelPoll poll;
  for (int i = 0; i < options.samples; ++i) {
    Eigen::Vector3d centre;
    for (int a = 0; a < 3; ++a) centre[a] = box.min()[a] + unit(rng) * box.sizes()[a];
    std::pair<int, int> cost{0, 1};
    switch (options.shape) {
      case QueryShape::Point:
        cost = visit(tree, centre, [](const auto&) { return 0.0; }, stack);  // a point reaches no plane
        break;
      case QueryShape::Segment: {
        // Uniform direction: z uniform in [-1, 1], azimuth uniform (Archimedes).
        const double z = 2 * unit(rng) - 1, phi = 2 * std::numbers::pi * unit(rng), s = std::sqrt(1 - z * z);
        const Eigen::Vector3d d = half * Eigen::Vector3d(s * std::cos(phi), s * std::sin(phi), z);
        cost = visit(tree, centre, [&](const auto& n) { return std::abs(n.a * d.x() + n.b * d.y() + n.c * d.z()); }, stack);
        break;
      }
      case QueryShape::Box:
        cost = visit(tree, centre, [&](const auto& n) { return half * (std::abs(n.a) + std::abs(n.b) + std::abs(n.c)); },
                     stack);
        break;
    }
    poll.tick(static_cast<std::uint32_t>(cost.first) +
              1);  // Ctrl-C, by nodes visited: a box query can visit most of the tree
    sum += cost.first;
    sum_sq += double(cost.first) * cost.first;
    leaf_sum += cost.second;
  }
  const double n = options.samples;
  out.mean_nodes = sum / n;
  out.mean_leaves = leaf_sum / n;
  out.std_dev = std::sqrt(std::max(0.0, (sum_sq - n * out.mean_nodes * out.mean_nodes) / (n - 1)));
  const double half_width = normal_quantile(options.confidence) * out.std_dev / std::sqrt(n);
  out.ci_low = out.mean_nodes - half_width;
  out.ci_high = out.mean_nodes + half_width;
  return out;
}

}  // namespace sculpt::reports
