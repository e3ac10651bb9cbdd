#pragma once
/// \file offset.hpp
/// Offsets of planar B-spline curves at a signed distance d (Pottmann, Leopoldseder & Hofer 2002,
/// sec. 3: the target is a known curve, here the exact offset o(t) = c(t) + d n(t), and an active
/// B-spline moves under its squared distance function, with foot points on the target).
///
/// n(t) is the unit normal to the right of the direction of travel, so d > 0 offsets a
/// counter-clockwise closed curve outwards and d < 0 inwards. Where |d| exceeds the radius of
/// curvature on the offset side the raw offset has cusps and a self-intersecting swallowtail (it
/// crosses the medial axis): the pieces of the raw offset closer than |d| to c are cut away, and
/// the fitted curve gets a knot of multiplicity `degree` at each resulting corner.

#include <Eigen/Core>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/fit.hpp"

namespace sculpt::splines {

struct OffsetOptions {
  int controls = 0;          ///< control points of the result; 0 chooses the fewest that meet `tolerance`
  int max_controls = 64;     ///< upper bound of the automatic choice
  int degree = 3;
  double tolerance = 1e-3;   ///< two-sided distance to the exact (trimmed) offset aimed at
  int iterations = 30;       ///< active-curve steps per fit
  int samples = 0;           ///< raw offset samples for trimming and foot point bracketing; 0: 64 per span, >= 2048
};

/// A sharp corner of the trimmed offset (where it crosses the medial axis of c).
struct OffsetCorner {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double parameter = 0.0;  ///< parameter of the result curve (a knot of multiplicity `degree`)
};

struct OffsetResult {
  BSpline curve;
  std::vector<FitIteration> history;  ///< of the last fit (see approximate.hpp)
  double max_error = 0.0;  ///< two-sided: dense samples of each of result and exact offset to the other
  std::vector<OffsetCorner> corners;
};

/// The offset of a planar curve at signed distance d, approximated by a B-spline.
/// \throw InvalidInput for a 3D curve, non-finite d, degree < 1, or too few controls for the
///        corners (each needs degree - 1 extra); GeometryError when the offset changes topology:
///        nothing of it is left (the inner offset vanishes) or it falls into several loops.
[[nodiscard]] OffsetResult offset_curve(const BSpline& curve, double d, const OffsetOptions& options = {});

}  // namespace sculpt::splines
