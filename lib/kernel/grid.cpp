#include "kernel/grid.hpp"

#include <cmath>
#include <sstream>

#include "base/errors.hpp"

namespace sculpt::kernel {

std::string range_text() {
  std::ostringstream s;
  s << "[-" << kMaxWorld << ", " << kMaxWorld << "] world units (grid step 2^-" << kGridShift << ")";
  return s.str();
}

std::int64_t snap(double v) {
  if (!std::isfinite(v) || std::fabs(v) > kMaxWorld) {
    std::ostringstream s;
    s << "coordinate " << v << " is outside the exact kernel's range " << range_text();
    throw RangeError(s.str());
  }
  return std::llround(v / kGridStep);  // exact scaling by a power of two, then nearest
}

GridPoint snap(const Eigen::Vector3d& p) { return {snap(p.x()), snap(p.y()), snap(p.z())}; }

}  // namespace sculpt::kernel
