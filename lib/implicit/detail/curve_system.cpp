#include "implicit/detail/curve_system.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace sculpt::implicit::detail {

using Vec = Eigen::Vector3d;

Vec CurvePoint::tangent(const Vec& direction) const {
  const double n = cross.norm();
  if (!(n > 0.0)) return Vec::Zero();
  const Vec t = cross / n;
  return t.dot(direction) < 0.0 ? Vec(-t) : t;
}

CurvePoint CurveSystem::eval(const Vec& p) const {
  ++evaluations_;
  const ValueGradient a = f_.value_gradient(p), b = g_.value_gradient(p);
  CurvePoint c;
  c.p = p;
  c.f = a.value;
  c.g = b.value;
  c.grad_f = a.gradient;
  c.grad_g = b.gradient;
  c.cross = a.gradient.cross(b.gradient);
  // A zero residual counts even where the gradient vanishes (the node of Fig. 8's sextic).
  c.on_curve = std::abs(a.value) <= target_ * a.gradient.norm() && std::abs(b.value) <= target_ * b.gradient.norm();
  return c;
}

std::optional<CurvePoint> CurveSystem::project(const Vec& start, double max_move, int max_iterations) const {
  Vec q = start;
  for (int k = 0; k <= max_iterations; ++k) {
    const CurvePoint c = eval(q);
    if (c.on_curve) return c;
    if (k == max_iterations) break;
    Eigen::Matrix<double, 2, 3> J;
    J.row(0) = c.grad_f.transpose();
    J.row(1) = c.grad_g.transpose();
    // Pseudo-inverse: the smallest correction that zeroes the linearization (rank 1 near a
    // singular point, where the two gradients are parallel).
    Eigen::JacobiSVD<Eigen::Matrix<double, 2, 3>> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    svd.setThreshold(1e-12);
    const Vec delta = -svd.solve(Eigen::Vector2d(c.f, c.g));
    if (!delta.allFinite()) return std::nullopt;
    q += delta;
    if ((q - start).norm() > max_move) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<CurvePoint> CurveSystem::project_on_plane(const Vec& start, const Vec& normal, double max_move,
                                                        int max_iterations) const {
  Vec q = start;
  for (int k = 0; k <= max_iterations; ++k) {
    const CurvePoint c = eval(q);
    const double plane = normal.dot(q - start);
    if (c.on_curve && std::abs(plane) <= 1e-9 * max_move) return c;
    if (k == max_iterations) break;
    Eigen::Matrix3d A;
    A.row(0) = c.grad_f.transpose();
    A.row(1) = c.grad_g.transpose();
    A.row(2) = normal.transpose();
    const double scale = c.grad_f.norm() * c.grad_g.norm() * normal.norm();
    if (!(std::abs(A.determinant()) > 1e-10 * scale)) return std::nullopt;
    const Vec delta = A.partialPivLu().solve(Vec(-c.f, -c.g, -plane));
    if (!delta.allFinite()) return std::nullopt;
    q += delta;
    if ((q - start).norm() > max_move) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<CurvePoint> CurveSystem::locate_singular(const Vec& start, double max_move) const {
  Vec q = start;
  const CurvePoint first = eval(start);
  // Row scales fixed at the start, so that the three kinds of equation weigh alike.
  const double sf = 1.0 / std::max(first.grad_f.norm(), 1e-300), sg = 1.0 / std::max(first.grad_g.norm(), 1e-300);
  const double sc = sf * sg;
  const double step = 1e-7 * std::max(max_move, 1e-300);
  std::optional<CurvePoint> best;
  for (int k = 0; k < 30; ++k) {
    const CurvePoint c = k == 0 ? first : eval(q);
    Eigen::Matrix<double, 5, 3> J;
    Eigen::Matrix<double, 5, 1> F;
    J.row(0) = sf * c.grad_f.transpose();
    J.row(1) = sg * c.grad_g.transpose();
    F << sf * c.f, sg * c.g, sc * c.cross;
    for (int axis = 0; axis < 3; ++axis) {
      const Vec h = step * Vec::Unit(axis);
      J.block<3, 1>(2, axis) = sc * (eval(q + h).cross - eval(q - h).cross) / (2.0 * step);
    }
    if (c.on_curve && (!best || c.mu() < best->mu())) best = c;
    const Vec delta = J.colPivHouseholderQr().solve(-F);
    if (!delta.allFinite()) break;
    q += delta;
    if ((q - start).norm() > max_move) break;
    if (delta.norm() <= 1e-14 * max_move) {
      const CurvePoint e = eval(q);
      if (e.on_curve && (!best || e.mu() <= best->mu())) best = e;
      break;
    }
  }
  return best;
}

}  // namespace sculpt::implicit::detail
