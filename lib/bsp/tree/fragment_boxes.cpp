#include "bsp/tree/fragment_boxes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace sculpt::bsp::detail {

FragmentBox fragment_box(kernel::PolygonView polygon) {
  const kernel::CornerBox b = kernel::corner_box(polygon);
  FragmentBox f{};
  f.valid = b.valid;
  if (!b.valid) return f;
  // nextafter(v, -inf) and nextafter(v, +inf) on the bit pattern (libm's nextafterf is a call):
  // away from zero is one unit more in the magnitude bits, towards zero one less, and from a zero
  // of either sign the step goes to the smallest subnormal (inf - 1 is the largest float).
  auto step = [](float v, bool up) {
    const auto bits = std::bit_cast<std::uint32_t>(v);
    if ((bits & 0x7fffffffu) == 0) return std::bit_cast<float>(up ? 0x00000001u : 0x80000001u);
    const bool away = (bits >> 31 == 0) == up;  // positive and up, or negative and down
    return std::bit_cast<float>(away ? bits + 1 : bits - 1);
  };
  for (int k = 0; k < 3; ++k) {  // outwards: float(x) may round either way
    f.lo[k] = float(b.lo[k]);
    if (double(f.lo[k]) > b.lo[k]) f.lo[k] = step(f.lo[k], false);
    f.hi[k] = float(b.hi[k]);
    if (double(f.hi[k]) < b.hi[k]) f.hi[k] = step(f.hi[k], true);
  }
  return f;
}

void FragmentBoxes::update_block(std::size_t j) {
  FragmentBox b{};
  b.valid = true;
  for (int k = 0; k < 3; ++k) b.lo[k] = HUGE_VALF, b.hi[k] = -HUGE_VALF;
  const std::size_t end = std::min(each.size(), (j + 1) * kBlock);
  for (std::size_t i = j * kBlock; i < end; ++i) {
    const FragmentBox& x = each[i];
    b.valid &= x.valid;
    for (int k = 0; k < 3; ++k) b.lo[k] = std::min(b.lo[k], x.lo[k]), b.hi[k] = std::max(b.hi[k], x.hi[k]);
  }
  blocks[j] = b;
}

}  // namespace sculpt::bsp::detail
