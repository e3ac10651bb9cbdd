#pragma once
/// \file plot.hpp
/// SVG figures of curves in the manner of the papers' figures (Ihm & Naylor 1990 Figs. 3-4 and
/// 10; Pottmann, Leopoldseder & Hofer 2002 Figs. 3-10): panels side by side, each a list of layers
/// of polylines and dots. Digitized curves are drawn as their points, linearizations as the
/// approximating polygon with its break points marked, splines as the curve with the control
/// polygon dashed. 2D data is drawn in its plane (y up); 3D data projected orthographically along
/// a view direction (camera.hpp) or, for the benchmarks' figures, obliquely.

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "curves/digitized_curve.hpp"
#include "curves/linearization.hpp"
#include "splines/bspline.hpp"

namespace sculpt::render {

struct PlotLayer {
  std::vector<std::vector<Eigen::Vector3d>> lines{};  ///< polylines
  std::vector<Eigen::Vector3d> dots{};
  std::string color = "#000";
  double width = 1.0;
  double dot_radius = 1.5;
  bool dashed = false;
  bool closed = false;        ///< close every polyline
  bool square_dots = false;   ///< dots drawn as squares (break points)
};

struct PlotPanel {
  std::string title;
  std::vector<PlotLayer> layers;
  std::vector<std::pair<std::string, std::string>> legend{};  ///< (color, label)
};

enum class Projection {
  Plane,    ///< (x, y)
  Oblique,  ///< (x + 0.35 z, y + 0.55 z), the benchmarks' figures
  View,     ///< orthographic along PlotOptions::view (screen right and up as in camera.hpp)
};

struct PlotOptions {
  Projection projection = Projection::Plane;
  Eigen::Vector3d view{1, -1, 1};  ///< for Projection::View: from the data towards the viewer
  double size = 320.0;             ///< side of a panel, in SVG units
};

/// The SVG text of panels side by side, each scaled to fit its panel (same scale on both axes,
/// centred). Text is escaped.
std::string svg_panels(const std::vector<PlotPanel>& panels, const PlotOptions& options = {});

/// Colour k of plots (as "#rrggbb"), the pictures' solid colours (picture.hpp) darkened.
std::string plot_color(std::size_t k);

/// A digitized curve: its points as dots (a closed curve's closing segment implied).
PlotLayer curve_layer(const curves::DigitizedCurve& curve, const std::string& color);

/// A linearization of `curve`: the approximating polygon and its break points as squares.
std::vector<PlotLayer> linearization_layers(const curves::DigitizedCurve& curve, const curves::Linearization& la,
                                            const std::string& color);

/// A B-spline curve: the curve sampled (`samples` points per knot span) and its control polygon
/// (dashed) with the control points.
std::vector<PlotLayer> spline_layers(const splines::BSpline& spline, const std::string& color, int samples = 24);

}  // namespace sculpt::render
