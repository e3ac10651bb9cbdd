#pragma once
// A small SVG writer for the spline figures (in the manner of Pottmann, Leopoldseder & Hofer 2002,
// Figs. 3-10): panels side by side, each a list of layers (polylines, dots, segments). 3D points
// are shown in an oblique projection. The y axis points up.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace sculpt::splines::bench {

struct Layer {
  std::vector<std::vector<Eigen::Vector3d>> lines{};  // polylines
  std::vector<Eigen::Vector3d> dots{};
  std::string color = "#000";
  double width = 1.0;
  double dot_radius = 1.5;
  bool dashed = false;
  bool closed = false;  // close every polyline
};

struct Panel {
  std::string title;
  std::vector<Layer> layers;
  std::vector<std::pair<std::string, std::string>> legend{};  // (color, label)
};

inline Eigen::Vector2d to2d(const Eigen::Vector3d& p, bool oblique) {
  return oblique ? Eigen::Vector2d(p.x() + 0.35 * p.z(), p.y() + 0.55 * p.z()) : Eigen::Vector2d(p.x(), p.y());
}

inline std::string svg_panels(const std::vector<Panel>& panels, bool oblique = false, double size = 320.0) {
  const double margin = 16.0, title = 20.0;
  std::string svg;
  char b[512];
  std::snprintf(b, sizeof b,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" "
                "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                panels.size() * (size + margin) + margin, size + title + 2 * margin + 16);
  svg += b;
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Panel& panel = panels[k];
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    for (const Layer& l : panel.layers) {
      for (const auto& line : l.lines)
        for (const auto& p : line) lo = lo.cwiseMin(to2d(p, oblique)), hi = hi.cwiseMax(to2d(p, oblique));
      for (const auto& p : l.dots) lo = lo.cwiseMin(to2d(p, oblique)), hi = hi.cwiseMax(to2d(p, oblique));
    }
    const double scale = (size - 2 * margin) / std::max(1e-300, (hi - lo).maxCoeff());
    const double x0 = margin + k * (size + margin) + margin, y0 = title + size - margin;
    const auto screen = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector2d q = to2d(p, oblique) - lo;
      return Eigen::Vector2d(x0 + scale * q.x(), y0 - scale * q.y());
    };
    std::snprintf(b, sizeof b, "<text x=\"%.1f\" y=\"%.1f\">%s</text>\n", x0 - margin, title - 4, panel.title.c_str());
    svg += b;
    for (const Layer& l : panel.layers) {
      for (const auto& line : l.lines) {
        svg += std::string(l.closed ? "<polygon" : "<polyline") + " fill=\"none\" stroke=\"" + l.color + "\"";
        std::snprintf(b, sizeof b, " stroke-width=\"%.2f\"%s points=\"", l.width, l.dashed ? " stroke-dasharray=\"4 3\"" : "");
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
        std::snprintf(b, sizeof b, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"%s\"/>\n", s.x(), s.y(), l.dot_radius,
                      l.color.c_str());
        svg += b;
      }
    }
    double lx = x0 - margin;
    for (const auto& [color, label] : panel.legend) {
      std::snprintf(b, sizeof b,
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"10\" height=\"3\" fill=\"%s\"/><text x=\"%.1f\" y=\"%.1f\" "
                    "font-size=\"10\">%s</text>\n",
                    lx, y0 + margin + 6, color.c_str(), lx + 13, y0 + margin + 10, label.c_str());
      svg += b;
      lx += 18 + 6.0 * label.size();
    }
  }
  return svg + "</svg>\n";
}

inline void write_file(const std::string& path, const std::string& text) {
  if (FILE* f = std::fopen(path.c_str(), "w")) {
    std::fputs(text.c_str(), f);
    std::fclose(f);
    std::printf("wrote %s\n", path.c_str());
  } else {
    std::printf("cannot write %s\n", path.c_str());
  }
}

}  // namespace sculpt::splines::bench
