// SVG plots: what each kind of item contributes (counted in the SVG text), the frame, escaping.
#include <gtest/gtest.h>

#include <regex>

#include "curves/linearize.hpp"
#include "render/plot.hpp"

namespace sculpt::render {
namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

curves::DigitizedCurve arc(int n) {
  curves::DigitizedCurve c;
  c.dimension = 2;
  for (int k = 0; k < n; ++k) {
    const double a = 3.0 * k / (n - 1);
    c.points.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  return c;
}

TEST(Plot, LinearizationMarksItsBreakPoints) {
  const curves::DigitizedCurve c = arc(60);
  const curves::Linearization la = curves::linearize(c, {.segments = 7});
  PlotPanel panel{.title = "arc <7 segments>", .layers = {curve_layer(c, "#000")}};
  for (auto& l : linearization_layers(c, la, "#c00")) panel.layers.push_back(l);
  const std::string svg = svg_panels({panel});
  EXPECT_EQ(count(svg, "<circle"), 60);           // the curve's points
  EXPECT_EQ(count(svg, "<rect x="), 8);           // the break points (7 segments)
  EXPECT_EQ(count(svg, "<polyline"), 1);          // the polygon
  EXPECT_NE(svg.find("arc &lt;7 segments&gt;"), std::string::npos);
  EXPECT_EQ(svg.find("<7"), std::string::npos);
}

TEST(Plot, CoordinatesStayInThePanel) {
  const curves::DigitizedCurve c = arc(30);
  const std::string svg = svg_panels({{.title = "", .layers = {curve_layer(c, "#000")}}}, {.size = 200});
  const std::regex circle("cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
  int seen = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator(); ++it, ++seen) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    EXPECT_GE(x, 16.0 - 1e-9);
    EXPECT_LE(x, 16.0 + 200 - 16 + 1e-9);
    EXPECT_GE(y, 20.0 + 16 - 1e-9);
    EXPECT_LE(y, 20.0 + 200 - 16 + 1e-9);
  }
  EXPECT_EQ(seen, 30);
}

TEST(Plot, SplineHasCurveAndDashedControlPolygon) {
  const splines::BSpline s = splines::BSpline::clamped(3, {{0, 0, 0}, {1, 2, 0}, {2, -1, 0}, {3, 1, 0}, {4, 0, 0}});
  PlotPanel panel;
  for (auto& l : spline_layers(s, "#00c")) panel.layers.push_back(l);
  const std::string svg = svg_panels({panel});
  EXPECT_EQ(count(svg, "stroke-dasharray"), 1);
  EXPECT_EQ(count(svg, "<circle"), 5);  // control points
  EXPECT_EQ(count(svg, "<polyline"), 2);
}

TEST(Plot, ViewProjectionOfA3DCurve) {
  // Seen from the top, a 3D curve projects to its (x, y): the same picture as the 2D plot.
  curves::DigitizedCurve flat = arc(20), lifted = arc(20);
  for (auto& p : lifted.points) p.z() = 5 * p.x();
  const std::string a = svg_panels({{.title = "", .layers = {curve_layer(flat, "#000")}}});
  const std::string b = svg_panels({{.title = "", .layers = {curve_layer(lifted, "#000")}}},
                                   {.projection = Projection::View, .view = {0, 0, 1}});
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace sculpt::render
