#pragma once
/// \file query_cost.hpp
/// Cost of queries with extent (Ihm & Naylor 1990, sec. 6: "if the query object Q has extent ...
/// a subgraph of the tree will be visited. Thus the cost of the query is the number of nodes in
/// this subgraph"), estimated by seeded Monte Carlo: queries are placed uniformly in the sample
/// box, and the mean number of partitioning nodes visited is reported with a confidence interval.
/// Point queries give the expected depth of depth_cost.hpp, a check of the exact computation.

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "bsp/solid.hpp"

namespace sculpt::reports {

enum class QueryShape {
  Point,    ///< a point: cost = depth of the leaf reached
  Segment,  ///< a segment of length `size`, centre uniform in the box, direction uniform on the sphere
  Box,      ///< an axis-aligned cube of edge `size`, centre uniform in the box
};
std::string query_shape_name(QueryShape shape);  ///< "point", "segment", "box"

struct QueryCostOptions {
  QueryShape shape = QueryShape::Segment;
  double size = 0;                ///< segment length or cube edge, world units; 0: a tenth of the box diagonal
  int samples = 10000;            ///< number of random queries, >= 2
  std::uint64_t seed = 1;         ///< std::mt19937_64 seed (portable mapping to doubles)
  double confidence = 0.95;       ///< of the interval, in (0, 1)
  std::optional<Eigen::AlignedBox3d> sample_box = std::nullopt;  ///< default: the solid's bounding box
};

struct QueryCost {
  QueryShape shape = QueryShape::Point;
  double size = 0;
  int samples = 0;
  double mean_nodes = 0;             ///< partitioning nodes visited, mean over the queries
  double std_dev = 0;                ///< sample standard deviation
  double ci_low = 0, ci_high = 0;    ///< normal-approximation interval for the mean
  double confidence = 0;
  double mean_leaves = 0;            ///< leaves reached, mean (1 for points)
};

/// \throw InvalidInput for samples < 2, a confidence outside (0, 1), size < 0, or a bad box
///        (see depth_cost)
QueryCost query_cost(const Solid& solid, const QueryCostOptions& options = {});

}  // namespace sculpt::reports
