#pragma once
/// \file depth_cost.hpp
/// Expected cost of point classification (Ihm & Naylor 1990, sec. 6): for points uniform in a
/// sample space of volume V, a leaf cell C of volume v_C at depth d_C is reached with probability
/// p_C = v_C / V at cost d_C, so the expected depth is sum p_C d_C. No binary tree with these
/// leaf probabilities can do better than the entropy H = -sum p_C log2 p_C (Shannon; Kraft's
/// inequality), so the ratio expected depth / H measures how far the tree is from optimal.
/// Each leaf cell is clipped to the sample box exactly by bsp/cells.hpp (DepthCost::cell_volumes
/// says so in the report).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bsp/solid.hpp"

namespace sculpt::reports {

/// Cells of one depth, and their share of the sample space.
struct DepthBin {
  int depth = 0;
  int in_cells = 0, out_cells = 0;        ///< cells meeting the sample box
  double in_probability = 0, out_probability = 0;  ///< sum of v_C / V
};

struct DepthCost {
  Eigen::AlignedBox3d sample_box;
  double sample_volume = 0;
  double cell_volume_sum = 0;   ///< sum of the clipped cell volumes (equals sample_volume)
  double expected_depth = 0;    ///< sum p_C d_C
  double entropy_bound = 0;     ///< H = -sum p_C log2 p_C
  double ratio = 0;             ///< expected_depth / entropy_bound (0 if H = 0)
  int nodes = 0;                ///< partitioning nodes of the whole tree
  int leaves = 0, in_leaves = 0, out_leaves = 0;
  int height = 0;
  int cells_in_box = 0;         ///< leaf cells with positive volume in the box
  double in_volume = 0;         ///< volume of the in-cells within the box (the solid's, if it fits)
  std::vector<DepthBin> histogram;  ///< by depth, only depths that occur in the box
  std::string cell_volumes;         ///< how the cell volumes were computed
};

struct DepthCostOptions {
  /// The sample space; default: the solid's bounding box. Its corners are snapped to the kernel
  /// grid (nearest point; \throw RangeError outside the world range).
  std::optional<Eigen::AlignedBox3d> sample_box = std::nullopt;
};

/// \throw InvalidInput if the box is empty or flat, or no box is given for an empty solid
DepthCost depth_cost(const Solid& solid, const DepthCostOptions& options = {});

}  // namespace sculpt::reports
