#pragma once
/// \file bspline.hpp
/// B-spline curves of any degree in 2D and 3D, open (any knot vector, clamped by the factories)
/// and closed (periodic), after Piegl & Tiller, "The NURBS Book", ch. 2-5: evaluation by the
/// basis functions and their derivatives (A2.2, A2.3), curvature, knot insertion (Boehm, A5.1).
/// The active curves of Pottmann, Leopoldseder & Hofer 2002 (sec. 3) are of this form: a curve
/// point at a fixed parameter depends linearly on the control points.

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

namespace sculpt::splines {

/// Basis functions (and derivatives) nonzero at one parameter: value(k, j) is the k-th
/// derivative of the basis function of control point index[j].
struct Basis {
  std::vector<int> index;  ///< indices into controls() (already wrapped for closed curves)
  Eigen::MatrixXd value;   ///< (order + 1) x (degree + 1)
};

/// Largest degree of the allocation-free paths (jet, small_basis).
inline constexpr int kMaxFastDegree = 7;

/// The nonzero basis function values at one parameter, without heap allocation (degree <= kMaxFastDegree).
struct SmallBasis {
  int count = 0;
  std::array<int, kMaxFastDegree + 1> index{};
  std::array<double, kMaxFastDegree + 1> value{};
  std::array<double, kMaxFastDegree + 1> derivative{};  ///< first derivatives (small_basis(t, true) only)
};

/// The nonzero basis functions and their first and second derivatives at one parameter, without
/// heap allocation: value[k][j] is the k-th derivative of the basis function of control index[j]
/// (index already wrapped for closed curves; entries above the requested order are zero). The
/// tensor-product surfaces (bspline_surface.hpp) evaluate through it.
struct BasisJet {
  int count = 0;
  std::array<int, kMaxFastDegree + 1> index{};
  std::array<std::array<double, kMaxFastDegree + 1>, 3> value{};
};

/// A B-spline curve. Points are Eigen::Vector3d; a 2D curve (`dimension() == 2`) keeps z = 0.
///
/// Knots, as given to the constructor and returned by knots():
/// - open curve with n control points: n + degree + 1 non-decreasing values; the domain is
///   [knots[degree], knots[n]] (clamped when the first and last degree + 1 values are equal);
/// - closed curve with n control points: the n + 1 break points u_0 <= ... <= u_n of one period,
///   domain [u_0, u_n); the curve repeats with period u_n - u_0 and the control polygon closes.
/// Interior knot multiplicity is at most `degree` (the curve stays continuous); multiplicity
/// `degree` gives a corner through a control point.
class BSpline {
 public:
  /// \throw InvalidInput for degree < 1, too few control points (open: degree + 1, closed:
  ///        degree + 1), a knot count that does not match, decreasing or non-finite knots, an
  ///        empty domain, a multiplicity above degree, non-finite control points, dimension not
  ///        0 (automatic: 2 if every z is 0), 2 or 3, or dimension 2 with a nonzero z.
  BSpline(int degree, std::vector<double> knots, std::vector<Eigen::Vector3d> controls, bool closed,
          int dimension = 0);

  /// Open curve with a clamped uniform knot vector over [0, 1].
  static BSpline clamped(int degree, std::vector<Eigen::Vector3d> controls, int dimension = 0);
  /// Closed curve with uniform break points 0, 1, ..., n (n = number of control points).
  static BSpline periodic(int degree, std::vector<Eigen::Vector3d> controls, int dimension = 0);
  /// Bezier curve of degree controls.size() - 1 over [0, 1] (a clamped B-spline without interior knots).
  static BSpline bezier(std::vector<Eigen::Vector3d> controls, int dimension = 0);

  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] bool closed() const { return closed_; }
  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] const std::vector<double>& knots() const { return knots_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& controls() const { return controls_; }
  [[nodiscard]] int control_count() const { return static_cast<int>(controls_.size()); }
  /// Open: [knots[degree], knots[n]]; closed: [u_0, u_n].
  [[nodiscard]] std::pair<double, double> domain() const;
  /// Distinct knot values inside the domain, both ends included: the span boundaries.
  [[nodiscard]] std::vector<double> breaks() const;
  /// True for an open curve without interior knots and clamped ends.
  [[nodiscard]] bool is_bezier() const;

  /// The curve point. Closed curves wrap t into the domain; open curves clamp t to it.
  /// \throw InvalidInput if t is not finite
  [[nodiscard]] Eigen::Vector3d point(double t) const;
  /// Point and derivatives c(t), c'(t), ..., c^(order)(t) (order >= 0); right derivatives at knots.
  [[nodiscard]] std::vector<Eigen::Vector3d> derivatives(double t, int order) const;
  /// c(t), c'(t), ..., c^(order)(t) for order <= 3 (higher entries zero), without heap allocation
  /// for degree <= kMaxFastDegree: the form the foot point search and the fitters use.
  [[nodiscard]] std::array<Eigen::Vector3d, 4> jet(double t, int order) const;
  /// basis(t, 0) without heap allocation. \throw InvalidInput for degree > kMaxFastDegree.
  [[nodiscard]] SmallBasis small_basis(double t, bool with_derivative = false) const;
  /// Basis values and derivatives up to `order` (0..2) at t (wrapped or clamped like point()).
  /// \throw InvalidInput for degree > kMaxFastDegree or an order outside [0, 2].
  [[nodiscard]] BasisJet basis_jet(double t, int order) const;
  /// Curvature |c' x c''| / |c'|^3; for a 2D curve signed (positive turning left). 0 where c' = 0.
  [[nodiscard]] double curvature(double t) const;
  /// Nonzero basis functions at t and their derivatives up to `order`.
  [[nodiscard]] Basis basis(double t, int order = 0) const;

  /// The same curve with the knot t inserted once (Boehm). \throw InvalidInput if t is outside
  /// the domain (open: strictly inside; closed: any finite t, wrapped) or the multiplicity would exceed degree.
  [[nodiscard]] BSpline insert_knot(double t) const;

  /// The curve with the control points replaced (same degree, knots, closedness, dimension).
  /// \throw InvalidInput if the count differs or a point is not finite.
  [[nodiscard]] BSpline with_controls(std::vector<Eigen::Vector3d> controls) const;

 private:
  [[nodiscard]] double wrap(double t) const;
  [[nodiscard]] int span(double t) const;

  int degree_ = 0;
  bool closed_ = false;
  int dimension_ = 3;
  std::vector<double> knots_;               // user form (see class comment)
  std::vector<Eigen::Vector3d> controls_;   // unique control points
  std::vector<double> ext_knots_;           // full knot vector (closed: periodically extended)
  std::vector<Eigen::Vector3d> ext_controls_;  // closed: controls followed by the first degree again
};

}  // namespace sculpt::splines
