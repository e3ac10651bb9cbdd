#include "splines/fit_surface.hpp"
#include "base/cancel.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/distance_models.hpp"
#include "splines/detail/surface_foot_point_search.hpp"
#include "splines/detail/surface_normal_equations.hpp"

namespace sculpt::splines {

namespace {

double thread_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

struct Term {
  double u = 0.0, v = 0.0;
  Eigen::Matrix3d M = Eigen::Matrix3d::Identity();
  double edge_u = 0.0, edge_v = 0.0;  // boundary points: the foot point on their edge curve
  Eigen::Matrix3d edge_M = Eigen::Matrix3d::Zero();
};

struct Evaluation {
  std::vector<Term> terms;
  double objective = 0.0, max = 0.0, rms = 0.0;  ///< true distances to the surface
  double merit = 0.0;  ///< with the boundary points' squared distances to their edges: the line search's objective
};

// A data point assigned to a boundary curve: the edge where parameter `direction` equals `at`.
struct Edge {
  int direction = -1;  // -1: not a boundary point
  double at = 0.0;
};

// The Hessian of the local quadratic model of the squared distance at data point p with foot
// point jet J (fit_surface.hpp, seed sec. 2 Proposition 1 and eq. 7). `on_boundary`: the foot
// point is a corner (edges take the edge curve's model, see evaluate), where the distance is the
// point distance, as the curve fitter's at its end points.
Eigen::Matrix3d distance_hessian(Method method, const Eigen::Vector3d& p, const SurfaceJet& J, bool on_boundary) {
  if (method == Method::PDM || on_boundary) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d cross = J.du.cross(J.dv);
  const double len = cross.norm();
  if (!(len > 1e-300)) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d n = cross / len;
  Eigen::Matrix3d M = n * n.transpose();
  if (method == Method::TDM) return M;
  Eigen::Matrix2d I, II;
  I << J.du.dot(J.du), J.du.dot(J.dv), J.du.dot(J.dv), J.dv.dot(J.dv);
  II << J.duu.dot(n), J.duv.dot(n), J.duv.dot(n), J.dvv.dot(n);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(II, I);
  const double d = (p - J.point).dot(n);
  for (int i = 0; i < 2; ++i) {
    const double dk = d * es.eigenvalues()[i];
    if (!(dk < 0)) continue;  // between the surface and the curvature centre (or flat): truncated to 0
    const Eigen::Vector2d e = es.eigenvectors().col(i);
    const Eigen::Vector3d t = (e[0] * J.du + e[1] * J.dv).normalized();
    M += (dk / (dk - 1.0)) * (t * t.transpose());
  }
  return M;
}

Evaluation evaluate(const BSplineSurface& s, const std::vector<Eigen::Vector3d>& points, Method method, const Evaluation* previous,
                    const std::vector<Edge>& edges) {
  const detail::SurfaceFootPointSearch search(s);
  const auto [a0, a1] = s.domain(0);
  const auto [b0, b1] = s.domain(1);
  Evaluation e;
  e.terms.resize(points.size());
  double sum = 0.0, merit = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const detail::SurfaceFootJet f =
        previous ? search.warm(points[k], previous->terms[k].u, previous->terms[k].v) : search.global(points[k]);
    sum += f.foot.distance * f.foot.distance;
    e.max = std::max(e.max, f.foot.distance);
    const bool on_u_edge = !s.closed(0) && (f.foot.u <= a0 || f.foot.u >= a1),
               on_v_edge = !s.closed(1) && (f.foot.v <= b0 || f.foot.v >= b1);
    Term& term = e.terms[k];
    term.u = f.foot.u;
    term.v = f.foot.v;
    if (on_u_edge != on_v_edge && method != Method::PDM) {
      // On an edge (not a corner) the distance is to the edge curve: the curve's model along it.
      const detail::Model model = method == Method::TDM ? detail::Model::TDM : detail::Model::SDM;
      term.M = on_u_edge ? detail::distance_hessian(model, points[k], f.foot.point, f.jet.dv, f.jet.dvv, false)
                         : detail::distance_hessian(model, points[k], f.foot.point, f.jet.du, f.jet.duu, false);
    } else {
      term.M = distance_hessian(method, points[k], f.jet, on_u_edge || on_v_edge);
    }
    merit += f.foot.distance * f.foot.distance;
    if (!edges.empty() && edges[k].direction >= 0) {
      // The seed's boundary approximation term (sec. 4, item 2), added to the surface term: the
      // point also pulls its edge curve, with the curve's distance model (detail/distance_models.hpp).
      const Edge& edge = edges[k];
      const double t0 = previous ? (edge.direction == 0 ? previous->terms[k].edge_v : previous->terms[k].edge_u)
                                 : (edge.direction == 0 ? f.foot.v : f.foot.u);
      const detail::SurfaceFootJet g = search.along_edge(points[k], edge.direction, edge.at, t0);
      const double t = edge.direction == 0 ? g.foot.v : g.foot.u;
      const auto [c0, c1] = edge.direction == 0 ? std::pair{b0, b1} : std::pair{a0, a1};
      const bool at_end = !s.closed(1 - edge.direction) && (t <= c0 || t >= c1);
      const detail::Model model = method == Method::PDM ? detail::Model::PDM : method == Method::TDM ? detail::Model::TDM : detail::Model::SDM;
      const Eigen::Vector3d& velocity = edge.direction == 0 ? g.jet.dv : g.jet.du;
      const Eigen::Vector3d& acceleration = edge.direction == 0 ? g.jet.dvv : g.jet.duu;
      term.edge_u = g.foot.u;
      term.edge_v = g.foot.v;
      term.edge_M = detail::distance_hessian(model, points[k], g.foot.point, velocity, acceleration, at_end);
      merit += g.foot.distance * g.foot.distance;
    }
  }
  e.objective = sum / static_cast<double>(points.size());
  e.merit = merit / static_cast<double>(points.size());
  e.rms = std::sqrt(e.objective);
  return e;
}

// Boundary points: those whose foot point on the start surface lies on an edge of an open direction.
std::vector<Edge> boundary_edges(const BSplineSurface& s, const std::vector<Eigen::Vector3d>& points) {
  const detail::SurfaceFootPointSearch search(s);
  std::vector<Edge> edges(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const SurfaceFootPoint f = search.global(points[k]).foot;
    for (int d = 0; d < 2 && edges[k].direction < 0; ++d) {
      if (s.closed(d)) continue;
      const auto [c0, c1] = s.domain(d);
      const double t = d == 0 ? f.u : f.v;
      if (t <= c0 || t >= c1) edges[k] = {d, t <= c0 ? c0 : c1};
    }
  }
  return edges;
}

}  // namespace

std::array<Eigen::Vector3d, 4> corner_points(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4) throw InvalidInput("corner points: need at least 4 points, got " + std::to_string(points.size()));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw InvalidInput("corner points: point " + std::to_string(i) + " is not finite");
    mean += points[i];
  }
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& p : points) C += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  const Eigen::Vector3d a = es.eigenvectors().col(2), b = es.eigenvectors().col(1);
  const Eigen::Vector3d dirs[4] = {-a - b, a - b, -a + b, a + b};
  std::array<Eigen::Vector3d, 4> out;
  for (int c = 0; c < 4; ++c) {
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& p : points)
      if (const double s = (p - mean).dot(dirs[c]); s > best) {
        best = s;
        out[c] = p;
      }
  }
  return out;
}

BSplineSurface bilinear_patch(const std::array<Eigen::Vector3d, 4>& corners, std::array<int, 2> controls, std::array<int, 2> degree) {
  for (const auto& c : corners)
    if (!c.allFinite()) throw InvalidInput("bilinear patch: a corner is not finite");
  const int nu = controls[0], nv = controls[1];
  // Greville abscissae of the clamped uniform knots: the linear function's control values.
  const auto greville = [](int p, int n) {
    const BSpline carrier = BSpline::clamped(p, std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()), 3);
    std::vector<double> g(n);
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int k = 1; k <= p; ++k) s += carrier.knots()[i + k];
      g[i] = s / p;
    }
    return g;
  };
  if (degree[0] < 1 || degree[1] < 1 || nu < degree[0] + 1 || nv < degree[1] + 1)
    throw InvalidInput("bilinear patch: a " + std::to_string(nu) + " x " + std::to_string(nv) + " grid of degree " +
                       std::to_string(degree[0]) + " x " + std::to_string(degree[1]) + " is too small");
  const std::vector<double> gu = greville(degree[0], nu), gv = greville(degree[1], nv);
  std::vector<Eigen::Vector3d> P(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double s = gu[i], t = gv[j];
      P[i * nv + j] = (1 - s) * (1 - t) * corners[0] + s * (1 - t) * corners[1] + (1 - s) * t * corners[2] + s * t * corners[3];
    }
  return BSplineSurface::uniform(degree, nu, nv, std::move(P));
}

FitSurfaceResult fit_surface(const std::vector<Eigen::Vector3d>& points, const FitSurfaceOptions& options) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput("fit surface: point " + std::to_string(i) + " is not finite");
  BSplineSurface surface = options.start ? *options.start
                                         : bilinear_patch(options.corners ? *options.corners : corner_points(points),
                                                          options.controls, options.degree);
  const int nu = surface.count(0), nv = surface.count(1), n = nu * nv;
  if (static_cast<long long>(points.size()) < n)
    throw InvalidInput("fit surface: " + std::to_string(points.size()) + " points for " + std::to_string(n) + " control points");
  std::vector<int> fixed = options.fixed;
  for (int f : fixed)
    if (f < 0 || f >= n) throw InvalidInput("fit surface: fixed control index " + std::to_string(f) + " out of range");
  if (options.fix_corners && !surface.closed(0) && !surface.closed(1))
    for (int c : {0, nv - 1, (nu - 1) * nv, n - 1}) fixed.push_back(c);
  if (options.fix_boundary) {
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j)
        if ((!surface.closed(0) && (i == 0 || i == nu - 1)) || (!surface.closed(1) && (j == 0 || j == nv - 1)))
          fixed.push_back(i * nv + j);
  }
  const bool line_search = options.method != Method::PDM;

  double t0 = thread_cpu_ms();
  const std::vector<Edge> edges =
      options.fit_boundary ? boundary_edges(surface, points) : std::vector<Edge>{};
  const std::vector<Edge> no_edges;
  const std::vector<Edge>& term_edges = options.fit_boundary ? edges : no_edges;
  Evaluation current = evaluate(surface, points, options.method, nullptr, term_edges);
  FitSurfaceResult result{surface, {}, 0, false};
  result.history.push_back({0, current.objective, current.max, current.rms, 0.0, 1.0, thread_cpu_ms() - t0});
  double lambda = options.smoothing;
  for (int k = 1; k <= options.iterations; ++k) {
    check_cancel();  // Ctrl-C (base/cancel.hpp): one iteration solves the whole fit
    t0 = thread_cpu_ms();
    detail::SurfaceNormalEquations system(surface);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Term& term = current.terms[i];
      system.add_term(surface.basis(0).basis_jet(term.u, 0), surface.basis(1).basis_jet(term.v, 0), term.M, points[i]);
      if (options.fit_boundary && edges[i].direction >= 0)
        system.add_term(surface.basis(0).basis_jet(term.edge_u, 0), surface.basis(1).basis_jet(term.edge_v, 0), term.edge_M, points[i]);
    }
    system.add_smoothing(lambda);
    const std::vector<Eigen::Vector3d> solved = system.solve(surface.controls(), fixed);
    double step = 1.0;
    BSplineSurface candidate = surface;
    Evaluation next;
    for (int halvings = 0;; ++halvings) {
      std::vector<Eigen::Vector3d> c(n);
      for (int i = 0; i < n; ++i) c[i] = surface.controls()[i] + step * (solved[i] - surface.controls()[i]);
      candidate = surface.with_controls(std::move(c));
      next = evaluate(candidate, points, options.method, &current, term_edges);
      if (!line_search || next.merit <= current.merit) break;
      if (halvings >= 8) {  // no descent along the step (rounding level near the optimum): keep the surface
        step = 0.0;
        break;
      }
      step *= 0.5;
    }
    if (step == 0.0) {
      result.history.push_back({k, current.objective, current.max, current.rms, lambda, 0.0, thread_cpu_ms() - t0});
      result.iterations = k;
      result.converged = true;
      break;
    }
    if (!std::isfinite(next.objective)) throw GeometryError("fit surface: the objective is not finite (diverged)");
    surface = candidate;
    result.history.push_back({k, next.objective, next.max, next.rms, lambda, step, thread_cpu_ms() - t0});
    result.iterations = k;
    const double change = std::abs(current.merit - next.merit);
    current = std::move(next);
    lambda *= options.smoothing_decay;
    if (change <= options.tolerance * std::max(current.merit, 1e-300) || current.merit == 0.0) {
      result.converged = true;
      break;
    }
  }
  result.surface = surface;
  return result;
}

}  // namespace sculpt::splines
