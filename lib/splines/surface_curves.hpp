#pragma once
/// \file surface_curves.hpp
/// Curves on surfaces (Pottmann, Leopoldseder & Hofer 2002, sec. 5): geodesics between two points
/// (sec. 5.1) and interpolating splines on a surface that minimize bending (sec. 5.2, Fig. 14).
/// A surface is given only by its foot point map and unit normal (`Surface`), so this layer needs
/// neither implicit functions nor B-spline surfaces; factories cover the sphere, cylinder, torus
/// and implicit surfaces f = 0 given by value and gradient.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "splines/bspline.hpp"
#include "splines/bspline_surface.hpp"

namespace sculpt::splines {

/// A smooth surface seen through its foot points: what the active-curve steps need (the tangent
/// plane at the foot point is the local quadratic approximant of the squared distance, TDM).
struct Surface {
  std::string name;
  /// The nearest point of the surface to p (one of them where it is not unique).
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> closest_point;
  /// The unit normal at a point of the surface (either orientation).
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> normal;
};

/// \throw InvalidInput for a radius <= 0 or non-finite data.
[[nodiscard]] Surface sphere_surface(const Eigen::Vector3d& center, double radius);
/// Infinite circular cylinder around the line through `point` with direction `axis`.
/// \throw InvalidInput for a zero axis or a radius <= 0.
[[nodiscard]] Surface cylinder_surface(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, double radius);
/// Torus around `axis` through `center`, radius `major` of the centre circle and `minor` of the tube.
/// \throw InvalidInput unless 0 < minor < major and the axis is non-zero.
[[nodiscard]] Surface torus_surface(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double major,
                                    double minor);

struct ImplicitSurfaceOptions {
  int iterations = 50;       ///< Newton and foot point steps at most
  double tolerance = 1e-13;  ///< relative to `scale`: |f| / |grad f| and tangential residual
  double scale = 1.0;        ///< a length of the model (tolerances are relative to it)
};
/// The surface f = 0. The foot point of p: Newton steps along the gradient onto f = 0
/// (x -= f grad f / |grad f|^2), alternated with moving x tangentially towards p until p - x is
/// parallel to grad f(x) (the foot point condition). Converges from points near a regular part of
/// the surface. \throw GeometryError (from closest_point) where the gradient vanishes or it does not converge.
[[nodiscard]] Surface implicit_surface(std::function<double(const Eigen::Vector3d&)> value,
                                       std::function<Eigen::Vector3d(const Eigen::Vector3d&)> gradient,
                                       const ImplicitSurfaceOptions& options = {});

/// A tensor-product B-spline surface as a constraint: exact foot points (bspline_surface.hpp,
/// closest_point; on an open surface a point beyond an edge goes to the edge) and the unit normal
/// there. \throw GeometryError (from normal) where the surface is singular at the foot point.
[[nodiscard]] Surface bspline_surface_constraint(BSplineSurface surface, std::string name = "B-spline surface");

struct GeodesicOptions {
  int segments = 64;         ///< vertices of the discrete geodesic minus one (at least 2)
  int iterations = 500;      ///< tangent steps per refinement level at most
  double tolerance = 1e-12;  ///< stop when no vertex moves more than this times the length
};

struct GeodesicResult {
  BSpline curve;                        ///< cubic, over [0, 1], interpolating `polygon` at i / segments: constant speed
  std::vector<Eigen::Vector3d> polygon; ///< the discrete geodesic: vertices on the surface, equal edges
  double length = 0.0;                  ///< of `curve` (Gauss quadrature)
  double polygon_length = 0.0;
  double max_distance = 0.0;            ///< of `curve` from the surface, sampled 16 times per segment
  int iterations = 0;                   ///< tangent steps, all levels
  bool converged = false;
};

/// A shortest path from p to q on the surface (both first moved to their foot points).
/// Sec. 5.1: the energy sum |p_{i+1} - p_i|^2 of a polygon (the discrete eq. 15, whose minimizers
/// are geodesics with constant speed) is minimized with the vertices on the surface, starting from
/// the straight segment projected onto it: each step solves the linearized problem with every
/// vertex moving in its tangent plane, then projects (the seed's "rope" refinement), halving the
/// step if the energy would grow; coarse to fine (8, 16, ... segments). The result is a local
/// minimum: near a cut locus (antipodal points on the sphere) the path found is one of several.
/// Vertices lie on the sphere's great circle and the cylinder's helix exactly (symmetry); on
/// general surfaces they are O(h^2) from the smooth geodesic (h the edge length).
/// \throw InvalidInput for fewer than 2 segments or non-finite points.
[[nodiscard]] GeodesicResult geodesic(const Surface& surface, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                      const GeodesicOptions& options = {});

struct SurfaceSplineOptions {
  int splits = 3;            ///< cubic segments per span between consecutive points (Fig. 14: 3)
  int samples = 8;           ///< foot-point samples per segment
  int iterations = 40;       ///< active-curve steps at most
  double penalty = 1e11;     ///< final weight of the distance term (dimensionless, see surface_curves.cpp)
  double tolerance = 1e-9;   ///< stop when no control point moves more than this times the length
  /// If positive: while the curve is farther than this from the surface, run again with more
  /// splits (the C2 cubic space stays O(h^4) off a curved surface; with 3 splits of spans of 1.1
  /// on a sphere of radius 1.3 that is 8e-5, of spans of 1.5 2e-4). 0: `splits` only.
  double distance = 0.0;
  int max_splits = 24;       ///< the most splits `distance` may ask for
};

struct SurfaceSplineResult {
  BSpline curve;                   ///< cubic, parameter = cumulative chord length, through the points
  BSpline start;                   ///< the natural cubic spline through the points (same parameters)
  std::vector<double> parameters;  ///< of the given points on `curve`
  double max_distance = 0.0;       ///< of `curve` from the surface, sampled 16 times per segment
  double bending = 0.0;            ///< integral |c''|^2 over the domain
  int iterations = 0;              ///< of the last run
  int splits = 0;                  ///< segments per span used
  bool converged = false;          ///< the last run met the tolerance at the full penalty
};

/// A cubic spline through `points` (moved to their foot points first) lying close to the surface
/// and minimizing the bending energy integral |c''|^2 (eq. 16): the natural cubic spline through
/// the points, each span split into `splits` segments by knot insertion, moved as an active curve
/// (eq. 13) whose distance term is the squared distance of sample points to the tangent planes at
/// their foot points, with the interpolation conditions kept exactly (a KKT system per step).
/// \throw InvalidInput for fewer than 2 points, repeated consecutive points, or bad options.
[[nodiscard]] SurfaceSplineResult surface_spline(const Surface& surface, const std::vector<Eigen::Vector3d>& points,
                                                 const SurfaceSplineOptions& options = {});

/// Integral of |c''|^2 over the curve's domain (Gauss quadrature per knot span).
[[nodiscard]] double bending_energy(const BSpline& curve);
/// Arc length of the curve (Gauss quadrature, 8 points per knot span).
[[nodiscard]] double curve_length(const BSpline& curve);

}  // namespace sculpt::splines
