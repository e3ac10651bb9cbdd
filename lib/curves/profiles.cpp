#include "curves/profiles.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "base/errors.hpp"

namespace sculpt::curves {
namespace {

/// A joint of a G1 chain: position (r, z) and tangent direction (need not be unit).
struct Joint {
  double r, z, dr, dz;
};

/// Cubic rational piece between two joints, Hermite-like handles. A handle rises by at most
/// 45% of the piece's height, so the control z values increase and (variation diminishing, the
/// rational Bernstein basis being totally positive) so does z along the piece.
RationalBezier hermite_piece(const Joint& a, const Joint& b, double w1, double w2) {
  const Eigen::Vector2d p0(a.r, a.z), p3(b.r, b.z);
  const Eigen::Vector2d ta = Eigen::Vector2d(a.dr, a.dz).normalized();
  const Eigen::Vector2d tb = Eigen::Vector2d(b.dr, b.dz).normalized();
  const double chord = (p3 - p0).norm(), rise = b.z - a.z;
  auto handle = [&](const Eigen::Vector2d& t) {
    double h = chord / 3.0;
    if (t.y() > 0.0) h = std::min(h, 0.45 * rise / t.y());
    return h;
  };
  return RationalBezier({p0, p0 + handle(ta) * ta, p3 - handle(tb) * tb, p3}, {1.0, w1, w2, 1.0});
}

/// Chains joints into pieces; the interior weights alternate so every piece is truly rational.
ProfileDesign chain(std::string name, const std::vector<Joint>& joints) {
  ProfileDesign d{std::move(name), {}};
  for (std::size_t i = 0; i + 1 < joints.size(); ++i) {
    const bool odd = i % 2 == 1;
    d.pieces.push_back(hermite_piece(joints[i], joints[i + 1], odd ? 0.8 : 1.25, odd ? 1.2 : 0.85));
  }
  return d;
}

/// Uniform double in [-1, 1) from the raw 64-bit engine (portable, unlike std distributions).
double symmetric_unit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-52 - 1.0;
}

}  // namespace

ProfileDesign goblet_profile() {
  return chain("goblet", {{3.00, 0.00, 0.2, 1.0},   {2.95, 0.22, -1.0, 0.6},  {2.00, 0.42, -1.0, 0.25},
                          {1.00, 0.70, -1.0, 0.6},  {0.45, 1.30, -0.1, 1.0},  {0.36, 2.40, 0.15, 1.0},
                          {0.72, 2.95, 0.0, 1.0},   {0.36, 3.50, -0.1, 1.0},  {0.42, 4.50, 0.6, 1.0},
                          {1.60, 5.20, 1.0, 0.7},   {2.90, 6.60, 0.3, 1.0},   {3.20, 8.40, 0.02, 1.0},
                          {3.10, 9.60, -0.1, 1.0}});
}

ProfileDesign goblet_cavity_profile() {
  return chain("goblet cavity", {{0.00, 5.45, 1.0, 0.15}, {1.50, 5.80, 1.0, 0.8},  {2.65, 6.90, 0.3, 1.0},
                                 {2.95, 8.40, 0.02, 1.0}, {2.88, 9.60, -0.05, 1.0}, {2.80, 10.20, -0.1, 1.0}});
}

ProfileDesign human_profile() {
  return chain("human", {{1.60, 0.00, 0.05, 1.0}, {1.55, 1.00, 0.4, 1.0},  {2.30, 1.70, 1.0, 0.5},
                         {2.70, 2.05, 0.1, 1.0},  {2.45, 2.45, 0.2, 1.0},  {2.72, 2.75, 0.1, 1.0},
                         {2.80, 3.20, 0.2, 1.0},  {2.70, 3.50, 1.0, 0.3},  {3.35, 3.75, -0.3, 1.0},
                         {2.75, 4.70, 0.3, 1.0},  {2.95, 5.30, 0.0, 1.0},  {2.70, 6.50, -0.5, 1.0},
                         {0.00, 7.60, -1.0, 0.0}});
}

ProfileDesign ball_profile(double radius, double z_center) {
  if (!(radius > 0.0) || !std::isfinite(radius) || !std::isfinite(z_center))
    throw InvalidInput("ball profile needs a finite radius > 0 and a finite centre");
  const double w = std::sqrt(0.5);  // cos 45 deg: a rational quadratic quarter circle
  const double r = radius, c = z_center;
  return {"ball",
          {RationalBezier({{0.0, c - r}, {r, c - r}, {r, c}}, {1.0, w, 1.0}),
           RationalBezier({{r, c}, {r, c + r}, {0.0, c + r}}, {1.0, w, 1.0})}};
}

DigitizedCurve sample_profile(const ProfileDesign& design, const SampleOptions& options) {
  if (options.points < 2) throw InvalidInput("sample_profile: points must be >= 2");
  if (!(options.noise >= 0.0) || !std::isfinite(options.noise))
    throw InvalidInput("sample_profile: noise must be finite and >= 0");
  if (design.pieces.empty()) throw InvalidInput("sample_profile: profile '" + design.name + "' has no pieces");
  for (std::size_t i = 0; i + 1 < design.pieces.size(); ++i)
    if ((design.pieces[i].points().back() - design.pieces[i + 1].points().front()).norm() > 1e-12)
      throw InvalidInput("sample_profile: piece " + std::to_string(i + 1) + " of '" + design.name +
                         "' does not start where piece " + std::to_string(i) + " ends");

  // Dense table of (piece, t) -> cumulative arc length, then equal arc-length spacing.
  constexpr int kTable = 2000;
  struct Entry { std::size_t piece; double t, s; };
  std::vector<Entry> table;
  double s = 0.0;
  Eigen::Vector2d prev = design.pieces.front().evaluate(0.0);
  table.push_back({0, 0.0, 0.0});
  for (std::size_t p = 0; p < design.pieces.size(); ++p)
    for (int k = 1; k <= kTable; ++k) {
      const double t = static_cast<double>(k) / kTable;
      const Eigen::Vector2d q = design.pieces[p].evaluate(t);
      s += (q - prev).norm();
      prev = q;
      table.push_back({p, t, s});
    }
  const int n = options.points - 1;  // segments between samples
  std::vector<Eigen::Vector2d> out;
  out.reserve(n + 1);
  std::size_t j = 0;
  for (int i = 0; i <= n; ++i) {
    const double target = s * i / n;
    while (j + 1 < table.size() - 1 && table[j + 1].s < target) ++j;
    const Entry& a = table[j];
    const Entry& b = table[std::min(j + 1, table.size() - 1)];
    if (i == 0) { out.push_back(design.pieces.front().evaluate(0.0)); continue; }
    if (i == n) { out.push_back(design.pieces.back().evaluate(1.0)); continue; }
    // Interpolate the parameter inside the table interval (same piece, or b starts a new one at t=1/kTable).
    const double f = b.s > a.s ? (target - a.s) / (b.s - a.s) : 0.0;
    const double ta = a.piece == b.piece ? a.t : 0.0;
    out.push_back(design.pieces[b.piece].evaluate(std::clamp(ta + f * (b.t - ta), 0.0, 1.0)));
  }

  if (options.noise > 0.0) {
    std::mt19937_64 rng(options.seed);
    const std::vector<Eigen::Vector2d> clean = out;
    for (int i = 1; i < n; ++i) {
      const double gap = std::min(clean[i].y() - clean[i - 1].y(), clean[i + 1].y() - clean[i].y());
      const double dr = options.noise * symmetric_unit(rng);
      const double dz = std::min(options.noise, 0.3 * std::max(gap, 0.0)) * symmetric_unit(rng);
      out[i].x() = std::max(0.0, clean[i].x() + dr);
      out[i].y() = clean[i].y() + dz;
    }
  }
  DigitizedCurve curve{{}, 2, false, design.name};
  for (const auto& p : out) curve.points.emplace_back(p.x(), p.y(), 0.0);
  return curve;
}

std::vector<Eigen::Vector2d> planar_points(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.emplace_back(p.x(), p.y());
  return out;
}

}  // namespace sculpt::curves
