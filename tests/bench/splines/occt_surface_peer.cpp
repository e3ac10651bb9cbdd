// OpenCascade's side of the active-surface comparison in tests/bench/splines/peers.sh (built by
// that script against Debian's libocct-modeling-algorithms-dev, not by CMake):
// GeomAPI_PointsToBSplineSurface (bicubic, C2, chord-length parameters) on a grid of points.
// OCCT chooses the knots itself to meet a tolerance Tol3D, so the tolerance is scanned (in log
// scale) for the smallest one whose result has at most `controls` poles in each direction: the
// closest OCCT gets with that many control points.
// Usage: occt_surface_peer <data.txt> <rows> <columns> <controls> <out.txt>
//   data.txt: rows * columns lines "x y z" (row-major); out.txt: the surface in the text form of
//   surfaces.cpp (degrees, expanded knots, poles). Prints the pole counts, Tol3D and the median
//   thread CPU time of 5 fits at that tolerance.
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Pnt.hxx>

#include <algorithm>
#include <cmath>
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
  if (argc != 6) {
    std::fprintf(stderr, "usage: occt_surface_peer data.txt rows columns controls out.txt\n");
    return 2;
  }
  const int rows = std::stoi(argv[2]), columns = std::stoi(argv[3]), controls = std::stoi(argv[4]);
  TColgp_Array2OfPnt points(1, rows, 1, columns);
  {
    std::ifstream in(argv[1]);
    for (int i = 1; i <= rows; ++i)
      for (int j = 1; j <= columns; ++j) {
        double x, y, z;
        if (!(in >> x >> y >> z)) return 2;
        points.SetValue(i, j, gp_Pnt(x, y, z));
      }
  }
  const auto fit = [&](double tol) {
    GeomAPI_PointsToBSplineSurface f;
    f.Init(points, Approx_ChordLength, 3, 3, GeomAbs_C2, tol);
    return f.IsDone() ? f.Surface() : Handle(Geom_BSplineSurface)();
  };
  const auto fits = [&](double tol) {
    const Handle(Geom_BSplineSurface) s = fit(tol);
    return !s.IsNull() && s->NbUPoles() <= controls && s->NbVPoles() <= controls;
  };
  // Pole counts do not fall monotonically with the tolerance: scan 400 tolerances from 1 down to
  // 1e-9 (log scale) and keep the smallest that stays within the budget.
  double best = -1;
  for (int k = 0; k <= 400; ++k) {
    const double tol = std::pow(10.0, -9.0 * k / 400);
    if (fits(tol)) best = tol;
  }
  if (best < 0) return 1;
  const double hi = std::log(best);
  const double tol = std::exp(hi);
  std::vector<double> times;
  Handle(Geom_BSplineSurface) s;
  for (int run = 0; run < 5; ++run) {
    const double t0 = thread_ms();
    s = fit(tol);
    times.push_back(thread_ms() - t0);
  }
  std::sort(times.begin(), times.end());
  std::ofstream out(argv[5]);
  out.precision(17);
  out << "degree " << s->UDegree() << ' ' << s->VDegree() << "\nknots_u";
  for (int i = 1; i <= s->NbUKnots(); ++i)
    for (int r = 0; r < s->UMultiplicity(i); ++r) out << ' ' << s->UKnot(i);
  out << "\nknots_v";
  for (int i = 1; i <= s->NbVKnots(); ++i)
    for (int r = 0; r < s->VMultiplicity(i); ++r) out << ' ' << s->VKnot(i);
  out << "\nsize " << s->NbUPoles() << ' ' << s->NbVPoles() << '\n';
  for (int i = 1; i <= s->NbUPoles(); ++i)
    for (int j = 1; j <= s->NbVPoles(); ++j) {
      const gp_Pnt& p = s->Pole(i, j);
      out << p.X() << ' ' << p.Y() << ' ' << p.Z() << '\n';
    }
  std::printf("occt GeomAPI_PointsToBSplineSurface: poles %d x %d Tol3D %.3e median_cpu_ms %.2f\n", s->NbUPoles(), s->NbVPoles(), tol,
              times[2]);
  return 0;
}
