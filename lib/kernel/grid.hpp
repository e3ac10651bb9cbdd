#pragma once
/// \file grid.hpp
/// The coordinate grid of the exact kernel (docs/kernel.md, "Precision contract" and "World
/// range"). In grid units the grid is fixed: integer coordinates with |x| <= kMaxCoord = 2^25,
/// which the bit budgets of kernel/exact_int.hpp are built on. A `Grid` chooses what one grid
/// unit is in the world: step = 2^-shift world units, so the world range is
/// [-2^(25 - shift), 2^(25 - shift)]. The default (shift 15) is step 2^-15, range [-1024, 1024].
/// Every solid carries its Grid (bsp/solid.hpp); every conversion between world and grid units
/// goes through it. Since the step is a power of two, the conversions are exact scalings, and a
/// solid at shift k is exactly the default-grid solid scaled by 2^(15 - k).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "kernel/exact_int.hpp"

namespace sculpt::kernel {

inline constexpr std::int64_t kMaxCoord = std::int64_t(1) << kCoordBits;  ///< in grid units

/// A point of the grid, in grid units (world = grid * step).
struct GridPoint {
  std::int64_t x = 0, y = 0, z = 0;
  friend bool operator==(const GridPoint&, const GridPoint&) = default;
};

/// The world <-> grid mapping: world = grid units * 2^-shift (see the file comment).
class Grid {
 public:
  static constexpr int kDefaultShift = 15;  ///< step 2^-15, range [-1024, 1024]
  static constexpr int kMinShift = -32;     ///< coarsest: step 2^32, range 2^57
  static constexpr int kMaxShift = 64;      ///< finest: step 2^-64, range 2^-39

  /// The default grid (step 2^-15).
  constexpr Grid() = default;
  /// Step 2^-shift. \throw InvalidInput unless kMinShift <= shift <= kMaxShift.
  static Grid from_shift(int shift);
  /// The grid of this step, which must be 2^-k with kMinShift <= k <= kMaxShift.
  /// \throw InvalidInput otherwise (the message names the nearest powers of two).
  static Grid from_step(double step);
  /// The finest grid whose range holds |v| (nullopt if v is not finite or beyond every grid).
  static std::optional<Grid> fitting(double v);

  [[nodiscard]] int shift() const { return shift_; }
  /// The step in world units, 2^-shift.
  [[nodiscard]] double step() const { return step_; }
  /// The largest |world coordinate|, kMaxCoord * step.
  [[nodiscard]] double max_world() const { return double(kMaxCoord) * step_; }
  /// 2^(kDefaultShift - shift): what one world unit at the default grid becomes at this grid.
  /// Absolute tolerances written for the default grid (1e-12 * (1 + |p|)) scale with it, so
  /// that every decision at this grid is the default grid's decision on the scaled solid.
  [[nodiscard]] double unit() const { return step_ * double(std::int64_t(1) << kDefaultShift); }

  /// Nearest grid value of a world coordinate (ties away from zero).
  /// \throw RangeError if not finite or |v| > max_world(); the message names a grid that fits.
  [[nodiscard]] std::int64_t snap(double v) const;
  /// Nearest grid point of a world point. \throw RangeError as above.
  [[nodiscard]] GridPoint snap(const Eigen::Vector3d& p) const;
  /// A world length or coordinate in grid units, unrounded (an exact scaling).
  [[nodiscard]] double to_grid(double world) const { return world * scale_; }
  /// Grid units (any double: rounded vertices, plane offsets) to world units, exactly.
  [[nodiscard]] double to_world(double grid_units) const { return grid_units * step_; }
  [[nodiscard]] Eigen::Vector3d to_world(const Eigen::Vector3d& grid_units) const { return grid_units * step_; }
  [[nodiscard]] Eigen::Vector3d to_world(const GridPoint& g) const {
    return {double(g.x) * step_, double(g.y) * step_, double(g.z) * step_};
  }

  /// The step as written in scripts and messages: "2^-15".
  [[nodiscard]] std::string name() const;
  /// "[-1024, 1024] world units (grid step 2^-15)": the text every RangeError quotes.
  [[nodiscard]] std::string range_text() const;
  /// A RangeError message for a world value v outside this grid's range: what was out of range
  /// (`what`, e.g. "coordinate 3000"), the range, and the finest grid that would hold v.
  [[nodiscard]] std::string out_of_range(const std::string& what, double v) const;

  friend bool operator==(const Grid& a, const Grid& b) { return a.shift_ == b.shift_; }

 private:
  explicit Grid(int shift);
  int shift_ = kDefaultShift;
  double step_ = 1.0 / double(std::int64_t(1) << kDefaultShift);
  double scale_ = double(std::int64_t(1) << kDefaultShift);  // 1 / step_
};

// The default grid's values, for code and tests that work at the default grid only; library code
// takes the Grid of its solid or its parameters.
inline constexpr int kGridShift = Grid::kDefaultShift;                   ///< step = 2^-15
inline constexpr double kGridStep = 1.0 / double(std::int64_t(1) << kGridShift);
inline constexpr double kMaxWorld = double(kMaxCoord) * kGridStep;       ///< 1024 world units

/// Grid{}.snap(v): nearest value at the default grid. \throw RangeError as Grid::snap.
inline std::int64_t snap(double v) { return Grid{}.snap(v); }
/// Grid{}.snap(p). \throw RangeError as Grid::snap.
inline GridPoint snap(const Eigen::Vector3d& p) { return Grid{}.snap(p); }
/// Grid{}.to_world(g).
inline Eigen::Vector3d to_world(const GridPoint& g) { return Grid{}.to_world(g); }
/// Grid{}.range_text().
inline std::string range_text() { return Grid{}.range_text(); }

}  // namespace sculpt::kernel
