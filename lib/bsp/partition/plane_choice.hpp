#pragma once
/// \file plane_choice.hpp
/// Internal (autopartition): choosing a node's plane. Only the choice is estimated (in doubles,
/// from sampled pieces and points, with a fixed seed); the splits it leads to are exact.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bsp/partition/autopartition.hpp"
#include "bsp/partition/piece_pool.hpp"

namespace sculpt::bsp::detail {

/// A node's plane: the outward plane of the piece at position `face` of the cell's pieces, or
/// (`auxiliary` >= 0, an arena plane) a plane that carries none of them.
struct PlaneChoice {
  std::size_t face = 0;
  std::int32_t auxiliary = -1;
};

/// SplitsAndBalance (autopartition.hpp): `split_weight * splits + |negative - positive|` over a
/// sample of the cell's pieces, for a few of their planes; where all of them leave nearly every
/// piece on one side, axis-aligned planes through the pieces' median compete (added to the arena).
PlaneChoice choose_by_balance(Arena& arena, const PiecePool& pool, std::span<const std::int32_t> pieces,
                              const AutopartitionOptions& options);

/// Deterministic sampling (splitmix64): the same input gives the same tree.
struct SplitMix {
  std::uint64_t state = 0x243f6a8885a308d3ull;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
};

using SamplePoint = std::array<double, 3>;  ///< grid units

/// ExpectedDepth: points uniform in the pieces' bounding box (Ihm & Naylor 1990 sec. 6: a cell
/// is reached with the probability of its share of the volume), at most
/// kVolumeSamplesPerFragment per piece.
std::vector<SamplePoint> volume_sample(const PiecePool& pool, const AutopartitionOptions& options, SplitMix& rng);

/// The signed value of plane `e` at `x`, in doubles (the side a sample point counts for).
double plane_value(const kernel::Plane& e, const SamplePoint& x);

/// ExpectedDepth (Naylor 1993): the candidate of least estimated expected depth, among a few of
/// the pieces' planes (drawn with `rng`), auxiliary planes through the median of the pieces or
/// of the cell's `points` (indices into `sample`), planes just past the pieces and, with
/// AutopartitionOptions::separating_planes, the scored planes moved past them. An auxiliary
/// plane that wins is added to the arena.
PlaneChoice choose_by_depth(Arena& arena, const PiecePool& pool, std::span<const std::int32_t> pieces,
                            std::span<const std::int32_t> points, std::span<const SamplePoint> sample,
                            const AutopartitionOptions& options, SplitMix& rng);

namespace partition {
/// Side of a piece with respect to a plane given by value, for scoring only: the box, else the
/// signs of the plane at the corners' approximations (with a small relative tolerance).
kernel::Side approximate_side(const PartitionPiece& piece, const kernel::CornerBox& box, const kernel::Plane& e);
/// The axis-aligned plane 2 x_axis - (2 floor(c) + 1) = 0, half a grid step above floor(c): it
/// contains no grid point, hence no vertex of a face of from_mesh. False outside the world.
bool half_step_plane(int axis, double c, kernel::Plane& out);
}  // namespace partition

}  // namespace sculpt::bsp::detail
