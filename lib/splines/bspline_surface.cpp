#include "splines/bspline_surface.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/surface_foot_point_search.hpp"

namespace sculpt::splines {

namespace {

BSpline direction_basis(int degree, std::vector<double> knots, int count, bool closed, const char* name) {
  if (degree < 1 || degree > kMaxFastDegree)
    throw InvalidInput(std::string("B-spline surface: ") + name + " degree must be in [1, " + std::to_string(kMaxFastDegree) +
                       "], got " + std::to_string(degree));
  try {
    return BSpline(degree, std::move(knots), std::vector<Eigen::Vector3d>(std::max(count, 0), Eigen::Vector3d::Zero()), closed, 3);
  } catch (const InvalidInput& e) {
    throw InvalidInput(std::string("B-spline surface, ") + name + " direction: " + e.what());
  }
}

std::vector<double> uniform_knots(int degree, int n, bool closed) {
  if (closed) {
    std::vector<double> k(std::max(n, 0) + 1);
    for (std::size_t i = 0; i < k.size(); ++i) k[i] = n > 0 ? static_cast<double>(i) / n : 0.0;
    return k;
  }
  std::vector<double> k(std::max(n + degree + 1, 0));
  const int spans = n - degree;
  for (int i = 0; i < static_cast<int>(k.size()); ++i)
    k[i] = i <= degree ? 0.0 : i >= n ? 1.0 : static_cast<double>(i - degree) / std::max(spans, 1);
  return k;
}

}  // namespace

BSplineSurface::BSplineSurface(std::array<int, 2> degree, std::array<std::vector<double>, 2> knots, int rows, int columns,
                               std::vector<Eigen::Vector3d> controls, std::array<bool, 2> closed)
    : basis_{direction_basis(degree[0], std::move(knots[0]), rows, closed[0], "u"),
             direction_basis(degree[1], std::move(knots[1]), columns, closed[1], "v")},
      controls_(std::move(controls)) {
  if (static_cast<long long>(controls_.size()) != static_cast<long long>(rows) * columns)
    throw InvalidInput("B-spline surface: " + std::to_string(rows) + " x " + std::to_string(columns) + " grid needs " +
                       std::to_string(static_cast<long long>(rows) * columns) + " control points, got " +
                       std::to_string(controls_.size()));
  for (std::size_t i = 0; i < controls_.size(); ++i)
    if (!controls_[i].allFinite()) throw InvalidInput("B-spline surface: control point " + std::to_string(i) + " is not finite");
}

BSplineSurface BSplineSurface::uniform(std::array<int, 2> degree, int rows, int columns, std::vector<Eigen::Vector3d> controls,
                                       std::array<bool, 2> closed) {
  return BSplineSurface(degree, {uniform_knots(degree[0], rows, closed[0]), uniform_knots(degree[1], columns, closed[1])}, rows,
                        columns, std::move(controls), closed);
}

SurfaceJet BSplineSurface::jet(double u, double v, int order) const {
  if (order < 0 || order > 2) throw InvalidInput("B-spline surface: derivative order must be in [0, 2]");
  const BasisJet bu = basis_[0].basis_jet(u, order), bv = basis_[1].basis_jet(v, order);
  const int m = count(1);
  SurfaceJet out;
  for (int a = 0; a < bu.count; ++a) {
    // Partial sums over v for this row of controls: the value and v-derivatives.
    Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = c0, c2 = c0;
    const Eigen::Vector3d* row = &controls_[static_cast<std::size_t>(bu.index[a]) * m];
    for (int b = 0; b < bv.count; ++b) {
      const Eigen::Vector3d& P = row[bv.index[b]];
      c0 += bv.value[0][b] * P;
      if (order >= 1) c1 += bv.value[1][b] * P;
      if (order >= 2) c2 += bv.value[2][b] * P;
    }
    out.point += bu.value[0][a] * c0;
    if (order >= 1) {
      out.du += bu.value[1][a] * c0;
      out.dv += bu.value[0][a] * c1;
    }
    if (order >= 2) {
      out.duu += bu.value[2][a] * c0;
      out.duv += bu.value[1][a] * c1;
      out.dvv += bu.value[0][a] * c2;
    }
  }
  return out;
}

Eigen::Vector3d BSplineSurface::normal(double u, double v) const {
  const SurfaceJet j = jet(u, v, 1);
  const Eigen::Vector3d n = j.du.cross(j.dv);
  const double len = n.norm();
  return len > 1e-300 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

PrincipalCurvatures BSplineSurface::curvatures(double u, double v) const {
  const SurfaceJet j = jet(u, v, 2);
  PrincipalCurvatures out;
  const Eigen::Vector3d cross = j.du.cross(j.dv);
  const double len = cross.norm();
  if (!(len > 1e-300)) return out;
  const Eigen::Vector3d n = cross / len;
  Eigen::Matrix2d I, II;
  I << j.du.dot(j.du), j.du.dot(j.dv), j.du.dot(j.dv), j.dv.dot(j.dv);
  II << j.duu.dot(n), j.duv.dot(n), j.duv.dot(n), j.dvv.dot(n);
  // The shape operator's eigenproblem II x = k I x (I is positive definite where S_u x S_v != 0).
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(II, I);
  out.k1 = es.eigenvalues()[1];
  out.k2 = es.eigenvalues()[0];
  const Eigen::Vector2d e1 = es.eigenvectors().col(1), e2 = es.eigenvectors().col(0);
  out.d1 = (e1[0] * j.du + e1[1] * j.dv).normalized();
  out.d2 = (e2[0] * j.du + e2[1] * j.dv).normalized();
  out.normal = n;
  return out;
}

BSplineSurface BSplineSurface::with_controls(std::vector<Eigen::Vector3d> controls) const {
  if (controls.size() != controls_.size())
    throw InvalidInput("B-spline surface: expected " + std::to_string(controls_.size()) + " control points, got " +
                       std::to_string(controls.size()));
  BSplineSurface out = *this;
  for (std::size_t i = 0; i < controls.size(); ++i)
    if (!controls[i].allFinite()) throw InvalidInput("B-spline surface: control point " + std::to_string(i) + " is not finite");
  out.controls_ = std::move(controls);
  return out;
}

SurfaceFootPoint closest_point(const BSplineSurface& surface, const Eigen::Vector3d& x) {
  if (!x.allFinite()) throw InvalidInput("closest point: the point is not finite");
  return detail::SurfaceFootPointSearch(surface).global(x).foot;
}

std::vector<SurfaceFootPoint> closest_points(const BSplineSurface& surface, const std::vector<Eigen::Vector3d>& points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw InvalidInput("closest point: point " + std::to_string(i) + " is not finite");
  const detail::SurfaceFootPointSearch search(surface);
  std::vector<SurfaceFootPoint> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(search.global(p).foot);
  return out;
}

DistanceSummary distance(const BSplineSurface& surface, const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) throw InvalidInput("distance: empty point set");
  DistanceSummary d;
  double sum = 0.0;
  for (const auto& f : closest_points(surface, points)) {
    d.max = std::max(d.max, f.distance);
    sum += f.distance * f.distance;
  }
  d.rms = std::sqrt(sum / static_cast<double>(points.size()));
  return d;
}

std::vector<Eigen::Vector3d> sample(const BSplineSurface& surface, int nu, int nv) {
  const int n[2] = {nu, nv};
  for (int d = 0; d < 2; ++d)
    if (n[d] < (surface.closed(d) ? 1 : 2))
      throw InvalidInput("sample: " + std::to_string(n[d]) + " samples in direction " + (d ? "v" : "u") + " is too few");
  std::vector<Eigen::Vector3d> out;
  out.reserve(static_cast<std::size_t>(nu) * nv);
  const auto param = [&](int d, int i) {
    const auto [a, b] = surface.domain(d);
    return a + (b - a) * i / (surface.closed(d) ? n[d] : n[d] - 1);
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) out.push_back(surface.point(param(0, i), param(1, j)));
  return out;
}

}  // namespace sculpt::splines
