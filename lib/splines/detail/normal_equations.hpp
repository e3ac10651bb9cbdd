#pragma once
/// \file normal_equations.hpp
/// The linear system of one active-curve step (Pottmann, Leopoldseder & Hofer 2002, eq. 11;
/// Wang, Pottmann & Liu 2006, sec. 4): minimize
///     sum_k (B_k P - X_k)^T M_k (B_k P - X_k) + lambda * sum |P_{i-1} - 2 P_i + P_{i+1}|^2
/// over the control points P, where B_k P is a curve point at a fixed parameter and M_k the
/// Hessian of a local quadratic model of the squared distance (detail/distance_models.hpp).
/// Blocks are accumulated per pair of control points and solved as a sparse LDL^T system.

#include <Eigen/Core>
#include <vector>

#include "splines/bspline.hpp"

namespace sculpt::splines::detail {

class NormalEquations {
 public:
  NormalEquations(int controls, int degree, int dimension, bool closed);
  /// Adds (sum_j b_j P_{index_j} - x)^T M (sum_j b_j P_{index_j} - x).
  void add_term(const std::vector<int>& index, const Eigen::VectorXd& b, const Eigen::Matrix3d& M,
                const Eigen::Vector3d& x);
  /// Adds the control polygon's bending energy (second differences; cyclic when closed) with weight
  /// `relative` times trace(data part) / trace(bending part), so the weight does not depend on scale or point count.
  /// The same for `count` basis values given as arrays (no allocation).
  void add_term(int count, const int* index, const double* b, const Eigen::Matrix3d& M, const Eigen::Vector3d& x);
  void add_smoothing(double relative);
  /// Adds weight * ((sum_j b_j P_j - c) . v)^2 + 2 weight ((sum_j b_j P_j - c) . v)((sum_j db_j P_j - v) . r)
  /// with c = sum_j b_j P_j and v = sum_j db_j P_j at the current control points (`point`, `velocity`):
  /// the correction of Newton's model of a squared distance to a moving curve (fit_loop.cpp),
  /// b the basis values, db their derivatives, r the residual.
  void add_newton_correction(int count, const int* index, const double* b, const double* db, const Eigen::Vector3d& point,
                             const Eigen::Vector3d& velocity, const Eigen::Vector3d& residual, double weight);
  /// Solves with the given control points fixed; `current` serves as the anchor of a tiny
  /// proximal term (weight 1e-12 of the mean diagonal) that keeps the system definite.
  /// \throw GeometryError if the system cannot be solved.
  [[nodiscard]] std::vector<Eigen::Vector3d> solve(const std::vector<Eigen::Vector3d>& current,
                                                   const std::vector<int>& fixed) const;

 private:
  Eigen::Matrix3d& block(int i, int j);
  int n_, p_, dim_;
  bool closed_, banded_;
  std::vector<Eigen::Matrix3d> blocks_;
  std::vector<Eigen::Vector3d> rhs_;
};

}  // namespace sculpt::splines::detail
