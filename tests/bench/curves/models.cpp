// Writes the sampled Appendix-B test curves to models/: <name>_<n>.txt at the paper's point
// counts (tests/curves checks them against the generators) and <name>_noisy_<n>.txt with
// seeded Gaussian noise of 0.2 % of the curve's extent.
//   curves_models [output-dir]   (default: the source tree's models/)
#include <cstdio>
#include <string>

#include "curves/appendix_b_curves.hpp"

using namespace sculpt::curves;

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : std::string(SCULPT_MODELS_DIR);
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const int n = paper_point_count(which);
    const std::string name = appendix_b_curve_name(which);
    DigitizedCurve clean = make_appendix_b_curve(which);
    save_curve(clean, dir + "/" + name + "_" + std::to_string(n) + ".txt");
    Eigen::Vector3d low = clean.points[0], high = clean.points[0];
    for (const auto& p : clean.points) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    const double noise = 0.002 * (high - low).maxCoeff();
    save_curve(make_appendix_b_curve(which, {.points = n, .noise = noise, .seed = 1}),
               dir + "/" + name + "_noisy_" + std::to_string(n) + ".txt");
    std::printf("%s: %d points%s, noisy sigma %.3g\n", name.c_str(), n, clean.closed ? " (closed)" : "", noise);
  }
}
