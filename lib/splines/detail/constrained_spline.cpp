#include "splines/detail/constrained_spline.hpp"

#include <Eigen/SparseLU>
#include <array>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::splines::detail {

std::vector<double> refined_knots(const std::vector<double>& parameters, int splits) {
  if (parameters.size() < 2) throw InvalidInput("a spline through points needs at least two of them");
  if (splits < 1) throw InvalidInput("splits must be at least 1, got " + std::to_string(splits));
  for (std::size_t j = 0; j + 1 < parameters.size(); ++j)
    if (!(parameters[j] < parameters[j + 1]) || !std::isfinite(parameters[j + 1]))
      throw InvalidInput("the parameters (times) must be finite and strictly increasing");
  std::vector<double> knots(4, parameters.front());
  for (std::size_t j = 0; j + 1 < parameters.size(); ++j)
    for (int s = 1; s <= splits; ++s) {
      if (j + 2 == parameters.size() && s == splits) break;
      knots.push_back(s == splits ? parameters[j + 1]
                                  : parameters[j] + (parameters[j + 1] - parameters[j]) * s / splits);
    }
  knots.insert(knots.end(), 4, parameters.back());
  return knots;
}

namespace {
BSpline zero_curve(const std::vector<double>& knots) {
  const int n = static_cast<int>(knots.size()) - 4;
  return BSpline(3, knots, std::vector<Eigen::Vector3d>(static_cast<std::size_t>(n), Eigen::Vector3d::Zero()), false, 3);
}
}  // namespace

ConstrainedSpline::ConstrainedSpline(std::vector<double> knots, int dimension)
    : knots_(std::move(knots)),
      dim_(dimension),
      controls_(static_cast<int>(knots_.size()) - 4),
      basis_curve_(zero_curve(knots_)),
      gradient_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(controls_) * dimension)) {}

Eigen::VectorXd ConstrainedSpline::evaluate(const Eigen::MatrixXd& X, double t, int order) const {
  const Basis b = basis_curve_.basis(t, order);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(dim_);
  for (std::size_t j = 0; j < b.index.size(); ++j) v += b.value(order, static_cast<Eigen::Index>(j)) * X.row(b.index[j]).transpose();
  return v;
}

void ConstrainedSpline::add_bending(double weight) {
  // c'' is linear on each segment, |c''|^2 quadratic: two Gauss points are exact.
  const double g = 1.0 / std::sqrt(3.0);
  for (std::size_t s = 3; s + 4 < knots_.size(); ++s) {
    const double a = knots_[s], b = knots_[s + 1];
    if (!(b > a)) continue;
    for (double x : {-g, g}) {
      const double t = 0.5 * (a + b) + 0.5 * (b - a) * x;
      const Basis B = basis_curve_.basis(t, 2);
      const double w = weight * 0.5 * (b - a);
      for (std::size_t i = 0; i < B.index.size(); ++i)
        for (std::size_t j = 0; j < B.index.size(); ++j) {
          const double h = w * B.value(2, static_cast<Eigen::Index>(i)) * B.value(2, static_cast<Eigen::Index>(j));
          if (h == 0.0) continue;
          for (int c = 0; c < dim_; ++c) hessian_.emplace_back(B.index[i] * dim_ + c, B.index[j] * dim_ + c, h);
        }
    }
  }
}

void ConstrainedSpline::add_term(double t, const Eigen::MatrixXd& L, const Eigen::VectorXd& r) {
  const Basis B = basis_curve_.basis(t, 0);
  const Eigen::MatrixXd LL = L.transpose() * L;
  const Eigen::VectorXd Lr = L.transpose() * r;
  for (std::size_t i = 0; i < B.index.size(); ++i) {
    const double bi = B.value(0, static_cast<Eigen::Index>(i));
    if (bi == 0.0) continue;
    gradient_.segment(static_cast<Eigen::Index>(B.index[i]) * dim_, dim_) += bi * Lr;
    for (std::size_t j = 0; j < B.index.size(); ++j) {
      const double bj = B.value(0, static_cast<Eigen::Index>(j));
      if (bj == 0.0) continue;
      for (int a = 0; a < dim_; ++a)
        for (int c = 0; c < dim_; ++c)
          if (LL(a, c) != 0.0) hessian_.emplace_back(B.index[i] * dim_ + a, B.index[j] * dim_ + c, bi * bj * LL(a, c));
    }
  }
}

void ConstrainedSpline::add_constraint(double t, const Eigen::VectorXd& value, int order) {
  constraints_.push_back({basis_curve_.basis(t, order), order, Eigen::MatrixXd::Identity(dim_, dim_), value});
}

void ConstrainedSpline::add_constraint(double t, const Eigen::MatrixXd& G, const Eigen::VectorXd& value, int order) {
  constraints_.push_back({basis_curve_.basis(t, order), order, G, value});
}

void ConstrainedSpline::clear_terms() {
  hessian_.clear();
  gradient_.setZero();
}

Eigen::MatrixXd ConstrainedSpline::solve(const Eigen::MatrixXd* anchor) const {
  const Eigen::Index n = static_cast<Eigen::Index>(controls_) * dim_;
  Eigen::Index m = 0;
  for (const Constraint& c : constraints_) m += c.G.rows();
  // Scale the constraint rows like the Hessian's diagonal so the KKT matrix is balanced.
  double diag = 0.0;
  for (const auto& e : hessian_)
    if (e.row() == e.col()) diag += e.value();
  const double scale = diag > 0.0 ? diag / static_cast<double>(n) : 1.0;
  std::vector<Eigen::Triplet<double>> kkt = hessian_;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = gradient_;
  Eigen::Index row = n;
  for (const Constraint& c : constraints_) {
    for (Eigen::Index g = 0; g < c.G.rows(); ++g, ++row) {
      for (std::size_t j = 0; j < c.basis.index.size(); ++j)
        for (int a = 0; a < dim_; ++a) {
          const double v = scale * c.basis.value(c.order, static_cast<Eigen::Index>(j)) * c.G(g, a);
          if (v == 0.0) continue;
          const Eigen::Index col = static_cast<Eigen::Index>(c.basis.index[j]) * dim_ + a;
          kkt.emplace_back(row, col, v);
          kkt.emplace_back(col, row, v);
        }
      rhs(row) = scale * c.value(g);
    }
  }
  Eigen::SparseMatrix<double> K(n + m, n + m);
  K.setFromTriplets(kkt.begin(), kkt.end());
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n + m);
  if (anchor != nullptr) {
    for (int i = 0; i < controls_; ++i) x0.segment(static_cast<Eigen::Index>(i) * dim_, dim_) = anchor->row(i).transpose();
    rhs -= K * x0;  // the multipliers' part of x0 is zero: the solve gives the change of the controls
  }
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(K);
  if (lu.info() != Eigen::Success) throw GeometryError("the constrained spline system is singular (too few points or constraints?)");
  const Eigen::VectorXd x = x0 + lu.solve(rhs);
  if (lu.info() != Eigen::Success || !x.allFinite()) throw GeometryError("the constrained spline system could not be solved");
  Eigen::MatrixXd X(controls_, dim_);
  for (int i = 0; i < controls_; ++i) X.row(i) = x.segment(static_cast<Eigen::Index>(i) * dim_, dim_).transpose();
  return X;
}

}  // namespace sculpt::splines::detail
