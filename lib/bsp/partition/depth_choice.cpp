// ExpectedDepth: a node's plane by the greedy estimate of a point query's expected depth
// (Naylor, "Constructing good partitioning trees", 1993; plane_choice.hpp).
#include <algorithm>
#include <cmath>

#include "bsp/partition/plane_choice.hpp"

namespace sculpt::bsp::detail {

using kernel::CornerBox;
using kernel::Side;

namespace {

// The estimated expected depth below a node on a plane: 1 + p- T(n-) + p+ T(n+) (the 1 left
// out), T(n) = log2(1 + n) for a balanced subtree over n pieces, p- the share of the cell's
// points below the plane (pulled towards the pieces' share where few points are left), plus
// `split_weight` times the share of sampled pieces the plane splits.
struct DepthScorer {
  const PiecePool& pool;
  std::span<const std::int32_t> pieces;  // the cell's
  std::span<const std::int32_t> points;  // the cell's, into `sample`
  std::span<const SamplePoint> sample;
  std::size_t piece_sample, point_sample;
  double split_weight;

  [[nodiscard]] double cost(const kernel::Plane& e, double extra) const {
    const std::size_t n = pieces.size(), s = piece_sample;
    int neg = 0, pos = 0, both = 0;
    for (std::size_t j = 0; j < s; ++j) {
      const auto id = std::size_t(pieces[j * n / s]);
      const Side side = partition::approximate_side(pool.pieces[id], pool.boxes[id], e);
      neg += side == Side::Negative;
      pos += side == Side::Positive;
      both += side == Side::Both;
    }
    const std::size_t m = points.size(), q = point_sample;
    double below = 0;
    for (std::size_t j = 0; j < q; ++j) {
      const double v = plane_value(e, sample[std::size_t(points[j * m / q])]);
      below += v < 0 ? 1.0 : (v == 0 ? 0.5 : 0.0);
    }
    constexpr double kPrior = 2.0;  // points' worth of the pieces' shares where few points are left
    const double scale = double(n) / double(s);
    const double n_neg = (neg + both) * scale, n_pos = (pos + both) * scale;
    const double share = n_neg + n_pos > 0 ? n_neg / (n_neg + n_pos) : 0.5;
    const double p_neg = (below + kPrior * share) / (double(q) + kPrior);
    auto subtree = [](double count) { return std::log2(1.0 + count); };
    return p_neg * subtree(n_neg) + (1 - p_neg) * subtree(n_pos) + split_weight * both / double(s) + extra;
  }
  // The centre of sampled piece j's box (0 for an empty box), or sampled point j, on `axis`.
  [[nodiscard]] double coordinate(bool by_points, std::size_t j, int axis) const {
    if (by_points) return sample[std::size_t(points[j * points.size() / point_sample])][std::size_t(axis)];
    const CornerBox& b = pool.boxes[std::size_t(pieces[j * pieces.size() / piece_sample])];
    return b.valid ? 0.5 * (b.lo[axis] + b.hi[axis]) : 0.0;
  }
};

// The least cost so far: a face candidate (position in the cell's pieces), and an auxiliary
// plane if one has cost less than every face candidate scored before it.
struct Best {
  double cost = 1e300;
  std::size_t face = 0;
  bool auxiliary = false;
  kernel::Plane plane{};
  void face_candidate(double c, std::size_t i) {
    if (c < cost) cost = c, face = i;
  }
  void auxiliary_candidate(double c, const kernel::Plane& e) {
    if (c < cost) cost = c, plane = e, auxiliary = true;
  }
};

// A few of the pieces' planes: all of them for a cell of at most `candidates` pieces, else drawn
// with `rng`. Their outward planes are appended to `tried`.
void try_faces(const Arena& arena, const DepthScorer& scorer, std::size_t candidates, SplitMix& rng, Best& best,
               std::vector<std::int32_t>& tried) {
  const std::size_t n = scorer.pieces.size(), k = std::min(n, candidates);
  for (std::size_t c = 0; c < k; ++c) {
    const std::size_t i = k == n ? c : std::size_t(rng.next() % n);
    tried.push_back(scorer.pool.pieces[std::size_t(scorer.pieces[i])].outward);
    best.face_candidate(scorer.cost(arena.planes[tried.back()], 0.0), i);
  }
}

// Axis-aligned planes through the median of the sampled pieces' box centres (balance in
// pieces) or of the cell's points (balance in volume), half a grid step off the grid; only
// across the longest extent of each (kd-tree style: the other axes rarely win, and scoring is
// most of the build's time).
void try_medians(const DepthScorer& scorer, double charge, Best& best) {
  std::vector<double> values;
  for (const bool by_points : {false, true}) {
    const std::size_t count = by_points ? scorer.point_sample : scorer.piece_sample;
    if (count < (by_points ? 16u : 2u)) continue;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (std::size_t j = 0; j < count; ++j)
      for (int a = 0; a < 3; ++a) {
        const double v = scorer.coordinate(by_points, j, a);
        lo[a] = std::min(lo[a], v), hi[a] = std::max(hi[a], v);
      }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
    values.resize(count);
    for (std::size_t j = 0; j < count; ++j) values[j] = scorer.coordinate(by_points, j, axis);
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(count / 2), values.end());
    kernel::Plane e{};
    if (partition::half_step_plane(axis, values[count / 2], e)) best.auxiliary_candidate(scorer.cost(e, charge), e);
  }
}

// Planes half a grid step past the extremes of the cell's pieces' boxes, which cut off a region
// without boundary where the cell's points say it has volume (the region's status is found
// after the build: PendingSide). False (nothing tried) with too few points or an empty box.
bool try_beyond_pieces(const DepthScorer& scorer, double charge, Best& best) {
  if (scorer.point_sample < 16) return false;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const std::int32_t id : scorer.pieces) {
    const CornerBox& b = scorer.pool.boxes[std::size_t(id)];
    if (!b.valid) return false;
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], b.lo[a]), hi[a] = std::max(hi[a], b.hi[a]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    kernel::Plane e{};
    if (partition::half_step_plane(axis, std::ceil(hi[axis]), e)) best.auxiliary_candidate(scorer.cost(e, charge), e);
    if (partition::half_step_plane(axis, std::floor(lo[axis]) - 1.0, e))
      best.auxiliary_candidate(scorer.cost(e, charge), e);
  }
  return true;
}

// Separating planes (Naylor 1993): each scored face plane moved just past all of the cell's
// pieces, behind them (inside a curved part) or in front; the split finds the exact sides.
void try_separating(const Arena& arena, const DepthScorer& scorer, std::span<const std::int32_t> tried, double charge,
                    Best& best) {
  for (const std::int32_t t : tried) {
    const kernel::Plane& e = arena.planes[t];
    const double a = double(e.a), b = double(e.b), c = double(e.c);
    double vmin = 1e300, vmax = -1e300, err = 0;
    for (const std::int32_t id : scorer.pieces)
      for (const kernel::Corner& corner : scorer.pool.pieces[std::size_t(id)].polygon.corners) {
        const double v = a * corner.at().x + b * corner.at().y + c * corner.at().z;
        vmin = std::min(vmin, v), vmax = std::max(vmax, v), err = std::max(err, corner.at().err);
      }
    const double margin =
        (std::fabs(a) + std::fabs(b) + std::fabs(c)) * (1.0 + err) + 1e-12 * std::max(std::fabs(vmin), std::fabs(vmax));
    for (const double offset : {std::floor(vmin - margin), std::ceil(vmax + margin)}) {
      if (!(std::fabs(offset) < 0x1p100)) continue;
      const kernel::Plane sep = kernel::make_plane(e.a, e.b, e.c, -kernel::Int128(offset));
      best.auxiliary_candidate(scorer.cost(sep, charge), sep);
    }
  }
}

}  // namespace

double plane_value(const kernel::Plane& e, const SamplePoint& x) {
  return double(e.a) * x[0] + double(e.b) * x[1] + double(e.c) * x[2] + e.d_nearest;
}

std::vector<SamplePoint> volume_sample(const PiecePool& pool, const AutopartitionOptions& options, SplitMix& rng) {
  SamplePoint lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const CornerBox& b : pool.boxes)
    if (b.valid)
      for (std::size_t a = 0; a < 3; ++a) lo[a] = std::min(lo[a], b.lo[a]), hi[a] = std::max(hi[a], b.hi[a]);
  std::vector<SamplePoint> points;
  if (!(lo[0] <= hi[0])) return points;
  points.resize(
      std::min(std::size_t(std::max(0, options.volume_samples)), std::size_t(kVolumeSamplesPerFragment) * pool.size()));
  for (SamplePoint& x : points)
    for (std::size_t a = 0; a < 3; ++a) x[a] = lo[a] + rng.uniform() * (hi[a] - lo[a]);
  return points;
}

PlaneChoice choose_by_depth(Arena& arena, const PiecePool& pool, std::span<const std::int32_t> pieces,
                            std::span<const std::int32_t> points, std::span<const SamplePoint> sample,
                            const AutopartitionOptions& options, SplitMix& rng) {
  const std::size_t n = pieces.size();
  if (n <= 1) return {};
  const DepthScorer scorer{pool,
                           pieces,
                           points,
                           sample,
                           std::min(n, std::size_t(std::max(1, options.sample))),
                           std::min(points.size(), std::size_t(std::max(0, options.point_sample))),
                           options.split_weight};
  Best best;
  std::vector<std::int32_t> tried;
  try_faces(arena, scorer, std::size_t(std::max(1, options.candidates)), rng, best, tried);
  if (options.auxiliary_splits) {
    try_medians(scorer, options.auxiliary_cost, best);
    if (try_beyond_pieces(scorer, options.auxiliary_cost, best) && options.separating_planes)
      try_separating(arena, scorer, tried, options.auxiliary_cost, best);
  }
  return {best.face, best.auxiliary ? arena.planes.add(best.plane, true) : -1};
}

}  // namespace sculpt::bsp::detail
