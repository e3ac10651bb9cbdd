#include "kernel/grid.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/errors.hpp"

namespace sculpt::kernel {

Grid::Grid(int shift) : shift_(shift), step_(std::ldexp(1.0, -shift)), scale_(std::ldexp(1.0, shift)) {}

Grid Grid::from_shift(int shift) {
  if (shift < kMinShift || shift > kMaxShift) {
    std::ostringstream s;
    s << "grid step 2^" << -shift << " is outside the supported steps 2^" << -kMaxShift << " .. 2^" << -kMinShift;
    throw InvalidInput(s.str());
  }
  return Grid(shift);
}

Grid Grid::from_step(double step) {
  int e = 0;
  const double m = std::isfinite(step) && step > 0 ? std::frexp(step, &e) : 0.0;
  if (m != 0.5) {  // step = m 2^e with m in [0.5, 1): a power of two has m = 0.5
    std::ostringstream s;
    s << "grid step must be a power of two (2^k, k in [" << -kMaxShift << ", " << -kMinShift << "]), got " << step;
    if (m > 0) {
      const int k = m < std::sqrt(0.5) ? e - 1 : e;  // nearest power of two (geometrically)
      s << "; the nearest is 2^" << k << " = " << std::ldexp(1.0, k);
    }
    throw InvalidInput(s.str());
  }
  return from_shift(1 - e);
}

std::optional<Grid> Grid::fitting(double v) {
  if (!std::isfinite(v)) return std::nullopt;
  const double a = std::fabs(v);
  if (a == 0) return Grid(kMaxShift);
  // |v| <= 2^(kCoordBits - k): a = m 2^e, m in [0.5, 1); k <= kCoordBits - e, or one more when
  // a is exactly 2^(e - 1).
  int e = 0;
  const double m = std::frexp(a, &e);
  const int k = std::min(kMaxShift, kCoordBits - e + (m == 0.5 ? 1 : 0));
  if (k < kMinShift) return std::nullopt;
  return Grid(k);
}

std::string Grid::name() const { return "2^" + std::to_string(-shift_); }

std::string Grid::range_text() const {
  std::ostringstream s;
  s << "[-" << max_world() << ", " << max_world() << "] world units (grid step " << name() << ")";
  return s.str();
}

std::string Grid::out_of_range(const std::string& what, double v) const {
  std::ostringstream s;
  s << what << " is outside the exact kernel's range " << range_text();
  if (std::optional<Grid> fit = fitting(v)) {
    // A value checked with a margin may lie within this grid's range: then the next coarser grid.
    if (fit->shift() >= shift_) fit = shift_ > kMinShift ? std::optional<Grid>(Grid(shift_ - 1)) : std::nullopt;
    if (fit) s << "; a grid of step " << fit->name() << " would fit coordinates up to " << fit->max_world();
  }
  return s.str();
}

std::int64_t Grid::snap(double v) const {
  if (!std::isfinite(v) || std::fabs(v) > max_world()) {
    std::ostringstream what;
    what << "coordinate " << v;
    throw RangeError(out_of_range(what.str(), v));
  }
  return std::llround(v * scale_);  // exact scaling by a power of two, then nearest
}

GridPoint Grid::snap(const Eigen::Vector3d& p) const { return {snap(p.x()), snap(p.y()), snap(p.z())}; }

}  // namespace sculpt::kernel
