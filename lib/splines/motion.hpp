#pragma once
/// \file motion.hpp
/// Rigid-body motion design (Pottmann, Leopoldseder & Hofer 2002, sec. 5.3, after Hofer, Pottmann
/// & Ravani): a motion through given poses is designed as a curve in the 12-dimensional space of
/// affine maps x -> A x + b and pulled onto the 6-dimensional manifold of rigid motions as an
/// active curve that minimizes the cubic spline functional (eq. 16) with the poses kept exactly.
///
/// The metric on affine maps is the sum of squared distances of feature points; with the six
/// isotropic feature points o +- s e_i (centroid o, the body's origin) it is 6 |db|^2 + 2 s^2 |dA|_F^2,
/// so the translation and the linear part separate: the translation is the natural cubic spline
/// through the positions, and A(t) is the active curve in R^9 whose distance to the rotations is
/// modelled by the squared distance to the tangent space at the nearest rotation (polar
/// decomposition): |sym(R^T A) - I|_F^2.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "splines/bspline.hpp"

namespace sculpt::splines {

/// A position of the body: x -> rotation * x + position.
struct Pose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
};

/// The nearest rotation to A in the Frobenius norm (polar decomposition by SVD, det = +1).
[[nodiscard]] Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& A);

/// A designed motion: a cubic curve of affine maps, evaluated as the affine map itself or as the
/// nearest rigid motion.
class Motion {
 public:
  /// columns: the curves of A's three columns and of the translation (same knots).
  Motion(std::vector<BSpline> columns, std::vector<double> times);

  /// The affine map (A | b) of the curve at t (t clamped to the domain).
  [[nodiscard]] Eigen::Matrix<double, 3, 4> affine(double t) const;
  /// The rigid motion at t: the nearest rotation to A(t), and b(t). Equal to affine(t) at the poses.
  [[nodiscard]] Eigen::Isometry3d rigid(double t) const;
  /// |A(t)^T A(t) - I|_F: how far the curve is from a rigid motion at t.
  [[nodiscard]] double rigidity(double t) const;
  /// The largest rigidity over `per_segment` samples per knot segment (ends included).
  [[nodiscard]] double max_rigidity(int per_segment = 32) const;
  /// The path of the body's origin (the translation curve).
  [[nodiscard]] const BSpline& path() const { return columns_[3]; }
  /// A's columns (0-2) and the translation (3).
  [[nodiscard]] const std::vector<BSpline>& columns() const { return columns_; }
  /// The poses' times (knots where the poses are met).
  [[nodiscard]] const std::vector<double>& times() const { return times_; }
  [[nodiscard]] std::pair<double, double> domain() const { return columns_[3].domain(); }

 private:
  std::vector<BSpline> columns_;
  std::vector<double> times_;
};

struct MotionOptions {
  std::vector<double> times{};  ///< one per pose, strictly increasing; empty: 0, 1, ..., n - 1
  int splits = 3;               ///< cubic segments per interval between poses (knot insertion)
  int samples = 8;              ///< samples of the rigidity term per segment
  int iterations = 40;          ///< active-curve steps at most
  double penalty = 1e10;        ///< final weight of the rigidity term (dimensionless)
  double tolerance = 1e-10;     ///< stop when no control moves more than this
  /// If positive: while max |A^T A - I|_F exceeds this, run again with more splits (the C2 cubic
  /// space stays O(h^4) off the rotations, h the angle per segment: 3 splits of 75 degrees give
  /// 2e-4). 0: `splits` only. The penalty keeps about 3e-5 even with many splits.
  double rigidity = 5e-5;
  int max_splits = 48;          ///< the most splits `rigidity` may ask for
};

struct MotionResult {
  Motion motion;          ///< the designed motion
  Motion start;           ///< the cubic spline through the poses' affine maps (no rigidity term): the
                          ///< classic "interpolate the poses pointwise, then project" motion is start.rigid(t)
  double max_rigidity = 0.0;  ///< motion.max_rigidity()
  int iterations = 0;     ///< of the last run
  int splits = 0;         ///< segments per interval used
  bool converged = false; ///< the last run met the tolerance at the full penalty
};

/// The motion through `poses` at `times` (sec. 5.3): start from the natural cubic spline through
/// the poses' 12-vectors, split each interval into `splits` segments, then move the curve as an
/// active curve: each step minimizes integral |A''|^2 + penalty * sum |sym(R_k^T A(t_k)) - I|^2
/// (R_k the nearest rotation to the current A(t_k)) with A(t_j) = R_j kept exactly (a KKT system);
/// with `rigidity` set, again with more splits until the curve is that close to rigid.
/// \throw InvalidInput for fewer than 2 poses, a rotation that is not one (|R^T R - I| > 1e-6 or
///        det < 0; smaller errors are projected away), bad times or options.
[[nodiscard]] MotionResult design_motion(const std::vector<Pose>& poses, const MotionOptions& options = {});

/// The rigid motion's squared second derivative integrated over the domain (rotation part in the
/// feature metric with s = `scale`: 2 s^2 |R''|_F^2 + 6 |b''|^2), by central differences and Simpson's
/// rule on `steps` intervals: the energy (eq. 16) of what is actually used.
[[nodiscard]] double rigid_energy(const Motion& motion, double scale = 1.0, int steps = 4000);

struct MotionSampling {
  double tolerance = 0.01;  ///< world units
  int checks = 8;           ///< interior times checked per step
  int max_steps = 100000;
};

/// Times t_0 < ... < t_m over the motion's domain such that moving `body` (points in body
/// coordinates, e.g. a tool's vertices) by straight lines between consecutive rigid poses stays
/// within tolerance / 2 of every point's trajectory at `checks` interior times of every step, and
/// 1/4 |R_i - R_{i+1}|_2 diam(body) <= tolerance / 2 (the most by which the hull of the body's two
/// poses exceeds the set of the straight-line interpolants; see docs/motions.md). Steps are halved
/// from the knot segments until both hold. \throw InvalidInput for an empty body or tolerance <= 0;
/// GeometryError if max_steps would be exceeded.
[[nodiscard]] std::vector<double> sample_motion(const Motion& motion, const std::vector<Eigen::Vector3d>& body,
                                                const MotionSampling& sampling = {});

}  // namespace sculpt::splines
