#pragma once
/// \file appendix_b_curves.hpp
/// The curves of Ihm & Naylor 1990, Appendix B (Figures 3, 4, 6, 7, 8), as generators with a
/// point count (sampled from a parametrization; see docs/curves.md for the ranges), plus a helix
/// (ours) and noisy variants. The language's curve built-ins (`folium()`, ...), the tests and the
/// benchmarks sample them here.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "curves/digitized_curve.hpp"

namespace sculpt::curves {

enum class AppendixBCurve {
  Folium,   ///< Fig. 3: x^3 - 3xy + y^3 = 0, the loop, t in [0, inf) via an angle map
  Cubic,    ///< Fig. 4: (t, t^3, 0), t in [-1, 1]
  Rose,     ///< Fig. 6: four-leaved rose r = sin(2 theta), closed
  Quartic,  ///< Fig. 7: ellipsoid 36x^2+81y^2+9z^2=324 cut by cylinder x^2+y^2=3.94, closed
  Sextic,   ///< Fig. 8: y^2 = x^2 + x^3 on the surface z = x^2 - x + 2
  Helix,    ///< not in the paper: (cos t, sin t, t / (2 pi)), three turns
};

/// All of them, in the order above.
[[nodiscard]] const std::vector<AppendixBCurve>& all_appendix_b_curves();
[[nodiscard]] std::string appendix_b_curve_name(AppendixBCurve which);  ///< "folium", "cubic", "rose", ...
[[nodiscard]] std::optional<AppendixBCurve> appendix_b_curve_from_name(const std::string& name);

struct AppendixBCurveOptions {
  int points = 0;          ///< n >= 2 (>= 3 for closed curves); 0 = the paper's n (or 400)
  double noise = 0.0;      ///< standard deviation of seeded Gaussian noise added to every coordinate
  std::uint64_t seed = 1;  ///< noise seed (deterministic on every platform)
};

/// Samples the curve. \throw InvalidInput for a point count below the minimum or negative noise.
[[nodiscard]] DigitizedCurve make_appendix_b_curve(AppendixBCurve which, const AppendixBCurveOptions& options = {});

/// The paper's point count for the figure of this curve (Appendix B), 400 for the helix.
[[nodiscard]] int paper_point_count(AppendixBCurve which);

}  // namespace sculpt::curves
