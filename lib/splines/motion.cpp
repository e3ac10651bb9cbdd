#include "splines/motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "splines/detail/constrained_spline.hpp"

namespace sculpt::splines {
namespace {

using V = Eigen::Vector3d;
using M3 = Eigen::Matrix3d;

/// A (3x3) as the 9-vector of its entries, row-major: entry (r, c) at 3 r + c.
Eigen::VectorXd flatten(const M3& A) {
  Eigen::VectorXd v(9);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v(3 * r + c) = A(r, c);
  return v;
}

M3 unflatten(const Eigen::VectorXd& v) {
  M3 A;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) A(r, c) = v(3 * r + c);
  return A;
}

/// The four column curves of (A | b) from the rotation controls (9 per row) and translation controls.
std::vector<BSpline> columns_of(const std::vector<double>& knots, const Eigen::MatrixXd& A, const Eigen::MatrixXd& b) {
  std::vector<BSpline> out;
  for (int c = 0; c < 4; ++c) {
    std::vector<V> controls(static_cast<std::size_t>(A.rows()));
    for (Eigen::Index i = 0; i < A.rows(); ++i)
      controls[static_cast<std::size_t>(i)] = c < 3 ? V(A(i, c), A(i, 3 + c), A(i, 6 + c)) : V(b.row(i).transpose());
    out.emplace_back(3, knots, std::move(controls), false, 3);
  }
  return out;
}

/// The 6 x 9 map A -> sym(R^T A) (upper triangle, off-diagonal entries times sqrt 2, so its squared
/// norm is the Frobenius norm of the symmetric part): the normal component of A - R at the rotation R.
Eigen::Matrix<double, 6, 9> symmetric_part(const M3& R) {
  Eigen::Matrix<double, 6, 9> L = Eigen::Matrix<double, 6, 9>::Zero();
  int row = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b, ++row) {
      const double f = a == b ? 1.0 : std::sqrt(0.5);  // sqrt(2) * 1/2 off the diagonal
      for (int c = 0; c < 3; ++c) {
        L(row, 3 * c + b) += f * R(c, a);
        if (a != b) L(row, 3 * c + a) += f * R(c, b);
      }
    }
  return L;
}

Eigen::Matrix<double, 6, 1> identity_part() {
  Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
  r(0) = r(3) = r(5) = 1.0;  // rows (0,0), (1,1), (2,2) in the order of symmetric_part
  return r;
}

}  // namespace

M3 nearest_rotation(const M3& A) {
  const Eigen::JacobiSVD<M3> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  M3 D = M3::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

Motion::Motion(std::vector<BSpline> columns, std::vector<double> times)
    : columns_(std::move(columns)), times_(std::move(times)) {
  if (columns_.size() != 4) throw InvalidInput("a motion has four column curves");
}

Eigen::Matrix<double, 3, 4> Motion::affine(double t) const {
  Eigen::Matrix<double, 3, 4> m;
  for (int c = 0; c < 4; ++c) m.col(c) = columns_[static_cast<std::size_t>(c)].point(t);
  return m;
}

Eigen::Isometry3d Motion::rigid(double t) const {
  const Eigen::Matrix<double, 3, 4> m = affine(t);
  Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
  iso.linear() = nearest_rotation(m.leftCols<3>());
  iso.translation() = m.col(3);
  return iso;
}

double Motion::rigidity(double t) const {
  const M3 A = affine(t).leftCols<3>();
  return (A.transpose() * A - M3::Identity()).norm();
}

double Motion::max_rigidity(int per_segment) const {
  const std::vector<double> br = columns_[3].breaks();
  double worst = 0.0;
  for (std::size_t s = 0; s + 1 < br.size(); ++s)
    for (int k = 0; k <= per_segment; ++k) worst = std::max(worst, rigidity(br[s] + (br[s + 1] - br[s]) * k / per_segment));
  return worst;
}

namespace {

MotionResult design_motion_run(const std::vector<Pose>& poses, const MotionOptions& options) {
  const std::size_t n = poses.size();
  if (n < 2) throw InvalidInput("motion: at least two poses");
  if (options.splits < 1 || options.samples < 1 || options.iterations < 0 || !(options.penalty > 0.0) ||
      !(options.tolerance > 0.0))
    throw InvalidInput("motion: splits, samples, penalty and tolerance must be positive");
  std::vector<double> times = options.times;
  if (times.empty())
    for (std::size_t j = 0; j < n; ++j) times.push_back(static_cast<double>(j));
  if (times.size() != n) throw InvalidInput("motion: one time per pose");
  std::vector<M3> R(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Pose& p = poses[j];
    if (!p.rotation.allFinite() || !p.position.allFinite()) throw InvalidInput("motion: a pose is not finite");
    if ((p.rotation.transpose() * p.rotation - M3::Identity()).norm() > 1e-6 || p.rotation.determinant() < 0.0)
      throw InvalidInput("motion: pose " + std::to_string(j + 1) + " has a matrix that is not a rotation");
    R[j] = nearest_rotation(p.rotation);
  }
  const std::vector<double> knots = detail::refined_knots(times, options.splits);
  const double T = times.back() - times.front();
  // Translation: the natural cubic spline (the refined space contains it, and nothing else acts on b).
  detail::ConstrainedSpline move(knots, 3);
  for (std::size_t j = 0; j < n; ++j) move.add_constraint(times[j], poses[j].position);
  move.add_bending(1.0);
  const Eigen::MatrixXd B = move.solve();
  // Linear part: the active curve in R^9.
  detail::ConstrainedSpline turn(knots, 9);
  for (std::size_t j = 0; j < n; ++j) turn.add_constraint(times[j], flatten(R[j]));
  turn.add_bending(1.0);
  Eigen::MatrixXd A = turn.solve();
  const std::vector<BSpline> start_columns = columns_of(knots, A, B);
  std::vector<double> ts;
  for (std::size_t s = 3; s + 4 < knots.size(); ++s)
    for (int k = 0; k < options.samples; ++k) ts.push_back(knots[s] + (knots[s + 1] - knots[s]) * (k + 0.5) / options.samples);
  const double quad = T / static_cast<double>(ts.size());
  const Eigen::Matrix<double, 6, 1> I6 = identity_part();
  double beta = std::min(1e2, options.penalty);
  int iterations = 0;
  bool converged = false;
  for (int it = 0; it < options.iterations; ++it) {
    turn.clear_terms();
    turn.add_bending(1.0);
    const double w = std::sqrt(beta * quad / std::pow(T, 4));
    for (double t : ts) {
      const M3 Rk = nearest_rotation(unflatten(turn.evaluate(A, t)));
      turn.add_term(t, w * symmetric_part(Rk), w * I6);
    }
    // End condition: the curve's natural ends (A'' = 0 with A' free) let it leave the rotations
    // near the ends; keeping A'(t) tangent to the rotations there, sym(R^T A') = 0 (for a rigid
    // R(t), R^T R' is skew), removes most of that. Only the angular velocity stays free.
    // (Also imposing the rigid second-order condition sym(R^T A'') = R^T W^2 R, linearized in the
    // angular velocity W, made the steps converge far more slowly: not used.)
    if (it == 0)
      for (const std::size_t j : {std::size_t{0}, n - 1}) turn.add_constraint(times[j], symmetric_part(R[j]), Eigen::VectorXd::Zero(6), 1);
    const Eigen::MatrixXd next = turn.solve(&A);
    const double change = (next - A).cwiseAbs().maxCoeff();
    A = next;
    iterations = it + 1;
    if (beta >= options.penalty && change <= options.tolerance) {
      converged = true;
      break;
    }
    beta = std::min(beta * 100.0, options.penalty);
  }
  MotionResult result{.motion = Motion(columns_of(knots, A, B), times),
                      .start = Motion(start_columns, times),
                      .max_rigidity = 0.0,
                      .iterations = iterations,
                      .splits = 0,
                      .converged = converged};
  result.max_rigidity = result.motion.max_rigidity();
  result.splits = options.splits;
  return result;
}

}  // namespace

MotionResult design_motion(const std::vector<Pose>& poses, const MotionOptions& options) {
  if (!(options.rigidity >= 0.0) || options.max_splits < options.splits)
    throw InvalidInput("motion: rigidity must be >= 0 and max_splits >= splits");
  MotionOptions run = options;
  MotionResult result = design_motion_run(poses, run);
  // The C2 cubic space stays O(h^4) off the rotations (h the angle turned per segment): split
  // finer, guided by that order, until the rigidity is met.
  while (options.rigidity > 0.0 && result.max_rigidity > options.rigidity && run.splits < options.max_splits) {
    const double factor = std::pow(result.max_rigidity / options.rigidity, 0.25) * 1.1;
    run.splits = std::min(options.max_splits, std::max(run.splits + 1, static_cast<int>(std::ceil(run.splits * factor))));
    result = design_motion_run(poses, run);
  }
  return result;
}

double rigid_energy(const Motion& motion, double scale, int steps) {
  // Not a structured binding: the lambda below captures a and b (clang 14 cannot capture bindings).
  const double a = motion.domain().first, b = motion.domain().second;
  steps += steps % 2;
  const double h = 1e-4 * (b - a);
  auto accel = [&](double t) {
    t = std::clamp(t, a + h, b - h);
    const Eigen::Matrix4d m = motion.rigid(t + h).matrix() - 2.0 * motion.rigid(t).matrix() + motion.rigid(t - h).matrix();
    const Eigen::Matrix4d d = m / (h * h);
    return 2.0 * scale * scale * d.topLeftCorner<3, 3>().squaredNorm() + 6.0 * d.topRightCorner<3, 1>().squaredNorm();
  };
  double sum = 0.0;
  for (int k = 0; k <= steps; ++k) sum += (k == 0 || k == steps ? 1 : (k % 2 ? 4 : 2)) * accel(a + (b - a) * k / steps);
  return sum * (b - a) / steps / 3.0;
}

std::vector<double> sample_motion(const Motion& motion, const std::vector<Eigen::Vector3d>& body,
                                  const MotionSampling& sampling) {
  if (body.empty()) throw InvalidInput("sample_motion: the body has no points");
  if (!(sampling.tolerance > 0.0) || sampling.checks < 1 || sampling.max_steps < 1)
    throw InvalidInput("sample_motion: tolerance and checks must be positive");
  V centre = V::Zero();
  for (const V& v : body) centre += v;
  centre /= static_cast<double>(body.size());
  double diam = 0.0;
  for (const V& v : body) diam = std::max(diam, 2.0 * (v - centre).norm());
  const double half = 0.5 * sampling.tolerance;
  // True when the step [t0, t1] needs no split.
  auto fine = [&](double t0, double t1) {
    const Eigen::Isometry3d P0 = motion.rigid(t0), P1 = motion.rigid(t1);
    const double spread = 0.25 * (P0.linear() - P1.linear()).jacobiSvd().singularValues()(0) * diam;
    if (spread > half) return false;
    for (int k = 1; k <= sampling.checks; ++k) {
      const double s = double(k) / (sampling.checks + 1);
      const Eigen::Isometry3d Pt = motion.rigid(t0 + (t1 - t0) * s);
      for (const V& v : body)
        if ((Pt * v - ((1.0 - s) * (P0 * v) + s * (P1 * v))).norm() > half) return false;
    }
    return true;
  };
  const std::vector<double> br = motion.path().breaks();
  std::vector<double> times{br.front()};
  std::vector<std::pair<double, double>> stack;  // explicit stack: no recursion on user input
  for (std::size_t s = br.size() - 1; s > 0; --s) stack.emplace_back(br[s - 1], br[s]);
  while (!stack.empty()) {
    const auto [t0, t1] = stack.back();
    stack.pop_back();
    if (fine(t0, t1) || t1 - t0 <= 1e-12 * (br.back() - br.front())) {
      times.push_back(t1);
      if (static_cast<int>(times.size()) > sampling.max_steps + 1)
        throw GeometryError("sample_motion: more than " + std::to_string(sampling.max_steps) +
                            " steps would be needed for this tolerance");
      continue;
    }
    const double mid = 0.5 * (t0 + t1);
    stack.emplace_back(mid, t1);
    stack.emplace_back(t0, mid);
  }
  return times;
}

}  // namespace sculpt::splines
