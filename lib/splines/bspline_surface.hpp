#pragma once
/// \file bspline_surface.hpp
/// Tensor-product B-spline surfaces S(u, v) = sum_ij N_i(u) M_j(v) P_ij, open or closed (periodic)
/// in each direction independently (Piegl & Tiller, "The NURBS Book", ch. 3.4: the basis of each
/// direction is the curve's, bspline.hpp), with partial derivatives up to second order, the
/// normal, principal curvatures, and robust foot points. The active surfaces of Pottmann,
/// Leopoldseder & Hofer 2002 (sec. 4) are of this form: a surface point at fixed parameters depends
/// linearly on the control points.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <utility>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/foot_point.hpp"

namespace sculpt::splines {

/// S and its partial derivatives at one parameter pair (entries above the requested order are zero).
struct SurfaceJet {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d duu = Eigen::Vector3d::Zero(), duv = Eigen::Vector3d::Zero(), dvv = Eigen::Vector3d::Zero();
};

/// Principal curvatures k1 >= k2 with unit principal directions, signed with respect to `normal`
/// (= S_u x S_v normalized): positive where the surface bends towards the normal.
struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), d2 = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::Zero();
};

/// A tensor-product B-spline surface. Direction 0 is u, direction 1 is v; control point (i, j)
/// (i < count(0), j < count(1)) is controls()[i * count(1) + j].
///
/// Knots per direction are given in the curve's form (bspline.hpp): open, n + degree + 1 values;
/// closed, the n + 1 break points of one period. Degrees are at most kMaxFastDegree.
class BSplineSurface {
 public:
  /// \throw InvalidInput for a degree outside [1, kMaxFastDegree], a control count or knot vector
  ///        the direction's curve would refuse, controls.size() != rows * columns, or a non-finite control.
  BSplineSurface(std::array<int, 2> degree, std::array<std::vector<double>, 2> knots, int rows, int columns,
                 std::vector<Eigen::Vector3d> controls, std::array<bool, 2> closed);

  /// Uniform knots over [0, 1] in both directions: clamped where open, uniform break points where closed.
  static BSplineSurface uniform(std::array<int, 2> degree, int rows, int columns, std::vector<Eigen::Vector3d> controls,
                                std::array<bool, 2> closed = {false, false});

  [[nodiscard]] int degree(int direction) const { return basis_[direction].degree(); }
  [[nodiscard]] bool closed(int direction) const { return basis_[direction].closed(); }
  [[nodiscard]] int count(int direction) const { return basis_[direction].control_count(); }
  [[nodiscard]] const std::vector<double>& knots(int direction) const { return basis_[direction].knots(); }
  [[nodiscard]] std::pair<double, double> domain(int direction) const { return basis_[direction].domain(); }
  /// Distinct knot values of the domain (span boundaries), both ends included.
  [[nodiscard]] std::vector<double> breaks(int direction) const { return basis_[direction].breaks(); }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& controls() const { return controls_; }
  [[nodiscard]] const Eigen::Vector3d& control(int i, int j) const { return controls_[i * count(1) + j]; }
  /// The curve that carries direction d's basis (its control points are placeholders).
  [[nodiscard]] const BSpline& basis(int direction) const { return basis_[direction]; }

  /// Closed directions wrap the parameter, open ones clamp it. \throw InvalidInput if u or v is not finite.
  [[nodiscard]] Eigen::Vector3d point(double u, double v) const { return jet(u, v, 0).point; }
  /// S and its partial derivatives up to `order` (0..2).
  [[nodiscard]] SurfaceJet jet(double u, double v, int order) const;
  /// Unit normal S_u x S_v / |S_u x S_v|; zero where the surface is singular (S_u x S_v = 0).
  [[nodiscard]] Eigen::Vector3d normal(double u, double v) const;
  /// Principal curvatures from the two fundamental forms; all zero where the surface is singular.
  [[nodiscard]] PrincipalCurvatures curvatures(double u, double v) const;

  /// The same surface with other control points. \throw InvalidInput if the count differs or a point is not finite.
  [[nodiscard]] BSplineSurface with_controls(std::vector<Eigen::Vector3d> controls) const;

 private:
  std::array<BSpline, 2> basis_;
  std::vector<Eigen::Vector3d> controls_;
};

/// A foot point on a surface: parameters, point, distance.
struct SurfaceFootPoint {
  double u = 0.0, v = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// The closest point of the surface to x. Every knot span whose control-point box (a bound of the
/// span by the convex hull property) is closer than the best point so far is searched: Newton on
/// (u, v) from the span's nearest sample, clamped to the span. \throw InvalidInput if x is not finite.
[[nodiscard]] SurfaceFootPoint closest_point(const BSplineSurface& surface, const Eigen::Vector3d& x);

/// closest_point for every point, sharing one search structure.
[[nodiscard]] std::vector<SurfaceFootPoint> closest_points(const BSplineSurface& surface,
                                                           const std::vector<Eigen::Vector3d>& points);

/// Largest and rms distance of a point set to the surface (exact foot points).
/// \throw InvalidInput for an empty set or a non-finite point.
[[nodiscard]] DistanceSummary distance(const BSplineSurface& surface, const std::vector<Eigen::Vector3d>& points);

/// Points at nu x nv uniform parameters over the domain (closed directions without repeating the
/// seam), row-major with u outer. \throw InvalidInput for a count below 2 (1 in a closed direction).
[[nodiscard]] std::vector<Eigen::Vector3d> sample(const BSplineSurface& surface, int nu, int nv);

}  // namespace sculpt::splines
