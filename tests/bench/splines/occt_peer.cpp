// OpenCascade's side of tests/bench/splines/peers.sh (built by that script against Debian's
// libocct-modeling-algorithms-dev, not by CMake): the fixed-knot least-squares approximation
// AppDef_BSplineCompute (chord-length parameters, OCCT's parameter-correction iterations) of a
// closed point list, with uniform knots chosen so the cubic has the same number of control points
// as ours. OCCT has no periodic least-squares fit: the curve is clamped, closed by the data (the
// first point repeated at the end) with SetPeriodic (C1 end conditions).
// Usage: occt_peer <data.txt> <controls> <out spline.txt>; prints the median thread CPU time of 5 fits.
#include <AppDef_BSplineCompute.hxx>
#include <AppDef_MultiLine.hxx>
#include <AppParCurves_MultiBSpCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace {
double thread_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: occt_peer data.txt controls out.txt\n");
    return 2;
  }
  std::vector<std::pair<double, double>> data;
  {
    std::ifstream in(argv[1]);
    double x, y;
    while (in >> x >> y) data.emplace_back(x, y);
  }
  const int controls = std::stoi(argv[2]);
  if (data.size() < 4 || controls < 4) return 2;
  const int m = static_cast<int>(data.size()) + 1;  // closed: the first point again at the end
  TColgp_Array1OfPnt2d points(1, m);
  for (int i = 0; i < m; ++i) points.SetValue(i + 1, gp_Pnt2d(data[i % data.size()].first, data[i % data.size()].second));
  // A clamped cubic with `controls` poles has controls - 2 distinct knots (end multiplicities 4).
  const int distinct = controls - 2;
  TColStd_Array1OfReal knots(1, distinct);
  TColStd_Array1OfInteger mults(1, distinct);
  for (int i = 0; i < distinct; ++i) {
    knots.SetValue(i + 1, static_cast<double>(i) / (distinct - 1));
    mults.SetValue(i + 1, i == 0 || i == distinct - 1 ? 4 : 1);
  }
  std::vector<double> times;
  AppParCurves_MultiBSpCurve result;
  bool ok = false;
  for (int run = 0; run < 5; ++run) {
    const double t0 = thread_ms();
    AppDef_MultiLine line(points);
    AppDef_BSplineCompute fit(3, 3, 1e-9, 1e-9, 5, Standard_False, Approx_ChordLength, Standard_True);
    fit.SetKnotsAndMultiplicities(knots, mults);
    fit.SetContinuity(2);
    fit.SetPeriodic(Standard_True);
    fit.Perform(line);
    times.push_back(thread_ms() - t0);
    result = fit.Value();
    ok = result.NbPoles() == controls;
  }
  std::sort(times.begin(), times.end());
  if (!ok) {
    std::fprintf(stderr, "occt_peer: %d poles, expected %d\n", result.NbPoles(), controls);
    return 1;
  }
  // Our text form (spline_io.hpp): the expanded knot vector and the poles.
  std::ofstream out(argv[3]);
  out.precision(17);
  out << "degree 3\nclosed false\ndimension 2\nknots";
  const TColStd_Array1OfReal& k = result.Knots();
  const TColStd_Array1OfInteger& mu = result.Multiplicities();
  for (int i = k.Lower(); i <= k.Upper(); ++i)
    for (int r = 0; r < mu.Value(i); ++r) out << ' ' << k.Value(i);
  out << "\ncontrols\n";
  TColgp_Array1OfPnt2d poles(1, result.NbPoles());
  result.Curve(1, poles);
  for (int i = 1; i <= poles.Length(); ++i) out << poles.Value(i).X() << ' ' << poles.Value(i).Y() << '\n';
  std::printf("occt AppDef_BSplineCompute: controls %d median_cpu_ms %.2f\n", result.NbPoles(), times[2]);
  return 0;
}
