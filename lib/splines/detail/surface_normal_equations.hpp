#pragma once
/// \file surface_normal_equations.hpp
/// The linear system of one active-surface step (Pottmann, Leopoldseder & Hofer 2002, eq. 11 and
/// sec. 4): minimize over the control points P
///     sum_k (S_k P - x_k)^T M_k (S_k P - x_k) + lambda * E_tp(P)
/// where S_k P is the surface point at fixed parameters (u_k, v_k), M_k the Hessian of a local
/// quadratic model of the squared distance (SDM, PDM or TDM), and E_tp the thin-plate energy
/// integral of |S_uu|^2 + 2 |S_uv|^2 + |S_vv|^2 over the parameter domain (Gauss-Legendre
/// quadrature per knot span, exact for the polynomial integrand). 3 x 3 blocks are accumulated per
/// control point and offset (|di| <= p, |dj| <= q) and solved as a sparse LDL^T system.

#include <Eigen/Core>
#include <vector>

#include "splines/bspline_surface.hpp"

namespace sculpt::splines::detail {

class SurfaceNormalEquations {
 public:
  explicit SurfaceNormalEquations(const BSplineSurface& surface);
  /// Adds (S(u, v) P - x)^T M (S(u, v) P - x) for the basis jets of u and v (values, row 0).
  void add_term(const BasisJet& bu, const BasisJet& bv, const Eigen::Matrix3d& M, const Eigen::Vector3d& x);
  /// Adds the thin-plate energy with weight `relative` * trace(data part) / trace(energy part), so
  /// the weight depends neither on the scale nor on the number of points.
  void add_smoothing(double relative);
  /// Solves with the listed control points (index i * columns + j) kept at `current`; a tiny
  /// proximal term (1e-12 of the mean diagonal) towards `current` keeps the system definite.
  /// \throw GeometryError if the system cannot be solved.
  [[nodiscard]] std::vector<Eigen::Vector3d> solve(const std::vector<Eigen::Vector3d>& current,
                                                   const std::vector<int>& fixed) const;

 private:
  void add_quadratic(const BasisJet& bu, const BasisJet& bv, const double* w, const Eigen::Matrix3d& M,
                     std::vector<Eigen::Matrix3d>& blocks) const;
  [[nodiscard]] std::size_t slot(int control, int di, int dj) const {
    return static_cast<std::size_t>(control) * width_ + static_cast<std::size_t>((di + p_) * (2 * q_ + 1) + (dj + q_));
  }
  const BSplineSurface* surface_;
  int nu_, nv_, p_, q_;
  std::size_t width_;
  std::vector<Eigen::Matrix3d> blocks_;
  std::vector<Eigen::Vector3d> rhs_;
};

}  // namespace sculpt::splines::detail
