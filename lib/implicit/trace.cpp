#include "implicit/trace.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "implicit/detail/coverage.hpp"
#include "implicit/detail/curve_system.hpp"
#include "implicit/detail/march.hpp"

namespace sculpt::implicit {
namespace {

using Vec = Eigen::Vector3d;
using detail::CurvePoint;
using detail::Walk;
using detail::WalkEnd;

constexpr int kLeafDivisions = 32;  // start cells: 1/32 of the box's longest side
constexpr int kExtraLevels = 3;     // further splits of a cell whose centre does not project nearby

void validate(const TraceOptions& o) {
  if (!o.box.lo.allFinite() || !o.box.hi.allFinite())
    throw InvalidInput("trace: the box corners must be finite");
  if (!(o.box.lo.array() < o.box.hi.array()).all())
    throw InvalidInput("trace: the box is empty (need lo < hi in every coordinate)");
  const double diagonal = (o.box.hi - o.box.lo).norm();
  if (!std::isfinite(o.tolerance) || !(o.tolerance > 0.0))
    throw InvalidInput("trace: tolerance must be a finite value > 0");
  if (o.tolerance < 1e-9 * diagonal)
    throw InvalidInput("trace: tolerance " + std::to_string(o.tolerance) + " is below 1e-9 times the box diagonal");
  if (o.tolerance > diagonal) throw InvalidInput("trace: tolerance is larger than the box");
  if (o.max_steps <= 0) throw InvalidInput("trace: max_steps must be > 0");
}

struct StartCell {
  Box box;
  int level = 0;  // 0 = the whole box; kLeafLevel = start-cell size; more = extra splits
};

// Start points (sec. 5.1, without user seeds): cells of a subdivision of the box in which
// interval bounds allow f = 0 and g = 0; the centre of each is projected onto the curve.
class Tracer {
 public:
  Tracer(const Expression& f, const Expression& g, const TraceOptions& options)
      : f_(f), g_(g), options_(options), diagonal_((options.box.hi - options.box.lo).norm()),
        system_(f, g, 1e-12 * diagonal_ * 0.25),
        context_{.system = system_, .box = options.box, .tolerance = options.tolerance, .diagonal = diagonal_,
                 .max_steps = options.max_steps, .steps = 0, .singular_points = {}},
        leaf_((options.box.hi - options.box.lo).maxCoeff() / kLeafDivisions),
        coverage_(options.box.lo, std::max(leaf_, 4.0 * options.tolerance)) {
    leaf_level_ = static_cast<int>(std::lround(std::log2(kLeafDivisions)));
  }

  TraceResult run();

 private:
  [[nodiscard]] bool may_hold_curve(const Box& b) const {
    return f_.bounds(b).range.contains(0.0) && g_.bounds(b).range.contains(0.0);
  }
  [[nodiscard]] bool strictly_inside(const Vec& p) const {
    return (p.array() > options_.box.lo.array()).all() && (p.array() < options_.box.hi.array()).all();
  }
  void trace_from(const CurvePoint& seed);

  const Expression& f_;
  const Expression& g_;
  TraceOptions options_;
  double diagonal_;
  detail::CurveSystem system_;
  detail::MarchContext context_;
  double leaf_;
  int leaf_level_ = 6;
  detail::Coverage coverage_;
  TraceResult result_;
};

void Tracer::trace_from(const CurvePoint& seed) {
  const Vec direction = seed.cross;
  Walk forward = detail::walk(context_, seed, direction, true);
  TracedCurve curve;
  if (forward.end == WalkEnd::Closed) {
    curve.points = std::move(forward.points);
    curve.closed = true;
  } else {
    const Walk backward = detail::walk(context_, seed, -direction, false);
    curve.points.assign(backward.points.rbegin(), backward.points.rend() - 1);  // without the seed twice
    curve.points.insert(curve.points.end(), forward.points.begin(), forward.points.end());
    if (forward.end == WalkEnd::Budget || backward.end == WalkEnd::Budget) result_.budget_exhausted = true;
  }
  if (forward.end == WalkEnd::Budget) result_.budget_exhausted = true;
  Eigen::AlignedBox3d extent;
  for (const Vec& p : curve.points) extent.extend(p);
  if (curve.points.size() < 2 || extent.diagonal().norm() <= options_.tolerance) {
    // Nothing to walk: an isolated point of the curve, where f = 0 and g = 0 touch (a sphere and
    // a tangent plane). Report it once, with no passes, and cover it.
    coverage_.add_polyline({seed.p, seed.p}, false);
    for (SingularPoint& s : context_.singular_points) {
      if ((s.point - seed.p).norm() <= 10.0 * options_.tolerance) {
        s = {.point = seed.p, .passes = 0, .resolved = true};
        return;
      }
    }
    context_.singular_points.push_back({.point = seed.p, .passes = 0, .resolved = true});
    return;
  }
  coverage_.add_polyline(curve.points, curve.closed);
  result_.curves.push_back(std::move(curve));
}

TraceResult Tracer::run() {
  const double cover_radius = 2.0 * options_.tolerance;
  std::vector<StartCell> stack{{options_.box, 0}};  // explicit stack: no recursion
  while (!stack.empty() && !result_.budget_exhausted) {
    const StartCell cell = stack.back();
    stack.pop_back();
    if (!may_hold_curve(cell.box)) continue;
    const Vec centre = 0.5 * (cell.box.lo + cell.box.hi);
    const double size = (cell.box.hi - cell.box.lo).norm();
    bool split = cell.level < leaf_level_;
    if (!split) {
      const auto p = system_.project(centre, 4.0 * size);
      const bool near = p && (p->p - centre).norm() <= size && strictly_inside(p->p);
      if (near && !coverage_.covers(p->p, cover_radius)) {
        if (p->mu() > 0.0) trace_from(*p);
      } else if (cell.level < leaf_level_ + kExtraLevels && (!near || cell.level == leaf_level_)) {
        // Far or failed projection: look closer. Covered: look once more at half the size,
        // in case a second branch runs through the same cell.
        split = true;
      }
    }
    if (!split) continue;
    for (int octant = 7; octant >= 0; --octant) {
      StartCell child{cell.box, cell.level + 1};
      for (int axis = 0; axis < 3; ++axis) {
        if (octant & (1 << axis))
          child.box.lo[axis] = centre[axis];
        else
          child.box.hi[axis] = centre[axis];
      }
      stack.push_back(child);
    }
  }
  if (context_.steps >= options_.max_steps) result_.budget_exhausted = true;
  result_.singular_points = context_.singular_points;
  result_.steps = context_.steps;
  return std::move(result_);
}

}  // namespace

TraceResult trace(const Expression& f, const Expression& g, const TraceOptions& options) {
  validate(options);
  Tracer tracer(f, g, options);
  return tracer.run();
}

}  // namespace sculpt::implicit
