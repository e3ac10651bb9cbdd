#pragma once
/// \file range_query_tree.hpp
/// A solid's tree flattened for Monte Carlo costs of queries with extent (Ihm & Naylor 1990,
/// sec. 6: a query visits every node whose plane its extent reaches). Planes are doubles in world
/// units with unit normals, so a query's reach along a normal is a plain dot product. Not exact
/// (a query within about 1e-12 world units of a plane may count one side more or less), which
/// does not matter for sampling; exact point classification is bsp/point_classifier.hpp.

#include <cstdint>
#include <vector>

#include "bsp/solid.hpp"

namespace sculpt::reports {

class RangeQueryTree {
 public:
  explicit RangeQueryTree(const Solid& solid);

  /// One flattened node: plane a x + b y + c z + d (world units, normal of unit length).
  struct FlatNode {
    double a, b, c, d;
    std::int32_t child[2];  ///< negative side, positive side (node index, kIn or kOut)
  };
  [[nodiscard]] const std::vector<FlatNode>& nodes() const { return nodes_; }
  [[nodiscard]] std::int32_t root() const { return root_; }

 private:
  std::vector<FlatNode> nodes_;
  std::int32_t root_;
};

}  // namespace sculpt::reports
