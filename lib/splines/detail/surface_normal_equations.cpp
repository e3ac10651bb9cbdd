#include "splines/detail/surface_normal_equations.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

#include "base/errors.hpp"

namespace sculpt::splines::detail {

namespace {

// Gauss-Legendre nodes and weights on [0, 1] (Golub-Welsch: eigenvalues of the Jacobi matrix).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int i = 1; i < n; ++i) J(i, i - 1) = J(i - 1, i) = i / std::sqrt(4.0 * i * i - 1.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(J);
  nodes.resize(n);
  weights.resize(n);
  for (int i = 0; i < n; ++i) {
    nodes[i] = 0.5 * (es.eigenvalues()[i] + 1.0);
    weights[i] = es.eigenvectors()(0, i) * es.eigenvectors()(0, i);  // 2 v0^2 on [-1, 1], halved on [0, 1]
  }
}

}  // namespace

SurfaceNormalEquations::SurfaceNormalEquations(const BSplineSurface& surface)
    : surface_(&surface),
      nu_(surface.count(0)),
      nv_(surface.count(1)),
      p_(surface.degree(0)),
      q_(surface.degree(1)),
      width_(static_cast<std::size_t>((2 * p_ + 1) * (2 * q_ + 1))) {
  blocks_.assign(static_cast<std::size_t>(nu_) * nv_ * width_, Eigen::Matrix3d::Zero());
  rhs_.assign(static_cast<std::size_t>(nu_) * nv_, Eigen::Vector3d::Zero());
}

void SurfaceNormalEquations::add_quadratic(const BasisJet& bu, const BasisJet& bv, const double* w, const Eigen::Matrix3d& M,
                                           std::vector<Eigen::Matrix3d>& blocks) const {
  // Block (a b, a' b') sits at the slot of control (a, b) with offset (a' - a, b' - b): the
  // offsets come from the positions in the basis, so closed directions need no wrapping here.
  for (int a = 0; a < bu.count; ++a)
    for (int b = 0; b < bv.count; ++b) {
      const double wab = w[a * bv.count + b];
      if (wab == 0.0) continue;
      const int c = bu.index[a] * nv_ + bv.index[b];
      Eigen::Matrix3d* base = &blocks[slot(c, -a, -b)];
      for (int a2 = 0; a2 < bu.count; ++a2) {
        Eigen::Matrix3d* row = base + static_cast<std::ptrdiff_t>(a2) * (2 * q_ + 1);
        for (int b2 = 0; b2 < bv.count; ++b2) row[b2].noalias() += (wab * w[a2 * bv.count + b2]) * M;
      }
    }
}

void SurfaceNormalEquations::add_term(const BasisJet& bu, const BasisJet& bv, const Eigen::Matrix3d& M, const Eigen::Vector3d& x) {
  double w[(kMaxFastDegree + 1) * (kMaxFastDegree + 1)];
  for (int a = 0; a < bu.count; ++a)
    for (int b = 0; b < bv.count; ++b) w[a * bv.count + b] = bu.value[0][a] * bv.value[0][b];
  const Eigen::Vector3d Mx = M * x;
  for (int a = 0; a < bu.count; ++a)
    for (int b = 0; b < bv.count; ++b) rhs_[bu.index[a] * nv_ + bv.index[b]] += w[a * bv.count + b] * Mx;
  add_quadratic(bu, bv, w, M, blocks_);
}

void SurfaceNormalEquations::add_smoothing(double relative) {
  if (!(relative > 0)) return;
  std::vector<Eigen::Matrix3d> energy(blocks_.size(), Eigen::Matrix3d::Zero());
  const BSplineSurface& s = *surface_;
  std::vector<double> gu, wu, gv, wv;
  gauss_legendre(p_ + 1, gu, wu);
  gauss_legendre(q_ + 1, gv, wv);
  const std::vector<double> bu = s.breaks(0), bv = s.breaks(1);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  double w[(kMaxFastDegree + 1) * (kMaxFastDegree + 1)];
  for (std::size_t i = 0; i + 1 < bu.size(); ++i)
    for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
      const double hu = bu[i + 1] - bu[i], hv = bv[j + 1] - bv[j];
      for (int gi = 0; gi <= p_; ++gi)
        for (int gj = 0; gj <= q_; ++gj) {
          const BasisJet ju = s.basis(0).basis_jet(bu[i] + hu * gu[gi], 2), jv = s.basis(1).basis_jet(bv[j] + hv * gv[gj], 2);
          const double weight = wu[gi] * wv[gj] * hu * hv;
          // |S_uu|^2 + 2 |S_uv|^2 + |S_vv|^2: three rank-one forms in the controls, each times I.
          const int derivative[3][2] = {{2, 0}, {1, 1}, {0, 2}};
          const double factor[3] = {1.0, 2.0, 1.0};
          for (int t = 0; t < 3; ++t) {
            for (int a = 0; a < ju.count; ++a)
              for (int b = 0; b < jv.count; ++b)
                w[a * jv.count + b] = ju.value[derivative[t][0]][a] * jv.value[derivative[t][1]][b];
            add_quadratic(ju, jv, w, (factor[t] * weight) * I, energy);
          }
        }
    }
  double data_trace = 0.0, energy_trace = 0.0;
  for (int c = 0; c < nu_ * nv_; ++c) {
    data_trace += blocks_[slot(c, 0, 0)].trace();
    energy_trace += energy[slot(c, 0, 0)].trace();
  }
  if (!(data_trace > 0) || !(energy_trace > 0)) return;
  const double lambda = relative * data_trace / energy_trace;
  for (std::size_t k = 0; k < blocks_.size(); ++k) blocks_[k] += lambda * energy[k];
}

std::vector<Eigen::Vector3d> SurfaceNormalEquations::solve(const std::vector<Eigen::Vector3d>& current,
                                                           const std::vector<int>& fixed) const {
  const int n = nu_ * nv_, N = 3 * n;
  std::vector<char> is_fixed(n, 0);
  for (int f : fixed) is_fixed[f] = 1;
  double mean_diag = 0.0;
  for (int c = 0; c < n; ++c) mean_diag += blocks_[slot(c, 0, 0)].trace();
  mean_diag = std::max(mean_diag / N, 1e-300);
  const double mu = 1e-12 * mean_diag;
  Eigen::VectorXd rhs(N);
  for (int c = 0; c < n; ++c)
    for (int a = 0; a < 3; ++a) rhs[3 * c + a] = is_fixed[c] ? current[c][a] : rhs_[c][a] + mu * current[c][a];
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(n) * width_ * 9);
  const bool closed_u = surface_->closed(0), closed_v = surface_->closed(1);
  for (int i = 0; i < nu_; ++i)
    for (int j = 0; j < nv_; ++j) {
      const int c = i * nv_ + j;
      if (is_fixed[c]) continue;
      for (int di = -p_; di <= p_; ++di)
        for (int dj = -q_; dj <= q_; ++dj) {
          int i2 = i + di, j2 = j + dj;
          if (closed_u) i2 = ((i2 % nu_) + nu_) % nu_;
          if (closed_v) j2 = ((j2 % nv_) + nv_) % nv_;
          if (i2 < 0 || i2 >= nu_ || j2 < 0 || j2 >= nv_) continue;
          const Eigen::Matrix3d& B = blocks_[slot(c, di, dj)];
          const int c2 = i2 * nv_ + j2;
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
              if (B(a, b) == 0.0) continue;
              if (is_fixed[c2])
                rhs[3 * c + a] -= B(a, b) * current[c2][b];
              else
                triplets.emplace_back(3 * c + a, 3 * c2 + b, B(a, b));
            }
        }
    }
  for (int c = 0; c < n; ++c)
    for (int a = 0; a < 3; ++a) triplets.emplace_back(3 * c + a, 3 * c + a, is_fixed[c] ? 1.0 : mu);
  Eigen::SparseMatrix<double> A(N, N);
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  Eigen::VectorXd x;
  if (ldlt.info() == Eigen::Success) x = ldlt.solve(rhs);
  if (ldlt.info() != Eigen::Success || !x.allFinite()) {
    if (N > 3000) throw GeometryError("active surface step: the linear system is singular");
    x = Eigen::MatrixXd(A).colPivHouseholderQr().solve(rhs);
    if (!x.allFinite()) throw GeometryError("active surface step: the linear system is singular");
  }
  std::vector<Eigen::Vector3d> out(n);
  for (int c = 0; c < n; ++c) out[c] = x.segment<3>(3 * c);
  return out;
}

}  // namespace sculpt::splines::detail
