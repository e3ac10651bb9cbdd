#include "splines/surface_curves.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/constrained_spline.hpp"

namespace sculpt::splines {
namespace {

using V = Eigen::Vector3d;

void require_finite(const V& v, const char* what) {
  if (!v.allFinite()) throw InvalidInput(std::string(what) + " must be finite");
}

/// A unit vector perpendicular to the unit vector a.
V perpendicular(const V& a) {
  const V c = std::abs(a.x()) < 0.9 ? V::UnitX() : V::UnitY();
  return a.cross(c).normalized();
}

/// The unit vector along v, or `fallback` where v vanishes (a foot point is not unique there).
V direction(const V& v, const V& fallback) {
  const double n = v.norm();
  return n > 0.0 ? V(v / n) : fallback;
}

V unit_axis(const V& axis) {
  require_finite(axis, "the axis");
  if (axis.norm() == 0.0) throw InvalidInput("the axis must not be zero");
  return axis.normalized();
}

// 5-point Gauss-Legendre on [-1, 1].
constexpr std::array<double, 5> kGaussX{0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                        0.9061798459386640};
constexpr std::array<double, 5> kGaussW{0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                        0.2369268850561891, 0.2369268850561891};

/// Sum over the curve's knot spans, each cut into `pieces`, of the 5-point Gauss rule applied to f(t).
template <class F>
double integrate(const BSpline& curve, int pieces, F f) {
  const std::vector<double> br = curve.breaks();
  double sum = 0.0;
  for (std::size_t s = 0; s + 1 < br.size(); ++s)
    for (int k = 0; k < pieces; ++k) {
      const double a = br[s] + (br[s + 1] - br[s]) * k / pieces, b = br[s] + (br[s + 1] - br[s]) * (k + 1) / pieces;
      for (std::size_t g = 0; g < kGaussX.size(); ++g) sum += 0.5 * (b - a) * kGaussW[g] * f(0.5 * (a + b) + 0.5 * (b - a) * kGaussX[g]);
    }
  return sum;
}

/// Largest distance of the curve from the surface, sampled `per_span` times per knot span.
double max_distance_to(const Surface& surface, const BSpline& curve, int per_span) {
  const std::vector<double> br = curve.breaks();
  double worst = 0.0;
  for (std::size_t s = 0; s + 1 < br.size(); ++s)
    for (int k = 0; k <= per_span; ++k) {
      const V c = curve.point(br[s] + (br[s + 1] - br[s]) * k / per_span);
      worst = std::max(worst, (surface.closest_point(c) - c).norm());
    }
  return worst;
}

BSpline to_curve(const std::vector<double>& knots, const Eigen::MatrixXd& X) {
  std::vector<V> controls(static_cast<std::size_t>(X.rows()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) controls[static_cast<std::size_t>(i)] = X.row(i).transpose();
  return BSpline(3, knots, std::move(controls), false, 3);
}

double polygon_energy(const std::vector<V>& p) {
  double e = 0.0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) e += (p[i + 1] - p[i]).squaredNorm();
  return e;
}

double polygon_length(const std::vector<V>& p) {
  double l = 0.0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) l += (p[i + 1] - p[i]).norm();
  return l;
}

/// Tangent steps on one level until no vertex moves more than `stop`; returns the steps taken.
int relax_geodesic(const Surface& surface, std::vector<V>& p, int iterations, double stop, bool& converged) {
  const int N = static_cast<int>(p.size()) - 1;
  const int unknowns = 2 * (N - 1);
  converged = unknowns == 0;
  if (converged) return 0;
  std::vector<Eigen::Matrix<double, 3, 2>> T(static_cast<std::size_t>(N + 1));
  int steps = 0;
  while (steps < iterations) {
    for (int i = 1; i < N; ++i) {
      const V n = surface.normal(p[i]);
      const V a = perpendicular(n);
      T[i].col(0) = a;
      T[i].col(1) = n.cross(a);
    }
    // minimize sum_i |e_i + T_{i+1} a_{i+1} - T_i a_i|^2 over the tangent moves a_i (a_0 = a_N = 0)
    std::vector<Eigen::Triplet<double>> h;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(unknowns);
    auto block = [&](int i, int j, const Eigen::Matrix2d& m) {
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) h.emplace_back(2 * (i - 1) + r, 2 * (j - 1) + c, m(r, c));
    };
    for (int i = 0; i < N; ++i) {
      const V e = p[i + 1] - p[i];
      const bool left = i >= 1, right = i + 1 <= N - 1;
      if (left) {
        block(i, i, Eigen::Matrix2d::Identity());
        b.segment<2>(2 * (i - 1)) += T[i].transpose() * e;
      }
      if (right) {
        block(i + 1, i + 1, Eigen::Matrix2d::Identity());
        b.segment<2>(2 * i) -= T[i + 1].transpose() * e;
      }
      if (left && right) {
        const Eigen::Matrix2d m = -T[i].transpose() * T[i + 1];
        block(i, i + 1, m);
        block(i + 1, i, m.transpose());
      }
    }
    Eigen::SparseMatrix<double> H(unknowns, unknowns);
    H.setFromTriplets(h.begin(), h.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
    if (ldlt.info() != Eigen::Success) throw GeometryError("geodesic: the tangent step system is singular");
    const Eigen::VectorXd a = ldlt.solve(b);
    ++steps;
    const double before = polygon_energy(p);
    double move = 0.0;
    for (int i = 1; i < N; ++i) move = std::max(move, (T[i] * a.segment<2>(2 * (i - 1))).norm());
    if (!std::isfinite(move)) throw GeometryError("geodesic: the tangent step failed");
    std::vector<V> trial(p);
    bool accepted = false;
    for (double s = 1.0; s > 1e-4; s *= 0.5) {
      for (int i = 1; i < N; ++i) trial[i] = surface.closest_point(p[i] + s * (T[i] * a.segment<2>(2 * (i - 1))));
      if (polygon_energy(trial) <= before) {
        accepted = true;
        move *= s;
        break;
      }
    }
    if (!accepted) {  // no decrease along the step: at a minimum to rounding
      converged = true;
      return steps;
    }
    p.swap(trial);
    if (move <= stop) {
      converged = true;
      return steps;
    }
  }
  return steps;
}

}  // namespace

Surface sphere_surface(const Eigen::Vector3d& center, double radius) {
  require_finite(center, "the sphere's centre");
  if (!(radius > 0.0) || !std::isfinite(radius)) throw InvalidInput("the sphere's radius must be positive");
  Surface s;
  s.name = "sphere";
  s.closest_point = [center, radius](const V& p) -> V { return center + radius * direction(p - center, V::UnitX()); };
  s.normal = [center](const V& x) -> V { return direction(x - center, V::UnitX()); };
  return s;
}

Surface cylinder_surface(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius) {
  require_finite(point, "the cylinder's axis point");
  const V a = unit_axis(axis);
  if (!(radius > 0.0) || !std::isfinite(radius)) throw InvalidInput("the cylinder's radius must be positive");
  const V fallback = perpendicular(a);
  Surface s;
  s.name = "cylinder";
  s.closest_point = [point, a, radius, fallback](const V& p) -> V {
    const V v = p - point;
    const V radial = v - v.dot(a) * a;
    return point + v.dot(a) * a + radius * direction(radial, fallback);
  };
  s.normal = [point, a, fallback](const V& x) -> V {
    const V v = x - point;
    return direction(V(v - v.dot(a) * a), fallback);
  };
  return s;
}

Surface torus_surface(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double major, double minor) {
  require_finite(center, "the torus' centre");
  const V a = unit_axis(axis);
  if (!(minor > 0.0) || !(major > minor) || !std::isfinite(major))
    throw InvalidInput("the torus needs 0 < minor radius < major radius");
  const V fallback = perpendicular(a);
  // The centre circle's point nearest to p, then the tube's.
  auto ring = [center, a, major, fallback](const V& p) -> V {
    const V v = p - center;
    return center + major * direction(V(v - v.dot(a) * a), fallback);
  };
  Surface s;
  s.name = "torus";
  s.closest_point = [ring, minor, center](const V& p) -> V {
    const V m = ring(p);
    return m + minor * direction(p - m, direction(m - center, V::UnitX()));
  };
  s.normal = [ring, center](const V& x) -> V {
    const V m = ring(x);
    return direction(x - m, direction(m - center, V::UnitX()));
  };
  return s;
}

Surface implicit_surface(std::function<double(const Eigen::Vector3d&)> value,
                         std::function<Eigen::Vector3d(const Eigen::Vector3d&)> gradient,
                         const ImplicitSurfaceOptions& options) {
  if (!value || !gradient) throw InvalidInput("an implicit surface needs its function and gradient");
  if (options.iterations < 1 || !(options.tolerance > 0.0) || !(options.scale > 0.0))
    throw InvalidInput("implicit surface: iterations, tolerance and scale must be positive");
  Surface s;
  s.name = "implicit";
  const double tol = options.tolerance * options.scale;
  const int iterations = options.iterations;
  // One Newton step onto f = 0 along the gradient; returns |f| / |grad f| before the step.
  auto newton = [value, gradient](V& x) -> double {
    const V g = gradient(x);
    const double gg = g.squaredNorm();
    const double f = value(x);
    if (!(gg > 0.0) || !std::isfinite(gg) || !std::isfinite(f))
      throw GeometryError("implicit surface: the gradient vanishes or is not finite near the point");
    x -= (f / gg) * g;
    return std::abs(f) / std::sqrt(gg);
  };
  s.closest_point = [value, gradient, newton, tol, iterations](const V& p) -> V {
    require_finite(p, "the point");
    V x = p;
    for (int k = 0; k < iterations; ++k) {
      const double off = newton(x);
      const V n = gradient(x).normalized();
      const V d = p - x;
      const V t = d - d.dot(n) * n;  // tangential part: zero at the foot point
      if (t.norm() <= tol && off <= tol) break;
      x += t;
    }
    for (int k = 0; k < iterations; ++k)
      if (newton(x) <= tol) break;
    const V g = gradient(x);
    if (!(std::abs(value(x)) <= 1e3 * tol * g.norm()))
      throw GeometryError("implicit surface: the projection onto f = 0 does not converge from this point");
    return x;
  };
  s.normal = [gradient](const V& x) -> V {
    const V g = gradient(x);
    if (!(g.norm() > 0.0) || !g.allFinite()) throw GeometryError("implicit surface: the gradient vanishes on the surface");
    return g.normalized();
  };
  return s;
}

double bending_energy(const BSpline& curve) {
  return integrate(curve, 1, [&](double t) { return curve.derivatives(t, 2)[2].squaredNorm(); });
}

double curve_length(const BSpline& curve) {
  return integrate(curve, 2, [&](double t) { return curve.derivatives(t, 1)[1].norm(); });
}

GeodesicResult geodesic(const Surface& surface, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                        const GeodesicOptions& options) {
  require_finite(p, "geodesic: p");
  require_finite(q, "geodesic: q");
  if (options.segments < 2) throw InvalidInput("geodesic: at least 2 segments");
  if (options.iterations < 1 || !(options.tolerance > 0.0)) throw InvalidInput("geodesic: iterations and tolerance must be positive");
  const V a = surface.closest_point(p), b = surface.closest_point(q);
  if ((a - b).norm() == 0.0) throw InvalidInput("geodesic: p and q are the same point of the surface");
  // Levels: segments, halved while even and above 8, run coarse to fine.
  std::vector<int> levels{options.segments};
  while (levels.back() % 2 == 0 && levels.back() > 8) levels.push_back(levels.back() / 2);
  std::reverse(levels.begin(), levels.end());
  GeodesicResult result{.curve = BSpline::clamped(1, {a, b}), .polygon = {}};
  std::vector<V>& poly = result.polygon;
  const int n0 = levels.front();
  // The straight segment projected. Where it passes through a symmetry centre (antipodal points
  // of a sphere) the projections collapse onto p and q (one edge carries the whole length) and
  // the tangent steps cannot separate them: then the segment is bulged by 1e-3 of its length to
  // one side first (only then: the bulge costs steps near conjugate points).
  auto start = [&](double bulge) {
    const V side = perpendicular((b - a).normalized()) * (bulge * (b - a).norm());
    poly.clear();
    for (int i = 0; i <= n0; ++i)
      poly.push_back(i == 0    ? a
                     : i == n0 ? b
                               : surface.closest_point(a + (b - a) * (double(i) / n0) +
                                                       std::sin(std::numbers::pi * i / n0) * side));
    double longest = 0.0;
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) longest = std::max(longest, (poly[i + 1] - poly[i]).norm());
    return longest <= 4.0 * polygon_length(poly) / n0;
  };
  if (!start(0.0)) start(1e-3);
  result.converged = true;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    if (level > 0) {  // midpoints projected
      std::vector<V> finer{poly.front()};
      for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
        finer.push_back(surface.closest_point(0.5 * (poly[i] + poly[i + 1])));
        finer.push_back(poly[i + 1]);
      }
      poly.swap(finer);
    }
    bool converged = false;
    const double stop = options.tolerance * std::max(polygon_length(poly), (b - a).norm());
    result.iterations += relax_geodesic(surface, poly, options.iterations, stop, converged);
    if (level + 1 == levels.size()) result.converged = converged;
  }
  result.polygon_length = polygon_length(poly);
  // The constant-speed cubic through the vertices at i / N, with end tangents in the tangent planes.
  const int N = static_cast<int>(poly.size()) - 1;
  std::vector<double> params(static_cast<std::size_t>(N + 1));
  for (int i = 0; i <= N; ++i) params[i] = double(i) / N;
  const std::vector<double> knots = detail::refined_knots(params, 1);
  detail::ConstrainedSpline spline(knots, 3);
  spline.add_bending(1.0);
  for (int i = 0; i <= N; ++i) spline.add_constraint(params[i], poly[i]);
  auto end_tangent = [&](const V& at, const V& chord) {
    const V n = surface.normal(at);
    return V(result.polygon_length * direction(V(chord - chord.dot(n) * n), chord.normalized()));
  };
  spline.add_constraint(0.0, end_tangent(poly.front(), poly[1] - poly[0]), 1);
  spline.add_constraint(1.0, end_tangent(poly.back(), poly[N] - poly[N - 1]), 1);
  result.curve = to_curve(knots, spline.solve());
  result.length = curve_length(result.curve);
  result.max_distance = max_distance_to(surface, result.curve, 16);
  return result;
}

namespace {

/// One run of the active curve with a fixed number of splits per span.
SurfaceSplineResult surface_spline_run(const Surface& surface, const std::vector<V>& on,
                                       const SurfaceSplineOptions& options) {
  // Chord-length parameters: the parameter is close to arc length, so integral |c''|^2 is close to
  // the geometric bending energy integral kappa^2 ds.
  std::vector<double> u{0.0};
  for (std::size_t j = 1; j < on.size(); ++j) {
    const double d = (on[j] - on[j - 1]).norm();
    if (d == 0.0) throw InvalidInput("surface_spline: two consecutive points coincide (on the surface)");
    u.push_back(u.back() + d);
  }
  const double U = u.back();
  const std::vector<double> knots = detail::refined_knots(u, options.splits);
  detail::ConstrainedSpline spline(knots, 3);
  for (std::size_t j = 0; j < on.size(); ++j) spline.add_constraint(u[j], on[j]);
  spline.add_bending(1.0);
  Eigen::MatrixXd X = spline.solve();  // the natural cubic spline (the refined space contains it)
  SurfaceSplineResult result{.curve = to_curve(knots, X), .start = to_curve(knots, X), .parameters = u, .max_distance = 0.0, .bending = 0.0, .iterations = 0, .splits = 0, .converged = false};
  // Sample parameters: `samples` per segment at the segment's midpoints of equal parts.
  std::vector<double> ts;
  for (std::size_t s = 3; s + 4 < knots.size(); ++s)
    for (int k = 0; k < options.samples; ++k) ts.push_back(knots[s] + (knots[s + 1] - knots[s]) * (k + 0.5) / options.samples);
  const double quad = U / static_cast<double>(ts.size());
  // Continuation: the penalty grows by 100 per step up to options.penalty, so early steps keep the
  // bending term strong (the seed's falling smoothing weight) and the curve does not fold.
  double beta = std::min(1e2, options.penalty);
  for (int it = 0; it < options.iterations; ++it) {
    spline.clear_terms();
    spline.add_bending(1.0);
    const double w = std::sqrt(beta * quad / std::pow(U, 4));  // beta / U^4 * integral dist^2 dt
    for (double t : ts) {
      const V c = spline.evaluate(X, t);
      const V f = surface.closest_point(c);
      const V n = surface.normal(f);
      // The squared distance to the tangent plane at the foot point (TDM); at the fixed point the
      // samples' offsets are normal, so the model's tangential blindness does not bias the result.
      spline.add_term(t, w * n.transpose(), Eigen::VectorXd::Constant(1, w * n.dot(f)));
    }
    Eigen::MatrixXd next = spline.solve(&X);
    // The step solves the model (distances to tangent planes); the objective it stands for, with
    // the true distances, must not grow: halve the step until it does not (at large penalties the
    // bending term no longer damps tangential sliding and full steps oscillate).
    auto objective = [&](const Eigen::MatrixXd& Y) {
      const BSpline c = to_curve(knots, Y);
      double e = bending_energy(c);
      for (double t : ts) {
        const V p = c.point(t);
        e += w * w * (surface.closest_point(p) - p).squaredNorm();
      }
      return e;
    };
    const double before = objective(X);
    const Eigen::MatrixXd full = next - X;
    double step = 1.0;
    for (int halving = 0; halving < 30 && objective(next) > before; ++halving) {
      step *= 0.5;
      next = X + step * full;
    }
    const double move = (next - X).rowwise().norm().maxCoeff();
    X = next;
    result.iterations = it + 1;
    if (beta >= options.penalty && move <= options.tolerance * U) {
      result.converged = true;
      break;
    }
    beta = std::min(beta * 100.0, options.penalty);
  }
  result.curve = to_curve(knots, X);
  result.max_distance = max_distance_to(surface, result.curve, 16);
  result.bending = bending_energy(result.curve);
  result.splits = options.splits;
  return result;
}

}  // namespace

SurfaceSplineResult surface_spline(const Surface& surface, const std::vector<Eigen::Vector3d>& points,
                                   const SurfaceSplineOptions& options) {
  if (points.size() < 2) throw InvalidInput("surface_spline: at least two points");
  if (options.splits < 1 || options.samples < 1 || options.iterations < 0 || !(options.penalty > 0.0) ||
      !(options.tolerance > 0.0) || !(options.distance >= 0.0) || options.max_splits < options.splits)
    throw InvalidInput("surface_spline: splits, samples, penalty and tolerance must be positive, max_splits >= splits");
  std::vector<V> on;
  for (const V& p : points) {
    require_finite(p, "surface_spline: a point");
    on.push_back(surface.closest_point(p));
  }
  SurfaceSplineOptions run = options;
  SurfaceSplineResult result = surface_spline_run(surface, on, run);
  // The C2 cubic space itself keeps the curve O(h^4) off a curved surface (h the segment length):
  // split finer, guided by that order, until the distance is met.
  while (options.distance > 0.0 && result.max_distance > options.distance && run.splits < options.max_splits) {
    const double factor = std::pow(result.max_distance / options.distance, 0.25) * 1.1;
    run.splits = std::min(options.max_splits, std::max(run.splits + 1, static_cast<int>(std::ceil(run.splits * factor))));
    result = surface_spline_run(surface, on, run);
  }
  return result;
}

Surface bspline_surface_constraint(BSplineSurface surface, std::string name) {
  const auto shared = std::make_shared<const BSplineSurface>(std::move(surface));
  Surface s;
  s.name = std::move(name);
  s.closest_point = [shared](const Eigen::Vector3d& p) { return closest_point(*shared, p).point; };
  s.normal = [shared](const Eigen::Vector3d& p) {
    const SurfaceFootPoint f = closest_point(*shared, p);
    const Eigen::Vector3d n = shared->normal(f.u, f.v);
    if (n.squaredNorm() == 0) throw GeometryError("the B-spline surface is singular at the foot point of a curve point");
    return n;
  };
  return s;
}

}  // namespace sculpt::splines
