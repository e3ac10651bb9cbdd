#pragma once
// Helpers shared by the surface-patch tests and benchmark (Ihm & Naylor sec. 5.2): the unit
// sphere and Fig. 9's quartic (Appendix B) as expressions, the corners of their positive-octant
// patches, and checks that use only f (independent of the patch code): normalized residuals and
// the distance of a point from the surface by Newton projection along the gradient.

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "implicit/expression.hpp"

namespace sculpt::implicit::testing {

/// f = x^2 + y^2 + z^2 - 1.
inline Expression unit_sphere() {
  ExpressionBuilder b;
  return b.finish(b.sub(b.add(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)), b.constant(1)));
}

/// Fig. 9's coefficients (Appendix B, item 7):
/// f = A z^4 - B y^2 z^2 - B x^2 z^2 + C z^2 - E y^4 - B x^2 y^2 + G y^2 + A x^4 + C x^2 - H.
struct Fig9 {
  static constexpr double A = 0.01853292, B = 1.14809166, C = 0.99982830, E = 1.16662458, G = 2.1849858,
                          H = 0.72183450;
};

inline Expression fig9_quartic() {
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term x2 = b.pow(x, 2), y2 = b.pow(y, 2), z2 = b.pow(z, 2);
  auto k = [&](double c) { return b.constant(c); };
  Term f = b.mul(k(Fig9::A), b.pow(z, 4));
  f = b.sub(f, b.mul(k(Fig9::B), b.mul(y2, z2)));
  f = b.sub(f, b.mul(k(Fig9::B), b.mul(x2, z2)));
  f = b.add(f, b.mul(k(Fig9::C), z2));
  f = b.sub(f, b.mul(k(Fig9::E), b.pow(y, 4)));
  f = b.sub(f, b.mul(k(Fig9::B), b.mul(x2, y2)));
  f = b.add(f, b.mul(k(Fig9::G), y2));
  f = b.add(f, b.mul(k(Fig9::A), b.pow(x, 4)));
  f = b.add(f, b.mul(k(Fig9::C), x2));
  f = b.sub(f, k(Fig9::H));
  return b.finish(f);
}

/// Where Fig. 9's inner sheet (the one around the origin, f(0) < 0) meets the positive axes:
/// on the x and z axes A t^2 + C t - H = 0, on the y axis E t^2 - G t + H = 0 (t the squared
/// coordinate; the smaller root), solved in the cancellation-free form.
inline std::array<Eigen::Vector3d, 3> fig9_octant_corners() {
  const double xz = std::sqrt(2.0 * Fig9::H / (Fig9::C + std::sqrt(Fig9::C * Fig9::C + 4.0 * Fig9::A * Fig9::H)));
  const double y = std::sqrt(2.0 * Fig9::H / (Fig9::G + std::sqrt(Fig9::G * Fig9::G - 4.0 * Fig9::E * Fig9::H)));
  return {Eigen::Vector3d(xz, 0, 0), Eigen::Vector3d(0, y, 0), Eigen::Vector3d(0, 0, xz)};
}

inline std::array<Eigen::Vector3d, 3> sphere_octant_corners() {
  return {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
}

/// |f(p)| / |grad f(p)|.
inline double normalized_residual(const Expression& f, const Eigen::Vector3d& p) {
  const ValueGradient vg = f.value_gradient(p);
  return std::abs(vg.value) / vg.gradient.norm();
}

/// Distance from p to the surface f = 0 near it: Newton along the gradient (converges to the
/// foot point to first order; for a point within a small fraction of the curvature radius the
/// error is of second order in the distance).
inline double distance_to_surface(const Expression& f, const Eigen::Vector3d& p) {
  Eigen::Vector3d q = p;
  for (int k = 0; k < 50; ++k) {
    const ValueGradient vg = f.value_gradient(q);
    const Eigen::Vector3d step = vg.value / vg.gradient.squaredNorm() * vg.gradient;
    q -= step;
    if (step.norm() <= 1e-15) break;
  }
  return (q - p).norm();
}

}  // namespace sculpt::implicit::testing
