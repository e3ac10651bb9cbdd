#include "render/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/camera.hpp"

namespace sculpt::render {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace

std::string plot_color(std::size_t k) {
  static constexpr const char* kColors[] = {"#1f5fa8", "#c0392b", "#2e8b3a", "#7a3fa0", "#b8731f", "#1f8a8a"};
  return kColors[k % std::size(kColors)];
}

std::string svg_panels(const std::vector<PlotPanel>& panels, const PlotOptions& options) {
  const Camera camera = options.projection == Projection::View ? orient_camera(options.view) : Camera{};
  const auto to2d = [&](const Eigen::Vector3d& p) -> Eigen::Vector2d {
    switch (options.projection) {
      case Projection::Oblique: return {p.x() + 0.35 * p.z(), p.y() + 0.55 * p.z()};
      case Projection::View: return {p.dot(camera.right), p.dot(camera.up)};
      case Projection::Plane: break;
    }
    return {p.x(), p.y()};
  };
  const double size = options.size, margin = 16.0, title = 20.0;
  std::string svg;
  char b[512];
  std::snprintf(b, sizeof b,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" "
                "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                static_cast<double>(panels.size()) * (size + margin) + margin, size + title + 2 * margin + 16);
  svg += b;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const PlotPanel& panel = panels[k];
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const PlotLayer& l : panel.layers) {
      for (const auto& line : l.lines)
        for (const auto& p : line) lo = lo.cwiseMin(to2d(p)), hi = hi.cwiseMax(to2d(p));
      for (const auto& p : l.dots) lo = lo.cwiseMin(to2d(p)), hi = hi.cwiseMax(to2d(p));
    }
    if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector2d::Zero();  // an empty panel
    const double scale = (size - 2 * margin) / std::max(1e-300, (hi - lo).maxCoeff());
    const double x0 = margin + static_cast<double>(k) * (size + margin) + margin, y0 = title + size - margin;
    // Centred in the panel along the shorter extent.
    const Eigen::Vector2d slack = 0.5 * ((size - 2 * margin) * Eigen::Vector2d::Ones() - scale * (hi - lo));
    const auto screen = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = to2d(p) - lo;
      return Eigen::Vector2d(x0 + slack.x() + scale * q.x(), y0 - slack.y() - scale * q.y());
    };
    std::snprintf(b, sizeof b, "<text x=\"%.1f\" y=\"%.1f\">", x0 - margin, title - 4);
    svg += b + escape(panel.title) + "</text>\n";
    for (const PlotLayer& l : panel.layers) {
      for (const auto& line : l.lines) {
        svg += std::string(l.closed ? "<polygon" : "<polyline") + " fill=\"none\" stroke=\"" + escape(l.color) + "\"";
        std::snprintf(b, sizeof b, " stroke-width=\"%.2f\"%s points=\"", l.width,
                      l.dashed ? " stroke-dasharray=\"4 3\"" : "");
        svg += b;
        for (const auto& p : line) {
          const Eigen::Vector2d s = screen(p);
          std::snprintf(b, sizeof b, "%.2f,%.2f ", s.x(), s.y());
          svg += b;
        }
        svg += "\"/>\n";
      }
      for (const auto& p : l.dots) {
        const Eigen::Vector2d s = screen(p);
        if (l.square_dots)
          std::snprintf(b, sizeof b, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" fill=\"%s\"/>\n",
                        s.x() - l.dot_radius, s.y() - l.dot_radius, 2 * l.dot_radius, 2 * l.dot_radius,
                        escape(l.color).c_str());
        else
          std::snprintf(b, sizeof b, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", s.x(), s.y(),
                        l.dot_radius, escape(l.color).c_str());
        svg += b;
      }
    }
    double lx = x0 - margin;
    for (const auto& [color, label] : panel.legend) {
      std::snprintf(b, sizeof b,
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"10\" height=\"3\" fill=\"%s\"/><text x=\"%.1f\" y=\"%.1f\" "
                    "font-size=\"10\">",
                    lx, y0 + margin + 6, escape(color).c_str(), lx + 13, y0 + margin + 10);
      svg += b + escape(label) + "</text>\n";
      lx += 18 + 6.0 * static_cast<double>(label.size());
    }
  }
  return svg + "</svg>\n";
}

PlotLayer curve_layer(const curves::DigitizedCurve& curve, const std::string& color) {
  return {.dots = curve.points, .color = color, .dot_radius = 1.3};
}

std::vector<PlotLayer> linearization_layers(const curves::DigitizedCurve& curve, const curves::Linearization& la,
                                            const std::string& color) {
  const std::vector<Eigen::Vector3d> polygon = curves::linearization_points(curve, la);
  return {{.lines = {polygon}, .color = color, .width = 1.5},
          {.dots = polygon, .color = color, .dot_radius = 2.5, .square_dots = true}};
}

std::vector<PlotLayer> spline_layers(const splines::BSpline& spline, const std::string& color, int samples) {
  samples = std::max(1, samples);
  std::vector<Eigen::Vector3d> points;
  const std::vector<double> breaks = spline.breaks();
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
    for (int i = 0; i < samples; ++i)
      points.push_back(spline.point(breaks[k] + (breaks[k + 1] - breaks[k]) * i / samples));
  points.push_back(spline.point(breaks.back()));
  std::vector<Eigen::Vector3d> controls = spline.controls();
  PlotLayer polygon{.lines = {controls}, .color = "#888888", .width = 0.8, .dashed = true, .closed = spline.closed()};
  PlotLayer corners{.dots = std::move(controls), .color = "#888888", .dot_radius = 2.0};
  return {std::move(polygon), std::move(corners), {.lines = {std::move(points)}, .color = color, .width = 1.6}};
}

}  // namespace sculpt::render
