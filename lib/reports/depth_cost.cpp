#include "reports/depth_cost.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "kernel/grid.hpp"
#include "bsp/cells.hpp"

namespace sculpt::reports {

DepthCost depth_cost(const Solid& solid, const DepthCostOptions& options) {
  DepthCost out;
  if (options.sample_box) {
    out.sample_box = *options.sample_box;
  } else {
    if (solid.is_empty() || solid.root() == kIn)
      throw InvalidInput("depth cost: an empty or unbounded solid has no bounding box; give a sample box");
    out.sample_box = bounding_box(solid);
  }
  // Snapped to the kernel grid (nearest), as bsp/cells.hpp clips to the snapped box: the sample
  // space is then exactly the union of the cells.
  if (!out.sample_box.isEmpty() && out.sample_box.min().allFinite() && out.sample_box.max().allFinite())
    out.sample_box = Eigen::AlignedBox3d(solid.grid().to_world(solid.grid().snap(out.sample_box.min())),
                                         solid.grid().to_world(solid.grid().snap(out.sample_box.max())));
  const Eigen::Vector3d size = out.sample_box.sizes();
  if (out.sample_box.isEmpty() || !(size.minCoeff() > 0.0) || !size.allFinite())
    throw InvalidInput("depth cost: the sample box must have positive, finite extent in x, y and z");
  out.sample_volume = size.prod();

  const TreeStats stats = tree_stats(solid);
  out.nodes = stats.nodes;
  out.in_leaves = stats.in_leaves;
  out.out_leaves = stats.out_leaves;
  out.leaves = stats.in_leaves + stats.out_leaves;
  out.height = stats.height;

  std::map<int, DepthBin> bins;
  out.cell_volumes = "exact (bsp/cells.hpp)";
  // One cell at a time: a large tree has millions, and a list of them would take gigabytes and
  // a second to free when Ctrl-C stops the walk.
  for_each_leaf_cell(solid, out.sample_box, [&](const LeafCell& cell) {
    if (!(cell.volume > 0.0)) return;
    const double p = cell.volume / out.sample_volume;
    ++out.cells_in_box;
    out.cell_volume_sum += cell.volume;
    out.expected_depth += p * cell.depth;
    out.entropy_bound -= p * std::log2(p);
    DepthBin& bin = bins[cell.depth];
    bin.depth = cell.depth;
    if (cell.inside) {
      ++bin.in_cells;
      bin.in_probability += p;
      out.in_volume += cell.volume;
    } else {
      ++bin.out_cells;
      bin.out_probability += p;
    }
  });
  out.ratio = out.entropy_bound > 0.0 ? out.expected_depth / out.entropy_bound : 0.0;
  for (auto& [depth, bin] : bins) out.histogram.push_back(bin);
  return out;
}

}  // namespace sculpt::reports
