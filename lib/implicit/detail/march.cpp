#include "implicit/detail/march.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace sculpt::implicit::detail {
namespace {

using Vec = Eigen::Vector3d;

constexpr double kMaxTurn = 0.6;     // radians of tangent turn allowed across one chord
constexpr double kAim = 0.95;        // aim at a chord height of 0.9 tol (kappa h^2 / 8)
constexpr double kStretch = 0.7;     // a chord below 0.7 tol is tried once more, longer
constexpr double kSingularDrop = 0.5;  // |grad f x grad g| below half its largest value on the walk
constexpr double kSingularConfirm = 0.35;  // ... and at the extrapolated zero below 0.35 of its value here
constexpr double kMidpointDip = 0.6;       // |grad f x grad g| at a chord's midpoint below 0.6 of its ends' mean
constexpr double kSingularMu = 1e-8;       // a located singular point: |grad f x grad g| below 1e-8 of the largest

class Walker {
 public:
  Walker(MarchContext& context)
      : c_(context), sys_(context.system), tol_(context.tolerance),
        h_max_(context.diagonal / 8.0), h_min_(std::max(1e-4 * context.tolerance, 1e-10 * context.diagonal)),
        cos_turn_(std::cos(kMaxTurn)) {}

  Walk run(const CurvePoint& start, const Vec& direction, bool allow_close);

 private:
  [[nodiscard]] bool inside(const Vec& p) const {
    const double slack = 1e-12 * c_.diagonal;
    return ((p.array() >= c_.box.lo.array() - slack) && (p.array() <= c_.box.hi.array() + slack)).all();
  }
  std::optional<double> sagitta(const Vec& a, const Vec& b) const;
  std::optional<CurvePoint> exit_point(const Vec& p, const Vec& q) const;
  bool step_over(double distance, double margin, double mu_ref);
  void record_singular(const Vec& point, bool resolved);

  MarchContext& c_;
  const CurveSystem& sys_;
  double tol_, h_max_, h_min_, cos_turn_;
  // Walk state.
  Walk w_;
  CurvePoint p_;
  mutable double last_midpoint_mu_ = 0.0;  // |grad f x grad g| at the last sagitta() midpoint
  Vec t_ = Vec::Zero(), kappa_ = Vec::Zero();  // tangent and curvature vector (from the last step)
};

// Chord height of a -> b: the distance from the chord's midpoint to the curve, measured on the
// plane normal to the chord (for an arc of curvature kappa, kappa |b - a|^2 / 8).
std::optional<double> Walker::sagitta(const Vec& a, const Vec& b) const {
  const Vec chord = b - a;
  const double length = chord.norm();
  if (!(length > 0.0)) return 0.0;
  const Vec dir = chord / length, mid = 0.5 * (a + b);
  const auto m = sys_.project_on_plane(mid, dir, 0.5 * length);
  if (!m) return std::nullopt;
  // The curve must cross the midplane along the chord, not across it (another branch).
  if (m->tangent(dir).dot(dir) < cos_turn_) return std::nullopt;
  last_midpoint_mu_ = m->mu();
  return (m->p - mid).norm();
}

// Where the curve leaves the box between p (inside) and q (outside): Newton on f = g = 0 and
// the face plane, started where the chord crosses the face.
std::optional<CurvePoint> Walker::exit_point(const Vec& p, const Vec& q) const {
  double lambda = 1.0;
  int face = -1;
  double bound = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double d = q[i] - p[i];
    if (q[i] > c_.box.hi[i] && d > 0.0 && (c_.box.hi[i] - p[i]) / d < lambda) {
      lambda = (c_.box.hi[i] - p[i]) / d, face = i, bound = c_.box.hi[i];
    }
    if (q[i] < c_.box.lo[i] && d < 0.0 && (c_.box.lo[i] - p[i]) / d < lambda) {
      lambda = (c_.box.lo[i] - p[i]) / d, face = i, bound = c_.box.lo[i];
    }
  }
  if (face < 0) return std::nullopt;
  Vec b0 = p + std::max(lambda, 0.0) * (q - p);
  b0[face] = bound;
  const auto b = sys_.project_on_plane(b0, Vec::Unit(face), 0.5 * (q - p).norm());
  if (!b || !inside(b->p)) return std::nullopt;
  return b;
}

void Walker::record_singular(const Vec& point, bool resolved) {
  for (SingularPoint& s : c_.singular_points) {
    if ((s.point - point).norm() <= 10.0 * tol_) {
      ++s.passes;
      s.resolved = s.resolved && resolved;
      return;
    }
  }
  c_.singular_points.push_back({.point = point, .passes = 1, .resolved = resolved});
}

// A singular point lies about `distance` ahead along t: land `margin` beyond it with a
// second-order predictor, correct on the plane normal to t, and accept only if the corrected
// point stays near the prediction and its tangent continues the incoming one (the same smooth
// branch, not the one crossing it). The crossing point itself joins the polyline when Newton
// puts it on the curve.
bool Walker::step_over(double distance, double margin, double mu_ref) {
  // Only a true singular point is stepped over: Gauss-Newton must find a curve point near the
  // prediction where grad f x grad g vanishes. Two branches that merely come close (surfaces
  // nearly tangent) have no such point, and are walked with ordinary, shorter steps.
  const Vec s0 = p_.p + distance * t_ + 0.5 * distance * distance * kappa_;
  const auto crossing = sys_.locate_singular(s0, 4.0 * tol_ + 0.5 * distance);
  if (!crossing || crossing->mu() > kSingularMu * mu_ref) return false;
  for (const double factor : {1.0, 0.5, 0.25, 2.0}) {
    if (c_.steps >= c_.max_steps) return false;
    ++c_.steps;
    const double m = factor * margin, length = distance + m;
    const Vec q0 = p_.p + length * t_ + 0.5 * length * length * kappa_;
    const Vec t_expected = (t_ + length * kappa_).normalized();
    const auto q = sys_.project_on_plane(q0, t_expected, 0.25 * m);
    if (!q || !inside(q->p)) continue;
    const Vec tq = q->tangent(t_expected);
    if (tq.dot(t_expected) < std::cos(0.35)) continue;
    // The crossing joins the polyline when it lies between p and q (it is on the curve).
    const Vec& s = crossing->p;
    const bool s_between = (s - p_.p).dot(t_) > 1e-6 * tol_ && (q->p - s).dot(tq) > 1e-6 * tol_;
    // Chord heights as for any step (the crossing point splits the chord in two).
    bool chords_ok = true;
    const std::vector<Vec> chain = s_between ? std::vector<Vec>{p_.p, s, q->p} : std::vector<Vec>{p_.p, q->p};
    for (std::size_t k = 0; k + 1 < chain.size() && chords_ok; ++k) {
      const auto height = sagitta(chain[k], chain[k + 1]);
      chords_ok = height && *height <= tol_;
    }
    if (!chords_ok) continue;
    record_singular(s, true);
    if (s_between) w_.points.push_back(s);
    kappa_ = Vec::Zero();  // the curvature estimate does not carry across the crossing
    p_ = *q;
    t_ = tq;
    w_.points.push_back(q->p);
    return true;
  }
  return false;
}

Walk Walker::run(const CurvePoint& start, const Vec& direction, bool allow_close) {
  w_ = Walk{};
  w_.points.push_back(start.p);
  p_ = start;
  t_ = start.tangent(direction);
  kappa_ = Vec::Zero();
  if (t_.isZero()) {
    record_singular(start.p, false);
    w_.end = WalkEnd::Singular;
    return w_;
  }
  const Vec t_start = t_;
  double h = std::min(h_max_, std::sqrt(tol_ * c_.diagonal));
  double mu_ref = p_.mu(), mu_prev = -1.0, chord_prev = 0.0, last_good = h;
  bool skip_singular = false;
  bool stretched = false;  // the step from p_ was lengthened once already

  while (true) {
    if (c_.steps >= c_.max_steps) {
      w_.end = WalkEnd::Budget;
      return w_;
    }
    ++c_.steps;
    // Closing the loop: the start lies within one step ahead, in the same direction.
    if (allow_close && w_.points.size() >= 3) {
      const Vec v = start.p - p_.p;
      const double dist = v.norm();
      if (dist <= 1.05 * h && v.dot(t_) > 0.5 * dist && t_.dot(t_start) > 0.5) {
        const auto s = sagitta(p_.p, start.p);
        if (s && *s <= tol_) {
          w_.end = WalkEnd::Closed;
          return w_;
        }
        h = 0.5 * dist;
      }
    }
    // A singular point ahead: |grad f x grad g| falls linearly towards it; extrapolate its zero
    // and confirm that it nearly vanishes there (a smooth minimum of it does not).
    if (mu_prev > 0.0 && chord_prev > 0.0 && p_.mu() < kSingularDrop * mu_ref && !skip_singular) {
      const double slope = (p_.mu() - mu_prev) / chord_prev;
      const double d = slope < 0.0 ? p_.mu() / -slope : 0.0;
      if (slope < 0.0 && d <= 1.5 * h &&
          sys_.eval(p_.p + d * t_ + 0.5 * d * d * kappa_).mu() < kSingularConfirm * p_.mu()) {
        if (d > h) {
          h = 0.5 * d;  // approach it first, so the chord up to it is not too long
        } else if (step_over(d, h, mu_ref)) {
          mu_prev = -1.0;
          mu_ref = std::max(mu_ref, p_.mu());
          continue;
        } else {
          skip_singular = true;  // try ordinary steps; stuck() decides if it cannot be passed
        }
      }
    }
    // Predictor (second order once the curvature is known) and corrector on the normal plane.
    const Vec q0 = p_.p + h * t_ + 0.5 * h * h * kappa_;
    // The corrector may move at most 6 tol (a first-order prediction misses by 4 tol at the
    // aimed chord height; the second-order one by far less): further away lies another branch.
    const auto q = sys_.project_on_plane(q0, t_, std::min(0.5 * h, 6.0 * tol_));
    auto shrink = [&]() {
      h *= 0.5;
      return h >= h_min_;
    };
    auto stuck = [&]() {
      // The corrector keeps failing: an undetected singular point right ahead. Step over it.
      if (step_over(0.0, last_good, mu_ref)) {
        h = last_good;
        mu_prev = -1.0;
        return false;
      }
      record_singular(p_.p, false);
      w_.end = WalkEnd::Singular;
      return true;
    };
    if (!q) {
      if (!shrink() && stuck()) return w_;
      continue;
    }
    if (!inside(q->p)) {
      if (const auto b = exit_point(p_.p, q->p)) {
        const auto s = sagitta(p_.p, b->p);
        if (s && *s <= tol_) {
          w_.points.push_back(b->p);
          w_.end = WalkEnd::Boundary;
          return w_;
        }
      }
      if (!shrink()) {
        w_.end = WalkEnd::Boundary;  // cannot resolve the exit: end here, inside the box
        return w_;
      }
      continue;
    }
    const Vec chord = q->p - p_.p;
    const double length = chord.norm();
    const Vec dir = chord / length;
    const Vec tq = q->tangent(dir);
    // No jumping between branches: the chord must follow both end tangents.
    if (!(length > 0.0) || tq.isZero() || dir.dot(t_) < cos_turn_ || dir.dot(tq) < cos_turn_) {
      if (!shrink() && stuck()) return w_;
      continue;
    }
    const auto s = sagitta(p_.p, q->p);
    if (!s) {
      if (!shrink() && stuck()) return w_;
      continue;
    }
    if (*s > tol_) {  // chord too high: shorten to the height aimed at (kappa h^2 / 8)
      h *= std::clamp(std::sqrt(kAim * tol_ / *s), 0.2, 0.9);  // h along t, not the chord: it shrinks
      if (h < h_min_ && stuck()) return w_;
      continue;
    }
    // |grad f x grad g| dipping at the midpoint: the chord spans a feature smaller than the step,
    // such as two branches nearly touching (nearly tangent surfaces), where the chord along
    // their common asymptote stays within tol of the curve but jumps from one to the other.
    if (last_midpoint_mu_ < kMidpointDip * 0.5 * (p_.mu() + q->mu())) {
      if (!shrink() && stuck()) return w_;
      continue;
    }
    // Passing the start of a loop: close it there instead.
    if (allow_close && w_.points.size() >= 3 && t_start.dot(dir) > 0.5) {
      const Vec v = start.p - p_.p;
      const double along = v.dot(dir);
      if (along > 0.0 && along <= length && (v - along * dir).norm() <= 2.0 * tol_) {
        w_.end = WalkEnd::Closed;
        return w_;
      }
    }
    // A chord well below the aimed height (the curvature falls ahead, or the last estimate was
    // short): try once more from p with the step lengthened to the aimed height, so that fewer
    // points are spent (q is found again if the longer chord is too high). Not near a singular
    // point (|grad f x grad g| falling), which is approached with short steps and stepped over.
    if (*s < kStretch * tol_ && !stretched && h < h_max_ && std::min(p_.mu(), q->mu()) >= kSingularDrop * mu_ref) {
      const double longer = std::min(h_max_, h * std::clamp(std::sqrt(kAim * tol_ / std::max(*s, 1e-300)), 1.0, 2.0));
      // nor where |grad f x grad g|, extrapolated along the chord, would vanish within the longer step
      const double slope = (q->mu() - p_.mu()) / length;
      if (!(slope < 0.0 && q->mu() / -slope < 2.0 * longer)) {
        stretched = true;
        h = longer;
        continue;
      }
    }
    stretched = false;
    kappa_ = (tq - t_) / length;
    skip_singular = false;
    mu_prev = p_.mu();
    chord_prev = length;
    p_ = *q;
    t_ = tq;
    w_.points.push_back(p_.p);
    mu_ref = std::max(mu_ref, p_.mu());
    last_good = length;
    h = std::min(h_max_, h * std::clamp(std::sqrt(kAim * tol_ / std::max(*s, 1e-300)), 0.3, 2.0));
  }
}

}  // namespace

Walk walk(MarchContext& context, const CurvePoint& start, const Vec& direction, bool allow_close) {
  Walker walker(context);
  return walker.run(start, direction, allow_close);
}

}  // namespace sculpt::implicit::detail
