// SVG chart of the depth distribution (tree_report.hpp): for each leaf depth, the probability
// mass of the sample space reaching it, one bar per tree, in-cells stacked on out-cells.
#include <algorithm>
#include <cstdio>
#include <string>

#include "reports/tree_report.hpp"

namespace sculpt::reports {
namespace {

std::string f(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  return buffer;
}

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

constexpr const char* kDark[] = {"#1f5fa8", "#b8431f", "#2e8b3a", "#7a3fa0", "#8a6d1c"};
constexpr const char* kLight[] = {"#9fc3ea", "#f0b39c", "#a5dbab", "#d2b5e6", "#e3cf94"};

}  // namespace

std::string depth_chart_svg(const std::vector<TreeReport>& reports) {
  const double legend = 16.0 * static_cast<double>(reports.size());
  const double width = 760, height = 340 + legend, left = 60, right = 20, top = 40, bottom = 50 + legend;
  int max_depth = 1;
  double max_p = 0;
  for (const auto& r : reports)
    for (const auto& b : r.depth.histogram) {
      max_depth = std::max(max_depth, b.depth);
      max_p = std::max(max_p, b.in_probability + b.out_probability);
    }
  if (max_p <= 0) max_p = 1;
  const double plot_w = width - left - right, plot_h = height - top - bottom;
  const double slot = plot_w / (max_depth + 1);
  const double bar = slot * 0.8 / std::max<std::size_t>(1, reports.size());
  auto x_of = [&](double depth) { return left + (depth + 0.5) * slot; };
  auto y_of = [&](double p) { return top + plot_h * (1 - p / max_p); };

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + f(width) + "\" height=\"" + f(height) +
                  "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + f(left) + "\" y=\"20\" font-size=\"13\">Probability of reaching a leaf at each depth "
       "(dark: in-cells, light: out-cells; solid line: expected depth, dashed: entropy bound)</text>\n";
  // Axes, ticks.
  s += "<line x1=\"" + f(left) + "\" y1=\"" + f(top + plot_h) + "\" x2=\"" + f(left + plot_w) + "\" y2=\"" +
       f(top + plot_h) + "\" stroke=\"black\"/>\n";
  s += "<line x1=\"" + f(left) + "\" y1=\"" + f(top) + "\" x2=\"" + f(left) + "\" y2=\"" + f(top + plot_h) +
       "\" stroke=\"black\"/>\n";
  int step = 1;  // at most about 16 depth labels
  for (int nice : {1, 2, 5, 10, 20, 50, 100, 200, 500, 1000})
    if (max_depth / nice <= 16) {
      step = nice;
      break;
    }
  for (int d = 0; d <= max_depth; d += step)
    s += "<text x=\"" + f(x_of(d)) + "\" y=\"" + f(top + plot_h + 14) + "\" text-anchor=\"middle\">" +
         std::to_string(d) + "</text>\n";
  s += "<text x=\"" + f(left + plot_w / 2) + "\" y=\"" + f(top + plot_h + 30) + "\" text-anchor=\"middle\">leaf depth</text>\n";
  for (int k = 0; k <= 4; ++k) {
    const double p = max_p * k / 4;
    s += "<text x=\"" + f(left - 6) + "\" y=\"" + f(y_of(p) + 4) + "\" text-anchor=\"end\">" + f(p) + "</text>\n";
  }
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const auto& r = reports[i];
    const char* dark = kDark[i % 5];
    const char* light = kLight[i % 5];
    for (const auto& b : r.depth.histogram) {
      const double x = x_of(b.depth) - 0.4 * slot + i * bar;
      const double y_out = y_of(b.out_probability), y_all = y_of(b.out_probability + b.in_probability);
      s += "<rect x=\"" + f(x) + "\" y=\"" + f(y_out) + "\" width=\"" + f(bar) + "\" height=\"" +
           f(top + plot_h - y_out) + "\" fill=\"" + light + "\"/>\n";
      s += "<rect x=\"" + f(x) + "\" y=\"" + f(y_all) + "\" width=\"" + f(bar) + "\" height=\"" + f(y_out - y_all) +
           "\" fill=\"" + dark + "\"/>\n";
    }
    const double xe = x_of(r.depth.expected_depth), xh = x_of(r.depth.entropy_bound);
    s += "<line x1=\"" + f(xe) + "\" y1=\"" + f(top) + "\" x2=\"" + f(xe) + "\" y2=\"" + f(top + plot_h) +
         "\" stroke=\"" + dark + "\" stroke-width=\"2\"/>\n";
    s += "<line x1=\"" + f(xh) + "\" y1=\"" + f(top) + "\" x2=\"" + f(xh) + "\" y2=\"" + f(top + plot_h) +
         "\" stroke=\"" + dark + "\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"/>\n";
    char label[160];
    std::snprintf(label, sizeof label, ": expected depth %.3f, entropy bound %.3f, ratio %.3f",
                  r.depth.expected_depth, r.depth.entropy_bound, r.depth.ratio);
    const double y_legend = top + plot_h + 44 + 16.0 * static_cast<double>(i);
    s += "<rect x=\"" + f(left) + "\" y=\"" + f(y_legend - 9) + "\" width=\"10\" height=\"10\" fill=\"" + dark +
         "\"/>\n";
    s += "<text x=\"" + f(left + 14) + "\" y=\"" + f(y_legend) + "\">" + escape(r.name) + label + "</text>\n";
  }
  return s + "</svg>\n";
}

}  // namespace sculpt::reports
