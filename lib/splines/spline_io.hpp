#pragma once
/// \file spline_io.hpp
/// A plain text form of a B-spline that a user can read and write by hand:
///
///     # sculpt B-spline
///     degree 3
///     closed false
///     dimension 2
///     knots 0 0 0 0 0.5 1 1 1 1
///     controls
///     0 0
///     1 2
///     ...
///
/// `#` starts a comment; keywords may come in any order but `controls` comes last, followed by
/// one point per line (2 or 3 coordinates as `dimension` says). `knots` may be omitted: then the
/// factories' uniform knots (clamped on [0, 1] for open curves, 0, 1, ..., n for closed) are used.

#include <string>

#include "splines/bspline.hpp"

namespace sculpt::splines {

/// The text form with full precision (%.17g): parse_spline(format_spline(c)) reproduces c exactly.
[[nodiscard]] std::string format_spline(const BSpline& curve);

/// Parses the text form. \throw InvalidInput with SourceLocation{source_name, line, column} for an
/// unknown keyword, a malformed number, a missing keyword, a wrong coordinate count, or any error
/// the BSpline constructor reports (then on the line of `controls`).
[[nodiscard]] BSpline parse_spline(const std::string& text, const std::string& source_name = "<text>");

/// Reads and writes files in the text form. \throw IoError if the file cannot be read or written.
[[nodiscard]] BSpline load_spline(const std::string& path);
void save_spline(const BSpline& curve, const std::string& path);

}  // namespace sculpt::splines
