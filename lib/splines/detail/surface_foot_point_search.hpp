#pragma once
/// \file surface_foot_point_search.hpp
/// The foot point machinery behind closest_point(BSplineSurface, x), shared with the surface fitter.
/// Per knot span: the box of the span's (p + 1) x (q + 1) control points, which holds the span's
/// piece of the surface (convex hull property), and a small grid of samples. The global search
/// visits spans in the order of their box distance and stops once a box is farther than the best
/// point found; in each visited span Newton on (u, v) starts from every local minimum of the distance
/// over the span's samples and is clamped to the span. The warm start (fitting) runs Newton from a previous parameter pair, then
/// searches every span whose box is closer than that result and whose nearest sample, less half the
/// span's largest sample-cell diagonal, is too (a surface point of the span is taken to lie within
/// half a cell diagonal of a sample: an estimate, not a bound).

#include <Eigen/Core>
#include <vector>

#include "splines/bspline_surface.hpp"

namespace sculpt::splines::detail {

/// Samples per span and direction (the span's grid has (k + 1)^2 points).
inline constexpr int kSurfaceSamplesPerSpan = 8;
inline constexpr int kMaxSamplesPerSpan = 8;

struct SurfaceFootJet {
  SurfaceFootPoint foot;
  SurfaceJet jet;  ///< derivatives up to second order at the foot point
};

class SurfaceFootPointSearch {
 public:
  explicit SurfaceFootPointSearch(const BSplineSurface& surface, int samples_per_span = kSurfaceSamplesPerSpan);
  [[nodiscard]] SurfaceFootJet global(const Eigen::Vector3d& x) const;
  [[nodiscard]] SurfaceFootJet warm(const Eigen::Vector3d& x, double u0, double v0) const;
  /// The foot point on the boundary curve where parameter `direction` (0: u, 1: v) equals `at`
  /// (an end of an open direction), by Newton along the curve from the other parameter t0.
  [[nodiscard]] SurfaceFootJet along_edge(const Eigen::Vector3d& x, int direction, double at, double t0) const;

 private:
  struct Span {
    double u0, u1, v0, v1;
    Eigen::Vector3d lo, hi;  // box of the span's control points
    int first_sample;        // into samples_ / sample_uv_
    double reach = 0.0;      // largest diagonal of the span's sample cells
  };
  /// Projected Newton for |S(u, v) - x|^2 on [u0, u1] x [v0, v1]; closed directions wrap instead
  /// of clamping when `wrap` (the warm start over the whole domain).
  [[nodiscard]] SurfaceFootJet newton(const Eigen::Vector3d& x, double u, double v, double u0, double u1, double v0,
                                      double v1, bool wrap) const;
  [[nodiscard]] SurfaceFootJet search_span(const Eigen::Vector3d& x, const Span& s) const;
  const BSplineSurface* surface_;
  int k_;
  std::vector<Span> spans_;
  std::vector<Eigen::Vector3d> samples_;
  std::vector<Eigen::Vector2d> sample_uv_;
};

}  // namespace sculpt::splines::detail
