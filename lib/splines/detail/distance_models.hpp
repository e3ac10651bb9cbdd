#pragma once
/// \file distance_models.hpp
/// Hessians M of the local quadratic models of the squared distance to a curve at a point p whose
/// normal foot point f has unit tangent T and curvature vector kN (Pottmann & Hofer; Pottmann,
/// Leopoldseder & Hofer 2002, sec. 2, eq. 4; Wang, Pottmann & Liu 2006, sec. 3-4):
///     F(x) ~ c ((x - f).T)^2 + |(x - f) - ((x - f).T) T|^2,    c = d / (d - rho)
/// with d the signed distance of p along the principal normal (towards the curvature centre) and
/// rho the radius of curvature, i.e. c = dk / (dk - 1) with dk = (p - f).kN. In 3D the same
/// formula holds with d measured along the principal normal (the normal plane term is isotropic).
/// For 0 <= dk < 1 (p between the curve and its curvature centre) c < 0 and the model is not
/// convex; SDM then truncates c to 0, the tangent distance model (WPL 2006, eq. 8).
///   SDM: c as above (truncated);  TDM: c = 0;  PDM: M = I (the squared distance to f itself).

#include <Eigen/Core>

namespace sculpt::splines::detail {

enum class Model { SDM, PDM, TDM };

/// `at_end`: f is an end point of an open curve, where the distance is the point distance (M = I).
inline Eigen::Matrix3d distance_hessian(Model model, const Eigen::Vector3d& p, const Eigen::Vector3d& f,
                                        const Eigen::Vector3d& velocity, const Eigen::Vector3d& acceleration,
                                        bool at_end) {
  const double speed2 = velocity.squaredNorm();
  if (model == Model::PDM || at_end || !(speed2 > 1e-300)) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d T = velocity / std::sqrt(speed2);
  const Eigen::Matrix3d TT = T * T.transpose();
  double c = 0.0;
  if (model == Model::SDM) {
    const Eigen::Vector3d kN = (acceleration - acceleration.dot(T) * T) / speed2;
    const double dk = (p - f).dot(kN);
    if (dk < 0) c = dk / (dk - 1.0);
  }
  return c * TT + (Eigen::Matrix3d::Identity() - TT);
}

}  // namespace sculpt::splines::detail
