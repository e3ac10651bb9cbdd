// Writes the spline figures docs/figures/splines_*.svg (in the manner of Pottmann, Leopoldseder &
// Hofer 2002, Figs. 3-10): fitting iterates with their control polygons, degree reduction with
// error vectors, offsets of an ellipse with their corners, the helix from its chord.
#include <cstdio>
#include <string>

#include "common.hpp"
#include "svg.hpp"
#include "splines/splines.hpp"

using namespace sculpt::splines;
using namespace sculpt::splines::bench;

namespace {
std::vector<V> dense(const BSpline& s, int n = 400) {
  auto p = sample(s, n);
  if (s.closed()) p.push_back(p.front());
  return p;
}
Layer curve(const BSpline& s, const std::string& color, double width = 1.5) { return {.lines = {dense(s)}, .color = color, .width = width}; }
Layer polygon(const BSpline& s, const std::string& color) {
  return {.lines = {s.controls()}, .dots = s.controls(), .color = color, .width = 0.7, .dot_radius = 2.0, .dashed = true,
          .closed = s.closed()};
}
std::vector<V> ring(int n, double r) {
  std::vector<V> p(n);
  for (int i = 0; i < n; ++i) p[i] = V(r * std::cos(2 * kPi * i / n), r * std::sin(2 * kPi * i / n), 0);
  return p;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "docs/figures";
  {  // Fig. 3-4 style: the star point cloud, SDM iterates from an enclosing circle, and PDM after as many steps.
    const auto star = t::star(0.3, 5);
    std::vector<V> data(500);
    for (int i = 0; i < 500; ++i) data[i] = star(2 * kPi * i / 500)[0];
    const BSpline start = BSpline::periodic(3, ring(24, 1.5));
    std::vector<Panel> panels;
    for (Method m : {Method::SDM, Method::PDM}) {
      Panel p{.title = "star, 24 controls: " + method_name(m) + " steps 0, 1, 2, 4", .layers = {}};
      p.layers.push_back({.dots = data, .color = "#1f3a93", .dot_radius = 1.0});
      const char* colors[] = {"#999", "#e67e22", "#27ae60", "#c0392b"};
      int c = 0;
      for (int k : {0, 1, 2, 4}) {
        const FitResult r = fit_curve(data, {.closed = true, .method = m, .iterations = k, .tolerance = 0, .start = start});
        p.layers.push_back(curve(r.curve, colors[c], k == 4 ? 1.6 : 1.0));
        if (k == 4) p.layers.push_back(polygon(r.curve, "#c0392b"));
        p.legend.emplace_back(colors[c++], "step " + std::to_string(k));
      }
      panels.push_back(p);
    }
    write_file(dir + "/splines_star_iterates.svg", svg_panels(panels));
  }
  {  // Figs. 6-7 style: degree 6 -> 4 with the ends kept; error vectors from the active curve to the target.
    const BSpline b = BSpline::bezier({V(0, 0, 0), V(1, 2, 0), V(2, 2, 0), V(3, 0, 0), V(4, -2, 0), V(5, -2, 0), V(6, 0, 0)});
    const FitResult a = reduce_degree(b, 4);
    const BSpline eck = reduce_degree_l2(b, 4);
    std::vector<Panel> panels;
    for (int which = 0; which < 2; ++which) {
      const BSpline& r = which == 0 ? a.curve : eck;
      Panel p{.title = which == 0 ? "degree 6 -> 4, active curve (seed sec. 3.1)" : "degree 6 -> 4, Eck's constrained L2", .layers = {}};
      p.layers.push_back(curve(b, "#1f3a93", 2.0));
      p.layers.push_back(polygon(b, "#1f3a93"));
      p.layers.push_back(curve(r, "#c0392b"));
      p.layers.push_back(polygon(r, "#c0392b"));
      Layer errors{.color = "#27ae60", .width = 1.0};
      for (const V& x : sample(r, 40)) {
        const V f = closest_point(b, x).point;
        errors.lines.push_back({x, x + 20.0 * (f - x)});
      }
      p.layers.push_back(errors);
      p.legend = {{"#1f3a93", "degree 6"}, {"#c0392b", "degree 4"}, {"#27ae60", "error x20"}};
      panels.push_back(p);
    }
    write_file(dir + "/splines_degree_reduction.svg", svg_panels(panels));
  }
  {  // Fig. 8-9 style: offsets of the ellipse 2 x 1; at -0.6 the corners where the offset crosses the medial axis.
    const BSpline e = interpolant(t::ellipse(2, 1), 96);
    Panel p{.title = "ellipse 2 x 1, offsets -0.6, -0.3, 0.2, 0.5, 1.0", .layers = {curve(e, "#1f3a93", 2.0)}};
    Panel q{.title = "d = -0.6: raw offset (grey) trimmed, 2 corners", .layers = {curve(e, "#1f3a93", 1.0)}};
    for (double d : {-0.6, -0.3, 0.2, 0.5, 1.0}) {
      const OffsetResult r = offset_curve(e, d, {.max_controls = 32});
      p.layers.push_back(curve(r.curve, "#c0392b"));
      if (d == -0.6) {
        std::vector<V> raw;
        for (int i = 0; i <= 800; ++i) raw.push_back(ellipse_offset(d)(2 * kPi * i / 800)[0]);
        q.layers.push_back({.lines = {raw}, .color = "#aaa", .width = 1.0});
        q.layers.push_back(curve(r.curve, "#c0392b"));
        q.layers.push_back(polygon(r.curve, "#c0392b"));
        Layer corners{.color = "#000", .dot_radius = 3.5};
        for (const auto& c : r.corners) corners.dots.push_back(c.point);
        q.layers.push_back(corners);
      }
    }
    write_file(dir + "/splines_offsets.svg", svg_panels({p, q}));
  }
  {  // Fig. 10 style: the helix by 4 cubic segments (7 controls) from the straight chord; oblique view.
    const TargetCurve helix{.evaluate = t::helix(0.2), .t0 = 0, .t1 = 2 * kPi, .closed = false, .samples = 256};
    const V a = helix.evaluate(0)[0], b = helix.evaluate(2 * kPi)[0];
    std::vector<V> chord(7);
    for (int i = 0; i < 7; ++i) chord[i] = a + (b - a) * (i / 6.0);
    const BSpline start = BSpline::clamped(3, chord, 3);
    std::vector<V> target;
    for (int i = 0; i <= 400; ++i) target.push_back(helix.evaluate(2 * kPi * i / 400)[0]);
    Panel p{.title = "helix from its chord: steps 0, 1, 2, final", .layers = {{.lines = {target}, .color = "#1f3a93", .width = 2.0}}};
    const char* colors[] = {"#999", "#e67e22", "#27ae60", "#c0392b"};
    int c = 0;
    for (int k : {0, 1, 2, 30}) {
      const FitResult r = approximate(helix, start, {.iterations = k, .fixed = {0, 6}});
      p.layers.push_back(curve(r.curve, colors[c], k == 30 ? 1.6 : 1.0));
      if (k == 30) p.layers.push_back(polygon(r.curve, "#c0392b"));
      p.legend.emplace_back(colors[c++], k == 30 ? "final" : "step " + std::to_string(k));
    }
    write_file(dir + "/splines_helix.svg", svg_panels({p}, {.projection = sculpt::render::Projection::Oblique}));
  }
}
