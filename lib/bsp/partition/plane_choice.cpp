// What both ways of choosing a node's plane share (plane_choice.hpp).
#include "bsp/partition/plane_choice.hpp"

#include <cmath>

namespace sculpt::bsp::detail::partition {

using kernel::Side;

Side approximate_side(const PartitionPiece& piece, const kernel::CornerBox& box, const kernel::Plane& e) {
  const Side quick = kernel::box_side(box, e);
  if (quick != Side::Both) return quick;
  const double a = double(e.a), b = double(e.b), c = double(e.c), d = e.d_nearest;
  const double tolerance =
      1e-9 * (std::fabs(a) + std::fabs(b) + std::fabs(c)) * (1.0 + std::fabs(box.lo[0]) + std::fabs(box.hi[0]));
  bool neg = false, pos = false;
  for (const kernel::Corner& k : piece.polygon.corners) {
    const double v = a * k.at().x + b * k.at().y + c * k.at().z + d;
    neg |= v < -tolerance;
    pos |= v > tolerance;
  }
  return neg ? (pos ? Side::Both : Side::Negative) : (pos ? Side::Positive : Side::On);
}

bool half_step_plane(int axis, double c, kernel::Plane& out) {
  const double f = std::floor(c);
  if (!(std::fabs(f) < double(kernel::PlaneTable::kWorld))) return false;
  kernel::Int128 normal[3] = {0, 0, 0};
  normal[axis] = 2;
  out = kernel::make_plane(normal[0], normal[1], normal[2], -(2 * kernel::Int128(f) + 1));
  return true;
}

}  // namespace sculpt::bsp::detail::partition
