// FeasibilitySolver: the segment errors of candidate edges (Definition 2.3), measured on demand or
// stored once per edge (build_rows, store_errors), exactly as segment_error() computes them.
#include "curves/optimal/feasibility_solver_impl.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace sculpt::curves::detail {

double FeasibilitySolver::Impl::evaluation_cost() const {
  double total = 0;
  for (int a = 0; a + 1 < count(); ++a)
    total += static_cast<double>(reach_[a] - a) *
             (vertex_[reach_[a]] - vertex_[a] <= kDirectSpan ? 0.5 * (vertex_[reach_[a]] - vertex_[a]) : 128.0);
  return total;
}

void FeasibilitySolver::Impl::store_errors(double limit) {
  const int count = this->count();
  row_.assign(count, 0);
  std::size_t total = 0;
  for (int a = 0; a + 1 < count; ++a) {
    row_[a] = total;
    total += static_cast<std::size_t>(reach_[a] - a);
  }
  std::vector<double> values(total);
  for (int a = 0; a + 1 < count; ++a)
    for (int b = a + 1; b <= reach_[a]; ++b)
      values[row_[a] + (b - a - 1)] = stored_error(vertex_[a], vertex_[b], limit);
  stored_ = std::move(values);
}

bool FeasibilitySolver::Impl::build_rows(double limit, double budget, double floor) {
  const int count = this->count();
  std::vector<std::size_t> rows(count, 0);
  std::vector<int> reach(count, count - 1);
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(count) * 16);
  if (!columns_) columns_.emplace(points_);
  measured_.clear();
  cross2_.clear();
  length2_.clear();
  // squared thresholds with margins far above rounding: beyond limit / certainly below floor
  const Thresholds squared{limit * limit * (1.0 + kRelativeMargin), floor * floor * (1.0 - kRelativeMargin), limit,
                           floor};
  double scanned = 0.0;  // point distances so far (work budget)
  for (int a = 0; a + 1 < count; ++a) {
    rows[a] = values.size();
    const int i = vertex_[a];
    int violator = -1, b = a + 1;
    bool rejected = false;
    for (; b < count; ++b) {
      const int j = vertex_[b];
      // (only after a rejected chord: while chords pass, the row certainly goes on)
      if (rejected && j - i >= 3 && pair_excludes(i, j - 1, i + (j - i) / 2, limit)) break;
      if (j - i == 1) {  // no interior point: error 0
        values.push_back(floor > 0.0 ? kBelow : 0.0);
        rejected = false;
        continue;
      }
      const RowEntry entry = hinted_scan(i, j, squared, violator);
      if (entry.queued) {
        measured_.push_back(values.size());
        cross2_.push_back(entry.cross2);
        length2_.push_back(entry.length2);
      }
      values.push_back(entry.value);
      violator = entry.violator;
      rejected = entry.beyond;
      scanned += entry.work;
      if ((scanned += 1.0) > 2e6 + budget * (a + 1)) return false;
    }
    reach[a] = b - 1;
  }
  // The distances of the measured chords' farthest points, sqrt(cross2) / sqrt(length2)
  // exactly as ChordDistance computes them, in a loop of independent roots and divisions.
  const std::vector<double> distances = chord_distances(cross2_, length2_, kBeyond, kBelow);
  for (std::size_t t = 0; t < measured_.size(); ++t) values[measured_[t]] = distances[t];
  row_ = std::move(rows);
  reach_ = std::move(reach);
  stored_ = std::move(values);
  reach_eps_ = limit;
  floor_ = floor;
  return true;
}

void FeasibilitySolver::Impl::materialize() {
  if (floor_ <= 0.0) return;
  for (int a = 0; a + 1 < count(); ++a)
    for (int b = a + 1; b <= reach_[a]; ++b)
      if (double& value = stored_[row_[a] + (b - a - 1)]; value < 0.0)
        value = segment_error(points_, vertex_[a], vertex_[b], norm_);
  floor_ = 0.0;
}

FeasibilitySolver::Impl::ChordError FeasibilitySolver::Impl::bounded_error(int i, int j, double limit) const {
  if (norm_ != Norm::LInf || j - i < 2 || !(limit < std::numeric_limits<double>::infinity()))
    return {segment_error(points_, i, j, norm_), -1};
  const Eigen::Vector3d& a = points_[i];
  const Eigen::Vector3d d = points_[j] - a;
  if (d.squaredNorm() == 0.0) return {segment_error(points_, i, j, norm_), -1};
  const double bound = beyond_squared(limit * limit * d.squaredNorm());
  int farthest = i + 1;
  double largest = -1.0;
  for (int k = i + 1; k < j; ++k) {
    const double s = (points_[k] - a).cross(d).squaredNorm();
    if (s > largest) {
      largest = s;
      farthest = k;
      if (s > bound) break;
    }
  }
  const double error = ChordDistance(a, points_[j])(points_[farthest]);  // as segment_error() measures it
  return {error, error > limit ? farthest : -1};
}

FeasibilitySolver::Impl::RowEntry FeasibilitySolver::Impl::hinted_scan(int i, int j, const Thresholds& t, int hint) {
  const PointColumns& c = *columns_;
  const double dx = c.x[j] - c.x[i], dy = c.y[j] - c.y[i], dz = c.z[j] - c.z[i];
  const double length2 = (dx * dx + dy * dy) + dz * dz;  // = (p_j - p_i).squaredNorm()
  if (norm_ != Norm::LInf || length2 == 0.0 || j - i > kRowTreeSpan) {
    const ChordError measured = hinted_error(i, j, t.limit, hint);
    return {.value = measured.error,
            .beyond = measured.error > t.limit,
            .violator = measured.violator,
            .work = std::min(j - i, kRowTreeSpan)};
  }
  const double bound = t.beyond2 * length2 + kUnderflowMargin;
  if (hint > i && hint < j && cross2_to(c, i, hint, dx, dy, dz) > bound)
    return {.value = kBeyond, .beyond = true, .violator = hint, .work = 0};
  const ChordScan scan = planar_ ? scan_chord_planar(c, i, j, bound) : scan_chord(c, i, j, bound);
  const int work = scan.beyond >= 0 ? scan.beyond - i : j - i;
  if (scan.beyond >= 0) return {.value = kBeyond, .beyond = true, .violator = scan.beyond, .work = work};
  // below floor for certain: sqrt(cross2) / sqrt(length2) < floor
  if (scan.cross2 < t.below2 * length2) return {.value = kBelow, .beyond = false, .violator = -1, .work = work};
  return {.value = 0.0,
          .beyond = false,
          .violator = -1,
          .work = work,
          .queued = true,
          .cross2 = scan.cross2,
          .length2 = length2};
}

FeasibilitySolver::Impl::ChordError FeasibilitySolver::Impl::hinted_error(int i, int j, double limit, int hint) {
  if (norm_ == Norm::LInf && hint > i && hint < j) {
    const Eigen::Vector3d d = points_[j] - points_[i];
    const double s = (points_[hint] - points_[i]).cross(d).squaredNorm();
    if (s > beyond_squared(limit * limit * d.squaredNorm()) && d.squaredNorm() > 0.0)
      return {ChordDistance(points_[i], points_[j])(points_[hint]), hint};
  }
  if (j - i > kRowTreeSpan) return {tree().error(i, j, limit), -1};
  return bounded_error(i, j, limit);
}

double FeasibilitySolver::Impl::stored_error(int i, int j, double limit) {
  if (j - i <= kDirectSpan) return bounded_error(i, j, limit).error;
  if (norm_ == Norm::LInf && limit < std::numeric_limits<double>::infinity()) {
    const ChordDistance distance(points_[i], points_[j]);
    for (int t = 1; t <= kSpreadProbes; ++t) {
      const int k = i + static_cast<int>((static_cast<long long>(j - i) * t) / (kSpreadProbes + 1));
      if (const double d = distance(points_[k]); d > limit) return d;
    }
  }
  return tree().error(i, j, limit);
}

}  // namespace sculpt::curves::detail
