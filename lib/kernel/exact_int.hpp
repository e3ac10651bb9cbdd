#pragma once
/// \file exact_int.hpp
/// Integer types of the exact kernel and the bit budget that makes every predicate exact.
/// See docs/kernel.md for the precision contract.

#include <boost/multiprecision/cpp_int.hpp>
#include <cstdint>

namespace sculpt::kernel {

__extension__ typedef __int128 Int128;  ///< plane offsets d and point evaluations
using Int256 = boost::multiprecision::int256_t;  ///< exact homogeneous vertices and orientations

/// Bit budget (Bernstein & Fussell 2009, sec. 3; Nehring-Wirxel et al. 2021, sec. 4).
/// |grid coordinate| <= 2^kCoordBits; |a|,|b|,|c| <= 2^kNormalBits; |d| <= 2^kOffsetBits.
inline constexpr int kCoordBits = 25;
inline constexpr int kNormalBits = 53;   ///< a plane through three grid points: 2 * (kCoordBits + 1) + 1
inline constexpr int kOffsetBits = 80;   ///< d = -n.p: kNormalBits + kCoordBits + 2
/// Homogeneous vertex of three planes: W = det(normals), X,Y,Z = det with one column replaced by d.
inline constexpr int kVertexWBits = 3 * kNormalBits + 3;                 // 6 terms
inline constexpr int kVertexXBits = 2 * kNormalBits + kOffsetBits + 3;   // 6 terms
/// Orientation of a vertex against a fourth plane: a X + b Y + c Z + d W.
inline constexpr int kOrientBits =
    (kNormalBits + kVertexXBits > kOffsetBits + kVertexWBits ? kNormalBits + kVertexXBits
                                                             : kOffsetBits + kVertexWBits) + 2;
static_assert(2 * (kCoordBits + 1) + 1 <= kNormalBits, "normal of three grid points must fit");
static_assert(kNormalBits + kCoordBits + 2 <= kOffsetBits, "offset of a grid plane must fit");
static_assert(kNormalBits <= 53, "normals must be exact in a double");
static_assert(kOffsetBits + 1 <= 127, "offsets must fit Int128");
static_assert(kNormalBits + kCoordBits + 2 <= 126 && kOffsetBits + 2 <= 126,
              "evaluating a plane at a grid point must fit Int128");
static_assert(kOrientBits <= 255, "vertex orientation must fit Int256");

}  // namespace sculpt::kernel
