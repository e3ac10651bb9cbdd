#pragma once
/// \file tree_report.hpp
/// Depth-cost reports of BSP trees (Ihm & Naylor 1990, sec. 6; docs/depth_cost.md): exact expected
/// depth and entropy bound (depth_cost.hpp) plus Monte Carlo query costs (query_cost.hpp), for one
/// tree or for several trees of the same solid built different ways, side by side, as readable
/// text, JSON, or an SVG chart of the depth distribution.
///
///   auto r = analyze(goblet, "goblet");
///   std::cout << report_text({r});
///   auto all = compare_trees({{"revolution", a}, {"B-rep", b}});   // one shared sample box

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "reports/depth_cost.hpp"
#include "reports/query_cost.hpp"

namespace sculpt::reports {

struct ReportOptions {
  std::optional<Eigen::AlignedBox3d> sample_box = std::nullopt;  ///< default: the solid's bounding box
  int query_samples = 2000;   ///< Monte Carlo queries per shape (point, segment, box); 0: none
  double segment_length = 0;  ///< 0: a tenth of the sample box's diagonal
  double box_size = 0;        ///< cube edge; 0: a tenth of the diagonal
  std::uint64_t seed = 1;
};

struct TreeReport {
  std::string name;
  DepthCost depth;
  std::vector<QueryCost> queries;  ///< point, segment, box (empty if query_samples == 0)
  kernel::Grid grid{};             ///< the solid's grid (reports show it when it is not the default)
};

/// \throw InvalidInput (see depth_cost, query_cost)
TreeReport analyze(const Solid& solid, const std::string& name, const ReportOptions& options = {});

struct NamedSolid {
  std::string name;
  Solid solid;
};
/// Reports of several trees over one sample box (given, or the union of their bounding boxes).
std::vector<TreeReport> compare_trees(const std::vector<NamedSolid>& solids, const ReportOptions& options = {});

/// Readable text: one column per tree, then each tree's depth histogram.
std::string report_text(const std::vector<TreeReport>& reports);
/// The same as JSON (an object with a "trees" array).
std::string report_json(const std::vector<TreeReport>& reports);
/// SVG bar chart: probability mass of the sample space by leaf depth, one series per tree,
/// in-cells and out-cells stacked; the expected depth and the entropy bound marked.
std::string depth_chart_svg(const std::vector<TreeReport>& reports);

}  // namespace sculpt::reports
