#pragma once
/// \file trace.hpp
/// Tracing the space curve f = g = 0 inside a box (Ihm & Naylor 1990, sec. 5.1: "the curve
/// segment is traced using a space curve tracing algorithm, generating a digitized space curve";
/// Appendix B gives the test curves of Figs. 3-8 as such pairs f, g).
///
/// Method: start points without user seeds, from a subdivision of the box by interval bounds of
/// f and g, projected onto the curve by minimum-norm Newton; then predictor-corrector marching
/// along t = grad f x grad g with a Newton corrector, the step chosen from the curvature so that
/// every chord stays within tol of the curve (about sqrt(8 tol / kappa)). Singular points, where
/// grad f x grad g vanishes (the node of the sextic of Fig. 8, the self-crossing of Viviani's
/// curve), are detected, reported and stepped over along the incoming tangent, so that each
/// smooth branch through them is traced once.

#include <Eigen/Core>
#include <vector>

#include "implicit/expression.hpp"

namespace sculpt::implicit {

struct TraceOptions {
  Box box;                  ///< the curve is traced inside this box (lo < hi in every coordinate)
  double tolerance = 1e-3;  ///< chord height: every chord lies within this distance of the curve
  long max_steps = 200'000;  ///< budget of marching steps (tried or accepted); about 3 s at most
};

/// One traced component: points on the curve, in order. A closed loop does not repeat its
/// first point; an open piece starts and ends on the box boundary (or at a singular point that
/// could not be passed, see TraceResult::unresolved).
struct TracedCurve {
  std::vector<Eigen::Vector3d> points;
  bool closed = false;
};

/// A point where grad f x grad g vanishes (the curve crosses itself or f, g are tangent).
struct SingularPoint {
  /// Located by Gauss-Newton on f = g = 0, grad f x grad g = 0 where that converges on the
  /// curve, else a curve point within about the tolerance of it.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int passes = 0;         ///< how many times a traced branch went through it; 0: an isolated
                          ///< point of the curve (f = 0 and g = 0 touch there), no curve output
  bool resolved = true;   ///< false: a branch stopped here (it could not be stepped over)
};

struct TraceResult {
  std::vector<TracedCurve> curves;
  std::vector<SingularPoint> singular_points;
  long steps = 0;                 ///< marching steps used
  bool budget_exhausted = false;  ///< max_steps ran out: curves may be incomplete
};

/// Every component of f = g = 0 inside options.box. Every output point p satisfies
/// |f(p)| / |grad f(p)| and |g(p)| / |grad g(p)| <= 1e-12 * (box diagonal).
/// \throw InvalidInput for an empty or non-finite box, tolerance <= 0, tolerance below
///        1e-9 times the box diagonal or above the diagonal, max_steps <= 0.
/// \throw NonFiniteValue if f or g (or a gradient) is not finite at a point the tracer visits.
[[nodiscard]] TraceResult trace(const Expression& f, const Expression& g, const TraceOptions& options);

}  // namespace sculpt::implicit
