#pragma once
/// \file constrained_spline.hpp
/// The linear step shared by splines on surfaces and motion design (Pottmann, Leopoldseder &
/// Hofer 2002, sec. 5.2-5.3): a clamped cubic B-spline curve in R^d whose knots are given
/// parameters u_0 < ... < u_{n-1}, each span split into `splits` equal segments (knot insertion),
/// with control points X minimizing
///     w_b * integral |c''(t)|^2 dt  +  sum_k |L_k c(t_k) - r_k|^2        (eq. 13 with eq. 16)
/// subject to the exact linear constraints c(u_j) = p_j (and optionally c'(t) = v), solved as one
/// sparse KKT system. The quadratic terms |L_k c(t_k) - r_k|^2 are the local quadratic
/// approximants of the squared distance to a surface or manifold (squared distance to the tangent
/// space at the foot point).

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "splines/bspline.hpp"

namespace sculpt::splines::detail {

/// The clamped cubic knot vector over `parameters` (strictly increasing, at least two) with each
/// span split into `splits` equal segments. \throw InvalidInput otherwise.
[[nodiscard]] std::vector<double> refined_knots(const std::vector<double>& parameters, int splits);

class ConstrainedSpline {
 public:
  /// A cubic curve in R^dimension with the full clamped knot vector `knots`.
  ConstrainedSpline(std::vector<double> knots, int dimension);

  [[nodiscard]] int controls() const { return controls_; }
  [[nodiscard]] int dimension() const { return dim_; }
  /// Nonzero basis functions (value, first and second derivative) at t.
  [[nodiscard]] Basis basis(double t) const { return basis_curve_.basis(t, 2); }
  /// The curve point (derivative `order` <= 2) at t for controls X (controls x dimension).
  [[nodiscard]] Eigen::VectorXd evaluate(const Eigen::MatrixXd& X, double t, int order = 0) const;

  /// Adds weight * integral over the domain of |c''|^2 (exact: Gauss quadrature per segment).
  void add_bending(double weight);
  /// Adds |L c(t) - r|^2 (L: rows x dimension).
  void add_term(double t, const Eigen::MatrixXd& L, const Eigen::VectorXd& r);
  /// Requires c^(order)(t) = value exactly (order 0, 1 or 2).
  void add_constraint(double t, const Eigen::VectorXd& value, int order = 0);
  /// Requires G c^(order)(t) = value exactly (G: rows x dimension, rows independent).
  void add_constraint(double t, const Eigen::MatrixXd& G, const Eigen::VectorXd& value, int order);
  /// Drops the quadratic terms, keeps the constraints.
  void clear_terms();

  /// The minimizing controls (controls x dimension). With `anchor` (controls x dimension) the
  /// system is solved for the change from it, so rounding is relative to the change, not to the
  /// controls (matters with large penalty weights). \throw GeometryError if the system is singular.
  [[nodiscard]] Eigen::MatrixXd solve(const Eigen::MatrixXd* anchor = nullptr) const;

 private:
  struct Constraint {
    Basis basis;
    int order;
    Eigen::MatrixXd G;
    Eigen::VectorXd value;
  };
  std::vector<double> knots_;
  int dim_;
  int controls_;
  BSpline basis_curve_;  // zero controls: only its basis functions are used
  std::vector<Eigen::Triplet<double>> hessian_;  // of the quadratic part, (control * dim + coordinate) indices
  Eigen::VectorXd gradient_;                     // the objective is x^T H x - 2 g^T x + const
  std::vector<Constraint> constraints_;
};

}  // namespace sculpt::splines::detail
