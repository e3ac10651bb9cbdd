#include "curves/digitized_curve.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "base/errors.hpp"

namespace sculpt::curves {
namespace {

// One parsed number with its 1-based column; strtod accepts "nan"/"inf", which we reject
// explicitly so that the message names the problem.
struct Token {
  std::string text;
  int column;
};

std::vector<Token> split_tokens(const std::string& line) {
  std::vector<Token> tokens;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t' || line[k] == '\r' || line[k] == ',')) ++k;
    if (k >= line.size()) break;
    const std::size_t start = k;
    while (k < line.size() && line[k] != ' ' && line[k] != '\t' && line[k] != '\r' && line[k] != ',') ++k;
    tokens.push_back({line.substr(start, k - start), static_cast<int>(start) + 1});
  }
  return tokens;
}

// "file:line:col: error: " (built with append: GCC 12 warns falsely (-Wrestrict) about the
// operator+ chain in SourceLocation::str() once it is inlined here).
std::string prefix(const SourceLocation& where) {
  std::string s = where.file;
  s.append(":").append(std::to_string(where.line)).append(":").append(std::to_string(where.column));
  s.append(": error: ");
  return s;
}

double parse_number(const Token& token, const SourceLocation& where) {
  const char* begin = token.text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0')
    throw InvalidInput(prefix(where) + "'" + token.text + "' is not a number", where);
  if (std::isnan(value)) throw InvalidInput(prefix(where) + "coordinate is NaN", where);
  if (std::isinf(value) || (errno == ERANGE && std::abs(value) > 1.0))
    throw InvalidInput(prefix(where) + "coordinate '" + token.text + "' is infinite or out of range", where);
  return value;
}

}  // namespace

DigitizedCurve parse_curve(const std::string& text, const std::string& source_name) {
  DigitizedCurve curve;
  curve.name = source_name;
  int expected = 0;  // coordinates per line, fixed by the first data line
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    const std::vector<Token> tokens = split_tokens(line);
    if (tokens.empty()) continue;
    SourceLocation where{source_name, line_number, tokens.front().column};
    const int count = static_cast<int>(tokens.size());
    if (count != 2 && count != 3)
      throw InvalidInput(prefix(where) + "expected 'x y' or 'x y z', found " + std::to_string(count) +
                             " values",
                         where);
    if (expected == 0) expected = count;
    if (count != expected)
      throw InvalidInput(prefix(where) + "" + std::to_string(count) + " coordinates, but earlier lines have " +
                             std::to_string(expected),
                         where);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int c = 0; c < count; ++c) {
      where.column = tokens[c].column;
      p[c] = parse_number(tokens[c], where);
    }
    curve.points.push_back(p);
  }
  curve.dimension = expected == 2 ? 2 : 3;
  return curve;
}

DigitizedCurve load_curve(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw IoError(path, "cannot open curve file");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw IoError(path, "read error");
  return parse_curve(text.str(), path);
}

std::string format_curve(const DigitizedCurve& curve) {
  std::string out = "# " + std::string(curve.closed ? "closed " : "") + std::to_string(curve.dimension) +
                    "D curve, " + std::to_string(curve.points.size()) + " points" +
                    (curve.name.empty() ? "" : " (" + curve.name + ")") + "\n";
  char buffer[128];
  for (const auto& p : curve.points) {
    if (curve.dimension == 2)
      std::snprintf(buffer, sizeof buffer, "%.17g %.17g\n", p.x(), p.y());
    else
      std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    out += buffer;
  }
  return out;
}

void save_curve(const DigitizedCurve& curve, const std::string& path) {
  std::ofstream file(path, std::ios::binary);
  if (!file) throw IoError(path, "cannot create file");
  file << format_curve(curve);
  if (!file) throw IoError(path, "write error");
}

std::vector<Eigen::Vector3d> path_points(const DigitizedCurve& curve) {
  std::vector<Eigen::Vector3d> points = curve.points;
  if (curve.closed && !points.empty()) points.push_back(points.front());
  return points;
}

void validate(const DigitizedCurve& curve) {
  if (curve.dimension != 2 && curve.dimension != 3)
    throw InvalidInput("curve '" + curve.name + "': dimension must be 2 or 3, not " + std::to_string(curve.dimension));
  for (std::size_t k = 0; k < curve.points.size(); ++k)
    if (!curve.points[k].allFinite())
      throw InvalidInput("curve '" + curve.name + "': point " + std::to_string(k) + " has a NaN or infinite coordinate");
}

}  // namespace sculpt::curves
