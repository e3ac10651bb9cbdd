#pragma once
/// \file profiles.hpp
/// The profile curves of Ihm & Naylor 1990, Figure 5 (a goblet and a human profile), and the
/// goblet's cavity and a ball, each a chain of rational Bezier pieces in the (r, z) half-plane
/// (x = r >= 0 is the distance from the z axis, y = z), z non-decreasing along the chain.
///
/// The paper generated its points "from 12 rational Bezier curves in [Piegl 1987], and then slightly
/// disturbed" them. We do not have Piegl's data: these pieces are our own design, G1-continuous
/// cubic (and, for the ball, exact conic) rational Bezier curves. See docs/revolution.md.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "curves/digitized_curve.hpp"
#include "curves/rational_bezier.hpp"

namespace sculpt::curves {

/// A profile design: rational Bezier pieces, each starting where the previous one ends.
struct ProfileDesign {
  std::string name;
  std::vector<RationalBezier> pieces;
};

/// Outer goblet profile (Figure 5, right; Figure 11): 12 pieces from the rim of the foot
/// (r = 3, z = 0) to the lip (r = 3.1, z = 9.6). It does not end on the axis: revolving it gives
/// flat caps at both ends.
ProfileDesign goblet_profile();
/// Inner (cavity) profile of the goblet's bowl: 5 pieces from the axis at z = 5.45 to above the
/// lip (z = 10.2), so that outer minus cavity is an open cup.
ProfileDesign goblet_cavity_profile();
/// Human (face) profile (Figure 5, left; Figure 10): 12 pieces from the neck (r = 1.6, z = 0)
/// over chin, lips, nose and forehead to the crown on the axis (r = 0, z = 7.6).
ProfileDesign human_profile();
/// A half circle of the given radius about (0, z_center), from the south to the north pole:
/// two exact rational quadratic quarter arcs (weights 1, cos 45 deg, 1).
ProfileDesign ball_profile(double radius, double z_center);

struct SampleOptions {
  int points = 237;          ///< n >= 2 points, equally spaced in arc length (paper: goblet 237, human 169)
  double noise = 0.0;        ///< amplitude of the uniform disturbance (same units as the profile)
  std::uint64_t seed = 1;    ///< seed of the disturbance (std::mt19937_64 with a portable mapping)
};

/// Samples a profile densely (like a digitized curve: dimension 2, open, named after the design),
/// then disturbs every point except the two ends by seeded uniform noise: r by up to `noise`, z by
/// up to `noise` but never so much that z stops increasing strictly between samples, so the
/// profile stays monotone in z. The same options give the same points on every platform.
/// \throw InvalidInput if points < 2, noise < 0 or not finite, or the design is empty or not chained
DigitizedCurve sample_profile(const ProfileDesign& design, const SampleOptions& options = {});

/// The (x, y) = (r, z) points of a planar curve, e.g. of linearization_points().
std::vector<Eigen::Vector2d> planar_points(const std::vector<Eigen::Vector3d>& points);

}  // namespace sculpt::curves
