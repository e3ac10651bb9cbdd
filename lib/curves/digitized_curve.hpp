#pragma once
/// \file digitized_curve.hpp
/// A digitized curve (Ihm & Naylor, Definition 2.2): an ordered sequence of 2D or 3D points,
/// open or closed, with loading from and writing to plain text files.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace sculpt::curves {

/// Ordered points of a curve. 2D curves keep z = 0 and have `dimension == 2`.
/// A closed curve does not repeat its first point at the end; the segment from the last
/// point back to the first is implied (see path_points()).
struct DigitizedCurve {
  std::vector<Eigen::Vector3d> points;
  int dimension = 3;    ///< 2 or 3
  bool closed = false;  ///< last point connects back to the first
  std::string name;     ///< file name or generator name, for messages
};

/// Parses `x y` or `x y z` per line; `#` starts a comment, blank lines are ignored.
/// All data lines must have the same number of coordinates.
/// \throw InvalidInput with SourceLocation{source_name, line, column} for a malformed line,
///        a NaN or infinite coordinate, or mixed 2D/3D lines.
[[nodiscard]] DigitizedCurve parse_curve(const std::string& text, const std::string& source_name = "<text>");

/// Reads a curve file (see parse_curve). \throw IoError if the file cannot be read.
[[nodiscard]] DigitizedCurve load_curve(const std::string& path);

/// Text form, one point per line with full precision (%.17g), a leading comment line.
[[nodiscard]] std::string format_curve(const DigitizedCurve& curve);

/// Writes format_curve() to `path`. \throw IoError on failure.
void save_curve(const DigitizedCurve& curve, const std::string& path);

/// The point sequence the linearizers work on: the points of an open curve, or for a closed
/// curve the points followed by the first point again (index size() denotes points[0]).
[[nodiscard]] std::vector<Eigen::Vector3d> path_points(const DigitizedCurve& curve);

/// Throws InvalidInput unless every coordinate is finite and dimension is 2 or 3.
void validate(const DigitizedCurve& curve);

}  // namespace sculpt::curves
