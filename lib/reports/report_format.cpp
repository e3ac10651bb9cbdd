// Text and JSON renderings of tree reports (tree_report.hpp).
#include <algorithm>
#include <cstdio>
#include <string>

#include "reports/tree_report.hpp"

namespace sculpt::reports {
namespace {

std::string fmt(const char* format, double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}
std::string num(double v) { return fmt("%.10g", v); }

std::string box_text(const Eigen::AlignedBox3d& b) {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, "[%.6g, %.6g] x [%.6g, %.6g] x [%.6g, %.6g]", b.min().x(), b.max().x(), b.min().y(),
                b.max().y(), b.min().z(), b.max().z());
  return buffer;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned char>(c));
      out += buffer;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string json_box(const Eigen::AlignedBox3d& b) {
  return "{\"min\": [" + num(b.min().x()) + ", " + num(b.min().y()) + ", " + num(b.min().z()) + "], \"max\": [" +
         num(b.max().x()) + ", " + num(b.max().y()) + ", " + num(b.max().z()) + "]}";
}

}  // namespace

std::string report_text(const std::vector<TreeReport>& reports) {
  if (reports.empty()) return "depth-cost report: no trees\n";
  std::vector<std::pair<std::string, std::vector<std::string>>> rows;
  auto row = [&](const std::string& label, auto cell) {
    std::vector<std::string> cells;
    for (const auto& r : reports) cells.push_back(cell(r));
    rows.emplace_back(label, std::move(cells));
  };
  row("", [](const TreeReport& r) { return r.name; });
  if (std::any_of(reports.begin(), reports.end(), [](const TreeReport& r) { return r.grid != kernel::Grid{}; }))
    row("grid step", [](const TreeReport& r) { return r.grid.name(); });
  row("partitioning nodes", [](const TreeReport& r) { return std::to_string(r.depth.nodes); });
  row("leaves (in / out)", [](const TreeReport& r) {
    return std::to_string(r.depth.leaves) + " (" + std::to_string(r.depth.in_leaves) + " / " +
           std::to_string(r.depth.out_leaves) + ")";
  });
  row("height", [](const TreeReport& r) { return std::to_string(r.depth.height); });
  row("cells in the sample box", [](const TreeReport& r) { return std::to_string(r.depth.cells_in_box); });
  row("sum of cell volumes / V", [](const TreeReport& r) { return fmt("%.12f", r.depth.cell_volume_sum / r.depth.sample_volume); });
  row("in-cell volume", [](const TreeReport& r) { return fmt("%.9g", r.depth.in_volume); });
  row("expected depth  sum p_C d_C", [](const TreeReport& r) { return fmt("%.4f", r.depth.expected_depth); });
  row("entropy bound  H", [](const TreeReport& r) { return fmt("%.4f", r.depth.entropy_bound); });
  row("ratio expected / H", [](const TreeReport& r) { return fmt("%.4f", r.depth.ratio); });
  const std::size_t shapes = reports.front().queries.size();
  for (std::size_t q = 0; q < shapes; ++q) {
    const QueryCost& first = reports.front().queries[q];
    const std::string label = first.shape == QueryShape::Point
                                  ? "points: mean depth"
                                  : query_shape_name(first.shape) + " " + fmt("%.3g", first.size) + ": mean nodes";
    row(label, [q](const TreeReport& r) {
      if (q >= r.queries.size()) return std::string("-");
      const QueryCost& c = r.queries[q];
      return fmt("%.3f", c.mean_nodes) + " +- " + fmt("%.3f", c.ci_high - c.mean_nodes);
    });
  }

  std::size_t label_width = 0;
  for (const auto& [label, cells] : rows) label_width = std::max(label_width, label.size());
  std::vector<std::size_t> widths(reports.size(), 0);
  for (const auto& [label, cells] : rows)
    for (std::size_t i = 0; i < cells.size(); ++i) widths[i] = std::max(widths[i], cells[i].size());

  const DepthCost& d0 = reports.front().depth;
  std::string out = "Depth-cost report (Ihm & Naylor 1990, sec. 6)\n";
  out += "sample space: " + box_text(d0.sample_box) + ", volume V = " + fmt("%.9g", d0.sample_volume) + "\n";
  for (const auto& r : reports)
    if (!r.depth.sample_box.isApprox(d0.sample_box))
      out += "  (" + r.name + ": sample space " + box_text(r.depth.sample_box) + ")\n";
  for (const auto& [label, cells] : rows) {
    std::string line = label + std::string(label_width - label.size() + 2, ' ');
    for (std::size_t i = 0; i < cells.size(); ++i) line += std::string(widths[i] - cells[i].size() + 2, ' ') + cells[i];
    out += line + "\n";
  }
  out += "(cell volumes: " + d0.cell_volumes + ")\n";
  if (shapes > 0)
    out += "(Monte Carlo: " + std::to_string(reports.front().queries.front().samples) + " queries per shape, " +
           fmt("%.0f", 100 * reports.front().queries.front().confidence) + "% confidence half-widths)\n";

  for (const auto& r : reports) {
    out += "\ndepth histogram of " + r.name + " (cells in / out, probability mass):\n";
    double most = 0;
    for (const auto& b : r.depth.histogram) most = std::max(most, b.in_probability + b.out_probability);
    for (const auto& b : r.depth.histogram) {
      const double p = b.in_probability + b.out_probability;
      const int bar = most > 0 ? static_cast<int>(40 * p / most + 0.5) : 0;
      char line[96];
      std::snprintf(line, sizeof line, "  %3d  %5d / %-5d  %8.5f  ", b.depth, b.in_cells, b.out_cells, p);
      out += line + std::string(static_cast<std::size_t>(bar), '#') + "\n";
    }
  }
  return out;
}

std::string report_json(const std::vector<TreeReport>& reports) {
  std::string out = "{\"trees\": [";
  for (std::size_t i = 0; i < reports.size(); ++i) {
    const TreeReport& r = reports[i];
    const DepthCost& d = r.depth;
    out += i ? ",\n  " : "\n  ";
    out += "{\"name\": " + json_string(r.name) + ", \"sample_box\": " + json_box(d.sample_box) +
           (r.grid != kernel::Grid{} ? ", \"grid_step\": " + num(r.grid.step()) : std::string()) +
           ", \"sample_volume\": " + num(d.sample_volume) + ", \"cell_volume_sum\": " + num(d.cell_volume_sum) +
           ", \"nodes\": " + std::to_string(d.nodes) + ", \"leaves\": " + std::to_string(d.leaves) +
           ", \"in_leaves\": " + std::to_string(d.in_leaves) + ", \"out_leaves\": " + std::to_string(d.out_leaves) +
           ", \"height\": " + std::to_string(d.height) + ", \"cells_in_box\": " + std::to_string(d.cells_in_box) +
           ", \"in_volume\": " + num(d.in_volume) + ", \"expected_depth\": " + num(d.expected_depth) +
           ", \"entropy_bound\": " + num(d.entropy_bound) + ", \"ratio\": " + num(d.ratio) + ", \"cell_volumes\": " + json_string(d.cell_volumes) +
           ", \"histogram\": [";
    for (std::size_t k = 0; k < d.histogram.size(); ++k) {
      const DepthBin& b = d.histogram[k];
      out += (k ? ", " : "") + std::string("{\"depth\": ") + std::to_string(b.depth) +
             ", \"in_cells\": " + std::to_string(b.in_cells) + ", \"out_cells\": " + std::to_string(b.out_cells) +
             ", \"in_probability\": " + num(b.in_probability) + ", \"out_probability\": " + num(b.out_probability) + "}";
    }
    out += "], \"queries\": [";
    for (std::size_t k = 0; k < r.queries.size(); ++k) {
      const QueryCost& q = r.queries[k];
      out += (k ? ", " : "") + std::string("{\"shape\": ") + json_string(query_shape_name(q.shape)) +
             ", \"size\": " + num(q.size) + ", \"samples\": " + std::to_string(q.samples) +
             ", \"mean_nodes\": " + num(q.mean_nodes) + ", \"std_dev\": " + num(q.std_dev) +
             ", \"ci_low\": " + num(q.ci_low) + ", \"ci_high\": " + num(q.ci_high) +
             ", \"confidence\": " + num(q.confidence) + ", \"mean_leaves\": " + num(q.mean_leaves) + "}";
    }
    out += "]}";
  }
  out += "\n]}\n";
  return out;
}

}  // namespace sculpt::reports
