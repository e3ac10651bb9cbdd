#pragma once
/// \file point_classifier.hpp
/// Exact point classification for many queries (Ihm & Naylor 1990 sec. 6: a point descends the
/// tree by the side of each node's plane; the cost is the number of nodes visited).
///
/// The tree is flattened once into an array of nodes holding each plane as doubles in grid units
/// with a static error bound: a point's side is decided by one floating-point evaluation when it
/// lies clearly off the plane (always, except within about 1e-7 grid steps of it), else by the
/// exact integer evaluation of bsp/classify.hpp. The answers, boundary included, equal
/// classify(solid, p) for every point; no allocation per query.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "bsp/classify.hpp"
#include "bsp/solid.hpp"

namespace sculpt {

class PointClassifier {
 public:
  /// Flattens the tree of `solid` (a copy: the classifier does not refer to the solid).
  explicit PointClassifier(const Solid& solid);

  /// Same result as classify(solid, point). \throw RangeError if the point is out of range.
  [[nodiscard]] Classification classify(const Eigen::Vector3d& point) const;

  /// Classifies many points with eight walks interleaved, so the processor overlaps their
  /// memory and arithmetic latencies. \pre out.size() == points.size().
  /// \throw RangeError if a point is out of range (out is then partly written).
  void classify(std::span<const Eigen::Vector3d> points, std::span<Classification> out) const;

 private:
  struct Node {
    double a, b, c, d;     ///< plane in grid units (a, b, c exact; d rounded)
    double bound;          ///< |computed f - exact f| < bound for every grid point in range
    std::int32_t child[2]; ///< negative side, positive side: node index, kIn or kOut
  };
  /// The exact walk of bsp/classify.hpp (both children of a plane through the point).
  Classification exact(const Eigen::Vector3d& point) const;

  std::vector<Node> nodes_;
  TreeRef root_ = kOut;
  std::vector<BspNode> tree_;  ///< the solid's nodes and planes, for the exact walk
  kernel::PlaneTable planes_;
  kernel::Grid grid_;  // the solid's: points are snapped to it
};

}  // namespace sculpt
