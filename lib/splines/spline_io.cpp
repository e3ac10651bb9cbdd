#include "splines/spline_io.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

#include "base/errors.hpp"

namespace sculpt::splines {

namespace {

struct Token {
  std::string text;
  int column;
};

std::vector<Token> tokens_of(const std::string& line) {
  std::vector<Token> out;
  std::size_t i = 0;
  while (i < line.size()) {
    if (line[i] == '#') break;
    if (std::isspace(static_cast<unsigned char>(line[i])) || line[i] == ',') {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])) && line[i] != ',' && line[i] != '#') ++i;
    out.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
  }
  return out;
}

[[noreturn]] void fail(const std::string& source, int line, int column, const std::string& message) {
  const SourceLocation where{source, line, column};
  throw InvalidInput(where.str() + ": error: " + message, where);
}

double number(const Token& t, const std::string& source, int line) {
  char* end = nullptr;
  const double v = std::strtod(t.text.c_str(), &end);
  if (end != t.text.c_str() + t.text.size() || t.text.empty()) fail(source, line, t.column, "expected a number, got '" + t.text + "'");
  if (!std::isfinite(v)) fail(source, line, t.column, "number is not finite: '" + t.text + "'");
  return v;
}

int integer(const Token& t, const std::string& source, int line) {
  const double v = number(t, source, line);
  if (v != std::floor(v) || std::abs(v) > 1e9) fail(source, line, t.column, "expected an integer, got '" + t.text + "'");
  return static_cast<int>(v);
}

}  // namespace

std::string format_spline(const BSpline& curve) {
  std::string s = "# sculpt B-spline\n";
  char buffer[128];
  s += "degree " + std::to_string(curve.degree()) + "\n";
  s += std::string("closed ") + (curve.closed() ? "true" : "false") + "\n";
  s += "dimension " + std::to_string(curve.dimension()) + "\n";
  s += "knots";
  for (double k : curve.knots()) {
    std::snprintf(buffer, sizeof buffer, " %.17g", k);
    s += buffer;
  }
  s += "\ncontrols\n";
  for (const auto& c : curve.controls()) {
    if (curve.dimension() == 2)
      std::snprintf(buffer, sizeof buffer, "%.17g %.17g\n", c.x(), c.y());
    else
      std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g\n", c.x(), c.y(), c.z());
    s += buffer;
  }
  return s;
}

BSpline parse_spline(const std::string& text, const std::string& source_name) {
  std::istringstream in(text);
  std::string line;
  int line_number = 0, controls_line = 0;
  std::optional<int> degree, dimension;
  std::optional<bool> closed;
  std::optional<std::vector<double>> knots;
  std::vector<Eigen::Vector3d> controls;
  bool in_controls = false;
  while (std::getline(in, line)) {
    ++line_number;
    const std::vector<Token> t = tokens_of(line);
    if (t.empty()) continue;
    if (in_controls) {
      const int dim = dimension.value_or(static_cast<int>(t.size()));
      if (static_cast<int>(t.size()) != dim || (dim != 2 && dim != 3))
        fail(source_name, line_number, t[0].column,
             "control point needs " + (dimension ? std::to_string(*dimension) : std::string("2 or 3")) +
                 " coordinates, got " + std::to_string(t.size()));
      if (!dimension) dimension = dim;
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (int i = 0; i < dim; ++i) p[i] = number(t[i], source_name, line_number);
      controls.push_back(p);
      continue;
    }
    const std::string& key = t[0].text;
    const auto expect_args = [&](std::size_t n) {
      if (t.size() != n + 1)
        fail(source_name, line_number, t[0].column, "'" + key + "' takes " + std::to_string(n) + " value(s)");
    };
    if (key == "degree") {
      expect_args(1);
      degree = integer(t[1], source_name, line_number);
    } else if (key == "dimension") {
      expect_args(1);
      dimension = integer(t[1], source_name, line_number);
      if (*dimension != 2 && *dimension != 3) fail(source_name, line_number, t[1].column, "dimension must be 2 or 3");
    } else if (key == "closed") {
      expect_args(1);
      if (t[1].text == "true" || t[1].text == "1")
        closed = true;
      else if (t[1].text == "false" || t[1].text == "0")
        closed = false;
      else
        fail(source_name, line_number, t[1].column, "'closed' must be true or false, got '" + t[1].text + "'");
    } else if (key == "knots") {
      std::vector<double> k;
      for (std::size_t i = 1; i < t.size(); ++i) k.push_back(number(t[i], source_name, line_number));
      knots = std::move(k);
    } else if (key == "controls") {
      expect_args(0);
      in_controls = true;
      controls_line = line_number;
    } else {
      fail(source_name, line_number, t[0].column,
           "unknown keyword '" + key + "' (expected degree, closed, dimension, knots or controls)");
    }
  }
  if (!degree) fail(source_name, line_number, 0, "missing 'degree'");
  if (!in_controls) fail(source_name, line_number, 0, "missing 'controls'");
  try {
    const bool c = closed.value_or(false);
    if (!knots) return c ? BSpline::periodic(*degree, controls, dimension.value_or(0)) : BSpline::clamped(*degree, controls, dimension.value_or(0));
    return BSpline(*degree, *knots, controls, c, dimension.value_or(0));
  } catch (const InvalidInput& e) {
    fail(source_name, controls_line, 1, e.what());
  }
}

BSpline load_spline(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open for reading");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_spline(ss.str(), path);
}

void save_spline(const BSpline& curve, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw IoError(path, "cannot open for writing");
  out << format_spline(curve);
  if (!out) throw IoError(path, "write failed");
}

}  // namespace sculpt::splines
