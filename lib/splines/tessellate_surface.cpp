#include "splines/tessellate_surface.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/errors.hpp"

namespace sculpt::splines {

SurfaceTriangles tessellate(const BSplineSurface& s, const TessellateOptions& options) {
  if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
    throw InvalidInput("tessellate: the tolerance must be a positive finite number");
  if (options.max_cells < 1) throw InvalidInput("tessellate: max_cells must be at least 1");
  const std::vector<double> bu = s.breaks(0), bv = s.breaks(1);
  // Second derivative maxima on 9 x 9 samples per span (with the span ends), times 1.25.
  double A = 0, B = 0, C = 0;
  constexpr int k = 8;
  for (std::size_t i = 0; i + 1 < bu.size(); ++i)
    for (std::size_t j = 0; j + 1 < bv.size(); ++j)
      for (int a = 0; a <= k; ++a)
        for (int b = 0; b <= k; ++b) {
          // Inside the span (a knot has one-sided derivatives): nudge the end samples inwards.
          const double fa = std::clamp(static_cast<double>(a) / k, 1e-9, 1 - 1e-9), fb = std::clamp(static_cast<double>(b) / k, 1e-9, 1 - 1e-9);
          const SurfaceJet J = s.jet(bu[i] + fa * (bu[i + 1] - bu[i]), bv[j] + fb * (bv[j + 1] - bv[j]), 2);
          A = std::max(A, J.duu.norm());
          B = std::max(B, J.dvv.norm());
          C = std::max(C, J.duv.norm());
        }
  A *= 1.25;
  B *= 1.25;
  C *= 1.25;
  // Rounding noise of a flat direction (far below any tolerance on one cell per span) counts as 0.
  Eigen::Vector3d lo = s.controls()[0], hi = lo;
  for (const auto& c : s.controls()) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const double size = (hi - lo).norm(), wu = bu.back() - bu.front(), wv = bv.back() - bv.front();
  if (A < 1e-12 * size / (wu * wu)) A = 0;
  if (B < 1e-12 * size / (wv * wv)) B = 0;
  if (C < 1e-12 * size / (wu * wv)) C = 0;
  // hu = r / sqrt(A), hv = r / sqrt(B) with (2 + 2 C / sqrt(A B)) r^2 / 8 = tol (A, B floored so a
  // flat direction still gets a cell per span).
  const double a = std::max(A, 1e-300), b = std::max(B, 1e-300);
  const double r = std::sqrt(8 * options.tolerance / (2 + 2 * C / (std::sqrt(a) * std::sqrt(b))));
  const auto cells = [&](double h, const std::vector<double>& br) {
    std::vector<int> per_span;
    long long total = 0;
    for (std::size_t i = 0; i + 1 < br.size(); ++i) {
      const double w = br[i + 1] - br[i];
      const double n = std::ceil(w / h);
      per_span.push_back(static_cast<int>(std::clamp(n, 1.0, static_cast<double>(options.max_cells))));
      total += per_span.back();
    }
    // Over the cap: scale every span down evenly.
    if (total > options.max_cells)
      for (int& n : per_span) n = std::max(1, static_cast<int>(static_cast<long long>(n) * options.max_cells / total));
    std::vector<double> t;
    for (std::size_t i = 0; i + 1 < br.size(); ++i)
      for (int c = 0; c < per_span[i]; ++c) t.push_back(br[i] + (br[i + 1] - br[i]) * c / per_span[i]);
    t.push_back(br.back());
    return t;
  };
  const std::vector<double> tu = cells(r / std::sqrt(a), bu), tv = cells(r / std::sqrt(b), bv);
  double hu = 0, hv = 0;
  for (std::size_t i = 0; i + 1 < tu.size(); ++i) hu = std::max(hu, tu[i + 1] - tu[i]);
  for (std::size_t i = 0; i + 1 < tv.size(); ++i) hv = std::max(hv, tv[i + 1] - tv[i]);
  SurfaceTriangles out;
  const int cu = static_cast<int>(tu.size()) - 1, cv = static_cast<int>(tv.size()) - 1;
  out.cells = {cu, cv};
  out.error_bound = (A * hu * hu + 2 * C * hu * hv + B * hv * hv) / 8;
  // Vertices: a closed direction drops the last row (the seam's copy of the first).
  const int nu = s.closed(0) ? cu : cu + 1, nv = s.closed(1) ? cv : cv + 1;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      out.parameters.emplace_back(tu[i], tv[j]);
      out.points.push_back(s.point(tu[i], tv[j]));
    }
  const auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < cu; ++i)
    for (int j = 0; j < cv; ++j) {
      out.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      out.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return out;
}

}  // namespace sculpt::splines
