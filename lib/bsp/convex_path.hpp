#pragma once
/// \file path_polygon.hpp
/// Convex paths of revolution (Ihm & Naylor 1990, section 6: "the revolution of the curve need not
/// be along a circle, but can be any convex path"): a strictly convex polygon, counter-clockwise,
/// around the z axis. A profile point (r, z) and a path vertex (u, v) give the point (r u, r v, z).

#include <string>
#include <vector>

#include <Eigen/Core>

namespace sculpt {

/// A strictly convex polygon, vertices counter-clockwise. Build it with the functions below,
/// which validate it; the vertex list is then never empty.
struct ConvexPath {
  std::vector<Eigen::Vector2d> vertices;
  [[nodiscard]] int edges() const { return static_cast<int>(vertices.size()); }
  [[nodiscard]] double area() const;  ///< shoelace area (> 0)
};

/// The regular n-gon inscribed in the circle of radius r, first vertex at (r, 0).
/// \pre n >= 3, r finite and > 0   \throw InvalidInput
ConvexPath circular_path(int n, double radius = 1.0);
/// The n-gon inscribed in the ellipse x^2/a^2 + y^2/b^2 = 1, vertex k at (a cos 2pi k/n, b sin 2pi k/n).
/// \pre n >= 3, a, b finite and > 0   \throw InvalidInput
ConvexPath ellipse_path(double a, double b, int n);
/// Any strictly convex polygon by its vertices, in either orientation (clockwise is reversed).
/// Convexity is checked exactly (orientation signs by mesh/predicates.hpp): every turn
/// strictly left and the boundary winding once.
/// \throw InvalidInput naming the offending vertex (repeated, collinear, reflex, self-overlapping)
ConvexPath polygon_path(std::vector<Eigen::Vector2d> vertices);


}  // namespace sculpt
