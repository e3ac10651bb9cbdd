// SplitsAndBalance: the batch union's and the cell merge's choice of a node's plane
// (Thibault & Naylor 1987 sec. 3; plane_choice.hpp).
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "bsp/partition/plane_choice.hpp"

namespace sculpt::bsp::detail {

using kernel::Side;

namespace {

// How a plane divides the sampled pieces of a cell.
struct Tally {
  int negative = 0, positive = 0, both = 0;
  [[nodiscard]] double score(double split_weight) const { return split_weight * both + std::abs(negative - positive); }
  [[nodiscard]] int larger() const { return std::max(negative, positive); }
};

// Scores planes against `sample` pieces of the cell, evenly spaced.
struct BalanceScorer {
  const kernel::PlaneTable& planes;
  const PiecePool& pool;
  std::span<const std::int32_t> pieces;
  std::size_t sample;
  bool approximate;

  // Side of a piece, for scoring only (a heuristic: the split itself is exact): the box first,
  // else exactly, or (`approximate`) from the corners' approximations.
  [[nodiscard]] Side side(std::size_t id, std::int32_t plane) const {
    const PartitionPiece& piece = pool.pieces[id];
    if (approximate) return partition::approximate_side(piece, pool.boxes[id], planes[plane]);
    const Side quick = kernel::box_side(pool.boxes[id], planes[plane]);
    return quick != Side::Both ? quick : kernel::classify(planes, piece.polygon, plane);
  }
  [[nodiscard]] Tally tally(std::int32_t plane) const {
    Tally t;
    const std::size_t n = pieces.size();
    for (std::size_t j = 0; j < sample; ++j) {
      const Side s = side(std::size_t(pieces[j * n / sample]), plane);
      t.negative += s == Side::Negative;
      t.positive += s == Side::Positive;
      t.both += s == Side::Both;
    }
    return t;
  }
};

}  // namespace

PlaneChoice choose_by_balance(Arena& arena, const PiecePool& pool, std::span<const std::int32_t> pieces,
                              const AutopartitionOptions& options) {
  PlaneChoice choice;
  const std::size_t n = pieces.size();
  if (n <= 1) return choice;
  const std::size_t k = std::min(n, std::size_t(std::max(1, options.candidates)));
  const std::size_t m = std::min(n, std::size_t(std::max(1, options.sample)));
  const BalanceScorer scorer{arena.planes, pool, pieces, m, options.approximate_scores};
  double best = 1e300;
  int best_larger = 0;  // the larger side of the best candidate, in sampled pieces
  for (std::size_t c = 0; c < k; ++c) {
    const std::size_t i = c * n / k;
    const Tally t = scorer.tally(pool.pieces[std::size_t(pieces[i])].outward);
    const double score = t.score(options.split_weight);
    if (score < best) best = score, choice.face = i, best_larger = t.larger();
  }
  // Where every candidate leaves nearly all pieces on one side (a convex part: its faces see
  // each other from behind), a plane x, y or z = median of the pieces' box centres + 1/2 grid
  // step, which carries no piece, may balance better (kd-tree style; Naylor 1990's balance).
  if (!options.auxiliary_splits || n < kAuxiliarySplitFrom || best_larger * 10 <= int(m) * 9) return choice;
  std::vector<double> centre(m);
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t j = 0; j < m; ++j) {
      const kernel::CornerBox& b = pool.boxes[std::size_t(pieces[j * n / m])];
      centre[j] = b.valid ? 0.5 * (b.lo[axis] + b.hi[axis]) : 0.0;
    }
    std::nth_element(centre.begin(), centre.begin() + std::ptrdiff_t(m / 2), centre.end());
    kernel::Plane e{};
    if (!partition::half_step_plane(axis, centre[m / 2], e)) continue;
    const std::int32_t candidate = arena.planes.add(e, true);
    const double score = scorer.tally(candidate).score(options.split_weight);
    if (score < best) best = score, choice.auxiliary = candidate;
  }
  return choice;
}

}  // namespace sculpt::bsp::detail
