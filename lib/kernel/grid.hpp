#pragma once
/// \file grid.hpp
/// The coordinate grid of the exact kernel (docs/kernel.md, "Precision contract").
/// Input coordinates are snapped to multiples of kGridStep world units and must lie within
/// [-kMaxWorld, kMaxWorld]; anything else is rejected with RangeError naming that range.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "kernel/exact_int.hpp"

namespace sculpt::kernel {

inline constexpr int kGridShift = 15;                                   ///< step = 2^-15
inline constexpr double kGridStep = 1.0 / double(std::int64_t(1) << kGridShift);
inline constexpr std::int64_t kMaxCoord = std::int64_t(1) << kCoordBits;  ///< in grid units
inline constexpr double kMaxWorld = double(kMaxCoord) * kGridStep;       ///< 1024 world units

/// A point of the grid, in grid units (world = grid * kGridStep).
struct GridPoint {
  std::int64_t x = 0, y = 0, z = 0;
  friend bool operator==(const GridPoint&, const GridPoint&) = default;
};

/// Nearest grid value of a world coordinate. \throw RangeError if NaN or |v| > kMaxWorld.
std::int64_t snap(double v);
/// Nearest grid point of a world point. \throw RangeError as above.
GridPoint snap(const Eigen::Vector3d& p);
/// World coordinates of a grid point.
inline Eigen::Vector3d to_world(const GridPoint& g) {
  return {double(g.x) * kGridStep, double(g.y) * kGridStep, double(g.z) * kGridStep};
}
/// "[-1024, 1024] world units (grid step 2^-15)": the text every RangeError quotes.
std::string range_text();

}  // namespace sculpt::kernel
