#pragma once
// A small SVG writer for the spline figures (in the manner of Pottmann, Leopoldseder & Hofer 2002,
// Figs. 3-10): panels side by side, each a list of layers (polylines, dots, segments). 3D points
// are shown in an oblique projection. The y axis points up.
#include <cstdio>
#include <string>
#include <vector>

#include "render/plot.hpp"

namespace sculpt::splines::bench {

// The writer itself is the render layer's (lib/render/plot.hpp), which grew out of this file.
using Layer = render::PlotLayer;
using Panel = render::PlotPanel;

using render::svg_panels;  // svg_panels(panels) in the plane; {.projection = Projection::Oblique} for 3D

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
