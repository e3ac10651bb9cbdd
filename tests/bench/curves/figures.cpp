// SVG figures in the manner of Figures 3-4 (and 7): LENGTH, IMAGE, INIT, ITER and the optimum
// side by side for the folium (n = 109, m = 20), the cubic (n = 408, m = 11) and the nonplanar
// quartic (n = 404, m = 32). Writes docs/figures/curves_<name>.svg.
//   curves_figures [output-dir]
#include <cstdio>
#include <fstream>
#include <string>

#include "curves/linearize.hpp"
#include "curves/appendix_b_curves.hpp"
#include "svg_plot.hpp"

using namespace sculpt::curves;

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : std::string(SCULPT_SOURCE_DIR) + "/docs/figures";
  struct Figure {
    AppendixBCurve which;
    int m;
  };
  const double alpha = 0.5;
  for (const Figure& figure : {Figure{AppendixBCurve::Folium, 20}, Figure{AppendixBCurve::Cubic, 11},
                               Figure{AppendixBCurve::Quartic, 32}}) {
    const DigitizedCurve curve = make_appendix_b_curve(figure.which);
    std::vector<bench::Panel> panels;
    for (Method method : {Method::Length, Method::Image, Method::Init, Method::Iter, Method::Optimal}) {
      const Linearization la = linearize(curve, {.segments = figure.m, .method = method, .alpha = alpha});
      char title[128];
      std::snprintf(title, sizeof title, "%s  m=%d  E=%.3g", method_name(method).c_str(), figure.m, la.error);
      panels.push_back({title, curve.points, linearization_points(curve, la)});
      std::printf("%s %s error %.6g\n", appendix_b_curve_name(figure.which).c_str(), title, la.error);
    }
    const std::string path = dir + "/curves_" + appendix_b_curve_name(figure.which) + ".svg";
    std::ofstream(path) << bench::svg_figure(panels, curve.dimension == 2);
    std::printf("wrote %s\n", path.c_str());
  }
}
