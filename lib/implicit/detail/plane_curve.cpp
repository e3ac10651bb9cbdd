#include "implicit/detail/plane_curve.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

namespace sculpt::implicit::detail {
namespace {

using Vec = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

constexpr double kPlaneMaxTurn = 0.6;      // radians of tangent turn allowed across one chord (as march.cpp)
constexpr double kPlaneAim = 0.9;          // aim at a chord height of 0.9 tol
constexpr double kPlaneMidpointDip = 0.6;  // in-plane |grad f| at a chord's midpoint below 0.6 of its ends' mean

Vec2 perp(const Vec2& g) { return {-g.y(), g.x()}; }

// f on the plane at one point: value, in-plane gradient, and whether it is on the curve.
struct Sample {
  Vec2 uv = Vec2::Zero();
  Vec p = Vec::Zero();
  double f = 0.0;
  Vec2 grad = Vec2::Zero();  // (grad f . e1, grad f . e2)
  bool on_curve = false;

  // Unit tangent agreeing with `direction`; zero where the in-plane gradient vanishes.
  [[nodiscard]] Vec2 tangent(const Vec2& direction) const {
    const double n = grad.norm();
    if (!(n > 0.0)) return Vec2::Zero();
    const Vec2 t = perp(grad) / n;
    return t.dot(direction) < 0.0 ? Vec2(-t) : t;
  }
};

class PlaneWalker {
 public:
  PlaneWalker(const Expression& f, const PlaneFrame& plane, const PlaneCurveOptions& options)
      : f_(f), plane_(plane), o_(options), cos_turn_(std::cos(kPlaneMaxTurn)) {}

  PlaneCurve run(const Vec& from, const Vec& to);

 private:
  [[nodiscard]] Sample eval_point(const Vec& p, const Vec2& uv) const {
    const ValueGradient vg = f_.value_gradient(p);
    Sample s;
    s.uv = uv;
    s.p = p;
    s.f = vg.value;
    s.grad = {vg.gradient.dot(plane_.e1), vg.gradient.dot(plane_.e2)};
    s.on_curve = std::abs(vg.value) <= o_.residual_target * vg.gradient.norm();
    return s;
  }
  [[nodiscard]] Sample eval(const Vec2& uv) const { return eval_point(plane_.at(uv), uv); }
  [[nodiscard]] bool inside(const Vec& p) const {
    return ((p.array() >= o_.box.lo.array()) && (p.array() <= o_.box.hi.array())).all();
  }
  // Newton on f = 0 and line . (q - start) = 0 (the line through start normal to `line`).
  [[nodiscard]] std::optional<Sample> correct(const Vec2& start, const Vec2& line, double max_move) const;
  // Chord height of a -> b, measured on the line normal to the chord through its midpoint.
  [[nodiscard]] std::optional<double> sagitta(const Vec2& a, const Vec2& b) const;

  const Expression& f_;
  const PlaneFrame& plane_;
  PlaneCurveOptions o_;
  double cos_turn_;
  mutable double last_midpoint_grad_ = 0.0;
};

std::optional<Sample> PlaneWalker::correct(const Vec2& start, const Vec2& line, double max_move) const {
  Vec2 q = start;
  for (int k = 0; k <= 16; ++k) {
    const Sample s = eval(q);
    const double along = line.dot(q - start);
    if (s.on_curve && std::abs(along) <= 1e-9 * max_move) return s;
    if (k == 16) break;
    Eigen::Matrix2d A;
    A << s.grad.x(), s.grad.y(), line.x(), line.y();
    if (!(std::abs(A.determinant()) > 1e-10 * s.grad.norm() * line.norm())) return std::nullopt;
    const Vec2 delta = A.partialPivLu().solve(Vec2(-s.f, -along));
    if (!delta.allFinite()) return std::nullopt;
    q += delta;
    if ((q - start).norm() > max_move) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<double> PlaneWalker::sagitta(const Vec2& a, const Vec2& b) const {
  const Vec2 chord = b - a;
  const double length = chord.norm();
  if (!(length > 0.0)) return 0.0;
  const Vec2 dir = chord / length, mid = 0.5 * (a + b);
  const auto m = correct(mid, dir, 0.5 * length);
  if (!m) return std::nullopt;
  // The curve must cross the midline along the chord, not across it (another branch).
  if (m->tangent(dir).dot(dir) < cos_turn_) return std::nullopt;
  last_midpoint_grad_ = m->grad.norm();
  return (m->uv - mid).norm();
}

PlaneCurve PlaneWalker::run(const Vec& from, const Vec& to) {
  PlaneCurve out;
  out.points.push_back(from);
  out.last = from;
  const Vec2 uv_from = plane_.coords(from), uv_to = plane_.coords(to);
  const Sample start = eval_point(from, uv_from);
  const Sample target = eval_point(to, uv_to);
  Sample p = start;
  Vec2 t = p.tangent(uv_to - uv_from);
  Vec2 kappa = Vec2::Zero();
  if (t.isZero()) {
    out.end = PlaneCurveEnd::Stuck;
    return out;
  }
  const double span = (uv_to - uv_from).norm();
  const double tol = o_.tolerance;
  const double h_max = o_.max_step;
  const double h_min = std::max(1e-4 * tol, 1e-10 * span);
  double h = std::min(h_max, std::sqrt(tol * span));

  // Ends the walk at `to` after p when the chord p -> to is within tol and follows the curve.
  auto arrive = [&]() {
    const Vec2 chord = uv_to - p.uv;
    const double length = chord.norm();
    if (!(length > 0.0)) return true;
    const Vec2 dir = chord / length;
    if (p.tangent(dir).dot(dir) < cos_turn_ || target.tangent(dir).dot(dir) < cos_turn_) return false;
    const auto s = sagitta(p.uv, uv_to);
    return s && *s <= tol;
  };
  auto finish = [&](PlaneCurveEnd end) {
    out.end = end;
    if (end == PlaneCurveEnd::Reached) out.points.push_back(to);
    out.last = out.points.back();
    return out;
  };

  while (true) {
    if (out.steps >= o_.max_steps) return finish(PlaneCurveEnd::Budget);
    ++out.steps;
    // The target lies within one step ahead: try the chord to it.
    const Vec2 v = uv_to - p.uv;
    const double dist = v.norm();
    if (dist <= 1.05 * h && v.dot(t) > 0.5 * dist) {
      if (arrive()) return finish(PlaneCurveEnd::Reached);
      h = 0.5 * dist;
      if (h < h_min) return finish(PlaneCurveEnd::Stuck);
    }
    const Vec2 q0 = p.uv + h * t + 0.5 * h * h * kappa;
    const auto q = correct(q0, t, std::min(0.5 * h, 6.0 * tol));
    auto shrink = [&]() {
      h *= 0.5;
      return h >= h_min;
    };
    if (!q) {
      if (!shrink()) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    if (!inside(q->p)) {
      if (h > 8.0 * h_min && shrink()) continue;  // leave the box only with a short, certain step
      out.points.push_back(q->p);
      return finish(PlaneCurveEnd::LeftBox);
    }
    const Vec2 chord = q->uv - p.uv;
    const double length = chord.norm();
    if (!(length > 0.0)) {
      if (!shrink()) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    const Vec2 dir = chord / length;
    const Vec2 tq = q->tangent(dir);
    // No jumping between branches: the chord must follow both end tangents.
    if (tq.isZero() || dir.dot(t) < cos_turn_ || dir.dot(tq) < cos_turn_) {
      if (!shrink()) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    const auto s = sagitta(p.uv, q->uv);
    if (!s) {
      if (!shrink()) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    if (*s > tol) {
      h *= std::clamp(std::sqrt(kPlaneAim * tol / *s), 0.2, 0.9);
      if (h < h_min) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    // The in-plane gradient dipping at the midpoint: the chord spans a feature smaller than the
    // step (two branches nearly touching where the plane is nearly tangent to the surface).
    if (last_midpoint_grad_ < kPlaneMidpointDip * 0.5 * (p.grad.norm() + q->grad.norm())) {
      if (!shrink()) return finish(PlaneCurveEnd::Stuck);
      continue;
    }
    // The chord passes the target (within 2 tol): end there instead.
    {
      const Vec2 w = uv_to - p.uv;
      const double along = w.dot(dir);
      if (along > 0.0 && along <= length && (w - along * dir).norm() <= 2.0 * tol && arrive())
        return finish(PlaneCurveEnd::Reached);
    }
    // The chord passes the start again: a closed curve that does not run through the target.
    if (out.points.size() >= 3) {
      const Vec2 w = uv_from - p.uv;
      const double along = w.dot(dir);
      if (along > 0.0 && along <= length && (w - along * dir).norm() <= 2.0 * tol) {
        out.points.push_back(q->p);
        return finish(PlaneCurveEnd::Closed);
      }
    }
    kappa = (tq - t) / length;
    p = *q;
    t = tq;
    out.points.push_back(p.p);
    h = std::min(h_max, h * std::clamp(std::sqrt(kPlaneAim * tol / std::max(*s, 1e-300)), 0.3, 2.0));
  }
}

}  // namespace

PlaneFrame PlaneFrame::make(const Vec& normal, double offset) {
  PlaneFrame frame;
  frame.normal = normal;
  frame.offset = offset;
  frame.origin = offset * normal;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    if (normal[a] == 0.0 && normal[b] == 0.0) {
      // Normal to a coordinate axis: origin has exact zeros in the other coordinates, and
      // o + u e1 + v e2 keeps coordinate `axis` equal to origin[axis] exactly.
      frame.e1 = Vec::Unit(a);
      frame.e2 = Vec::Unit(b);
      return frame;
    }
  }
  // Any orthonormal pair: e1 along the coordinate axis least aligned with the normal, projected.
  int least = 0;
  for (int axis = 1; axis < 3; ++axis)
    if (std::abs(normal[axis]) < std::abs(normal[least])) least = axis;
  frame.e1 = (Vec::Unit(least) - normal[least] * normal).normalized();
  frame.e2 = normal.cross(frame.e1);
  return frame;
}

PlaneCurve trace_on_plane(const Expression& f, const PlaneFrame& plane, const Vec& from, const Vec& to,
                          const PlaneCurveOptions& options) {
  PlaneWalker walker(f, plane, options);
  return walker.run(from, to);
}

}  // namespace sculpt::implicit::detail
