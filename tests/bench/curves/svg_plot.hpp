#pragma once
// Minimal SVG writer for curve figures in the manner of the paper's Figures 3-4: the sampled
// points as dots and an approximation as a polyline, in panels side by side. 3D curves are
// shown in an oblique projection.
#include <Eigen/Core>
#include <cstdio>
#include <string>
#include <vector>

namespace sculpt::curves::bench {

struct Panel {
  std::string title;
  std::vector<Eigen::Vector3d> points;   // the digitized curve
  std::vector<Eigen::Vector3d> polygon;  // the approximation
};

inline Eigen::Vector2d project(const Eigen::Vector3d& p) { return {p.x() + 0.35 * p.y(), p.z() + 0.55 * p.y()}; }

inline std::string svg_figure(const std::vector<Panel>& panels, bool planar, double panel_size = 260.0) {
  const auto to2d = [planar](const Eigen::Vector3d& p) { return planar ? Eigen::Vector2d(p.x(), p.y()) : project(p); };
  const double margin = 14.0, title_height = 18.0;
  std::string svg;
  char buffer[256];
  std::snprintf(buffer, sizeof buffer,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" "
                "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                panels.size() * (panel_size + margin) + margin, panel_size + title_height + 2 * margin);
  svg += buffer;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Panel& panel = panels[k];
    Eigen::Vector2d low = to2d(panel.points[0]), high = low;
    for (const auto& p : panel.points) {
      low = low.cwiseMin(to2d(p));
      high = high.cwiseMax(to2d(p));
    }
    const double scale = (panel_size - 2 * margin) / std::max(1e-300, (high - low).maxCoeff());
    const double x0 = margin + k * (panel_size + margin) + margin, y0 = title_height + margin + panel_size - margin;
    const auto screen = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = to2d(p) - low;
      return Eigen::Vector2d(x0 + scale * q.x(), y0 - scale * q.y());  // y up
    };
    std::snprintf(buffer, sizeof buffer, "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", x0, title_height,
                  panel.title.c_str());
    svg += buffer;
    svg += "<polyline fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : panel.polygon) {
      const Eigen::Vector2d s = screen(p);
      std::snprintf(buffer, sizeof buffer, "%.2f,%.2f ", s.x(), s.y());
      svg += buffer;
    }
    svg += "\"/>\n";
    for (const auto& p : panel.points) {
      const Eigen::Vector2d s = screen(p);
      std::snprintf(buffer, sizeof buffer, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"1.3\" fill=\"#1f3a93\"/>\n", s.x(),
                    s.y());
      svg += buffer;
    }
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace sculpt::curves::bench
