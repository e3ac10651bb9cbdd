#include "reports/tree_report.hpp"

#include "base/errors.hpp"
#include "bsp/boundary.hpp"

namespace sculpt::reports {

TreeReport analyze(const Solid& solid, const std::string& name, const ReportOptions& options) {
  TreeReport r{name, depth_cost(solid, {.sample_box = options.sample_box}), {}, solid.grid()};
  if (options.query_samples > 0) {
    const double diagonal = r.depth.sample_box.diagonal().norm();
    const struct { QueryShape shape; double size; } kinds[] = {
        {QueryShape::Point, 0.0},
        {QueryShape::Segment, options.segment_length > 0 ? options.segment_length : 0.1 * diagonal},
        {QueryShape::Box, options.box_size > 0 ? options.box_size : 0.1 * diagonal}};
    for (const auto& k : kinds)
      r.queries.push_back(query_cost(solid, {.shape = k.shape,
                                             .size = k.size,
                                             .samples = options.query_samples,
                                             .seed = options.seed,
                                             .sample_box = r.depth.sample_box}));
  }
  return r;
}

std::vector<TreeReport> compare_trees(const std::vector<NamedSolid>& solids, const ReportOptions& options) {
  ReportOptions shared = options;
  if (!shared.sample_box) {
    Eigen::AlignedBox3d box;  // empty
    for (const auto& s : solids)
      if (!s.solid.is_empty() && s.solid.root() != kIn) box.extend(bounding_box(s.solid));
    if (box.isEmpty()) throw InvalidInput("compare trees: no bounded, non-empty solid to take a sample box from");
    shared.sample_box = box;
  }
  std::vector<TreeReport> out;
  for (const auto& s : solids) out.push_back(analyze(s.solid, s.name, shared));
  return out;
}

}  // namespace sculpt::reports
