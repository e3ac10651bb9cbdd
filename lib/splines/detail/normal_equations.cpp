#include "splines/detail/normal_equations.hpp"

#include <Eigen/QR>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>

#include "base/errors.hpp"

namespace sculpt::splines::detail {

NormalEquations::NormalEquations(int controls, int degree, int dimension, bool closed)
    : n_(controls), p_(degree), dim_(dimension), closed_(closed), banded_(controls >= 2 * degree + 4) {
  blocks_.assign(banded_ ? static_cast<std::size_t>(n_) * (2 * p_ + 3) : static_cast<std::size_t>(n_) * n_,
                 Eigen::Matrix3d::Zero());
  rhs_.assign(n_, Eigen::Vector3d::Zero());
}

Eigen::Matrix3d& NormalEquations::block(int i, int j) {
  if (!banded_) return blocks_[static_cast<std::size_t>(i) * n_ + j];
  int offset = j - i;  // in [-p-1, p+1] (cyclic for closed curves)
  if (offset > n_ / 2) offset -= n_;
  if (offset < -n_ / 2) offset += n_;
  return blocks_[static_cast<std::size_t>(i) * (2 * p_ + 3) + (offset + p_ + 1)];
}

void NormalEquations::add_term(const std::vector<int>& index, const Eigen::VectorXd& b, const Eigen::Matrix3d& M,
                               const Eigen::Vector3d& x) {
  add_term(static_cast<int>(index.size()), index.data(), b.data(), M, x);
}

void NormalEquations::add_term(int count, const int* index, const double* b, const Eigen::Matrix3d& M,
                               const Eigen::Vector3d& x) {
  const Eigen::Vector3d Mx = M * x;
  bool consecutive = banded_ && count <= p_ + 1;
  for (int a = 1; a < count && consecutive; ++a) consecutive = index[a] == (index[0] + a) % n_;
  if (consecutive) {  // the usual case: block (i, i + o) sits at column o + p + 1 of row i
    const int width = 2 * p_ + 3;
    for (int a = 0; a < count; ++a) {
      rhs_[index[a]] += b[a] * Mx;
      Eigen::Matrix3d* row = &blocks_[static_cast<std::size_t>(index[a]) * width + (p_ + 1 - a)];
      if (dim_ == 2) {
        for (int c = 0; c < count; ++c) row[c].topLeftCorner<2, 2>() += (b[a] * b[c]) * M.topLeftCorner<2, 2>();
      } else {
        for (int c = 0; c < count; ++c) row[c] += (b[a] * b[c]) * M;
      }
    }
    return;
  }
  for (int a = 0; a < count; ++a) {
    rhs_[index[a]] += b[a] * Mx;
    for (int c = 0; c < count; ++c) block(index[a], index[c]) += (b[a] * b[c]) * M;
  }
}

void NormalEquations::add_newton_correction(int count, const int* index, const double* b, const double* db,
                                            const Eigen::Vector3d& point, const Eigen::Vector3d& velocity,
                                            const Eigen::Vector3d& residual, double weight) {
  // With alpha = u.P - v.c (u_j = b_j v) and beta = w.P - r.v (w_j = db_j r), the form is
  // weight (alpha^2 + alpha beta + beta alpha): blocks weight (u_i u_j^T + u_i w_j^T + w_i u_j^T),
  // right-hand side weight (u_i (v.c + r.v) + w_i v.c).
  const double vc = velocity.dot(point), rv = residual.dot(velocity);
  const Eigen::Matrix3d VV = weight * (velocity * velocity.transpose()), VR = weight * (velocity * residual.transpose()),
                        RV = VR.transpose();
  bool consecutive = banded_ && count <= p_ + 1;
  for (int a = 1; a < count && consecutive; ++a) consecutive = index[a] == (index[0] + a) % n_;
  for (int a = 0; a < count; ++a) {
    rhs_[index[a]] += weight * ((b[a] * (vc + rv)) * velocity + (db[a] * vc) * residual);
    Eigen::Matrix3d* row = consecutive ? &blocks_[static_cast<std::size_t>(index[a]) * (2 * p_ + 3) + (p_ + 1 - a)] : nullptr;
    for (int c = 0; c < count; ++c) {
      Eigen::Matrix3d& B = row ? row[c] : block(index[a], index[c]);
      if (dim_ == 2)
        B.topLeftCorner<2, 2>() += (b[a] * b[c]) * VV.topLeftCorner<2, 2>() + (b[a] * db[c]) * VR.topLeftCorner<2, 2>() +
                                   (db[a] * b[c]) * RV.topLeftCorner<2, 2>();
      else
        B += (b[a] * b[c]) * VV + (b[a] * db[c]) * VR + (db[a] * b[c]) * RV;
    }
  }
}

void NormalEquations::add_smoothing(double relative) {
  if (!(relative > 0)) return;
  double data_trace = 0.0;
  for (int i = 0; i < n_; ++i) data_trace += block(i, i).topLeftCorner(dim_, dim_).trace();
  const int rows = closed_ ? n_ : n_ - 2;
  if (rows <= 0 || !(data_trace > 0)) return;
  const double bend_trace = 6.0 * rows * dim_;  // each second difference row contributes 1 + 4 + 1 per coordinate
  const double lambda = relative * data_trace / bend_trace;
  Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int r = 0; r < rows; ++r) {
    const int idx[3] = {closed_ ? (r + n_ - 1) % n_ : r, closed_ ? r : r + 1, closed_ ? (r + 1) % n_ : r + 2};
    const double w[3] = {1.0, -2.0, 1.0};
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) block(idx[a], idx[c]) += (lambda * w[a] * w[c]) * I;
  }
}

std::vector<Eigen::Vector3d> NormalEquations::solve(const std::vector<Eigen::Vector3d>& current,
                                                    const std::vector<int>& fixed) const {
  const int N = n_ * dim_;
  std::vector<char> is_fixed(n_, 0);
  for (int f : fixed) is_fixed[f] = 1;
  double mean_diag = 0.0;
  for (int i = 0; i < n_; ++i) {
    const Eigen::Matrix3d& B = banded_ ? blocks_[static_cast<std::size_t>(i) * (2 * p_ + 3) + p_ + 1]
                                       : blocks_[static_cast<std::size_t>(i) * n_ + i];
    mean_diag += B.topLeftCorner(dim_, dim_).trace();
  }
  mean_diag = std::max(mean_diag / N, 1e-300);
  const double mu = 1e-12 * mean_diag;

  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs(N);
  for (int i = 0; i < n_; ++i)
    for (int a = 0; a < dim_; ++a) rhs[i * dim_ + a] = is_fixed[i] ? current[i][a] : rhs_[i][a] + mu * current[i][a];
  const auto visit = [&](int i, int j, const Eigen::Matrix3d& B) {
    if (is_fixed[i]) return;
    for (int a = 0; a < dim_; ++a)
      for (int c = 0; c < dim_; ++c) {
        if (B(a, c) == 0.0) continue;
        if (is_fixed[j])
          rhs[i * dim_ + a] -= B(a, c) * current[j][c];
        else
          triplets.emplace_back(i * dim_ + a, j * dim_ + c, B(a, c));
      }
  };
  if (banded_) {
    for (int i = 0; i < n_; ++i)
      for (int o = -p_ - 1; o <= p_ + 1; ++o) {
        const int j = i + o;
        if (!closed_ && (j < 0 || j >= n_)) continue;
        visit(i, (j + n_) % n_, blocks_[static_cast<std::size_t>(i) * (2 * p_ + 3) + (o + p_ + 1)]);
      }
  } else {
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) visit(i, j, blocks_[static_cast<std::size_t>(i) * n_ + j]);
  }
  for (int i = 0; i < n_; ++i)
    for (int a = 0; a < dim_; ++a) triplets.emplace_back(i * dim_ + a, i * dim_ + a, is_fixed[i] ? 1.0 : mu);
  Eigen::SparseMatrix<double> A(N, N);
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  Eigen::VectorXd x;
  if (ldlt.info() == Eigen::Success) x = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !x.allFinite()) {
    x = Eigen::MatrixXd(A).colPivHouseholderQr().solve(rhs);
    if (!x.allFinite()) throw GeometryError("active curve step: the linear system is singular");
  }
  std::vector<Eigen::Vector3d> out(n_, Eigen::Vector3d::Zero());
  for (int i = 0; i < n_; ++i)
    for (int a = 0; a < dim_; ++a) out[i][a] = x[i * dim_ + a];
  return out;
}

}  // namespace sculpt::splines::detail
