#include "curves/profiles.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "support/source_paths.hpp"

using namespace sculpt::curves;

namespace {

std::vector<ProfileDesign> designs() {
  return {goblet_profile(), goblet_cavity_profile(), human_profile(), ball_profile(1.5, 6.8)};
}

}  // namespace

TEST(Profiles, DesignsAreChainedWithMonotoneControlPolygons) {
  for (const auto& d : designs()) {
    ASSERT_FALSE(d.pieces.empty()) << d.name;
    for (std::size_t i = 0; i < d.pieces.size(); ++i) {
      const auto& pts = d.pieces[i].points();
      if (i + 1 < d.pieces.size()) {
        EXPECT_EQ(pts.back(), d.pieces[i + 1].points().front()) << d.name << " piece " << i;
      }
      for (std::size_t k = 1; k < pts.size(); ++k)
        EXPECT_GE(pts[k].y(), pts[k - 1].y()) << d.name << " piece " << i << " control " << k;
      for (const auto& p : pts) EXPECT_GE(p.x(), 0.0) << d.name;
    }
  }
  EXPECT_EQ(goblet_profile().pieces.size(), 12u);  // the paper's "12 rational Bezier curves"
  EXPECT_EQ(human_profile().pieces.size(), 12u);
}

TEST(Profiles, SamplesAreStrictlyMonotoneInZEvenWithNoise) {
  for (const auto& d : designs())
    for (double noise : {0.0, 0.005, 0.05}) {
      const auto c = sample_profile(d, {.points = 400, .noise = noise, .seed = 11});
      ASSERT_EQ(c.points.size(), 400u);
      EXPECT_EQ(c.dimension, 2);
      EXPECT_FALSE(c.closed);
      for (std::size_t i = 1; i < c.points.size(); ++i)
        ASSERT_GT(c.points[i].y(), c.points[i - 1].y()) << d.name << " noise " << noise << " at " << i;
      for (const auto& p : c.points) EXPECT_GE(p.x(), 0.0);
    }
}

TEST(Profiles, EndsAreExactAndNoiseIsBounded) {
  const auto d = goblet_profile();
  const auto clean = sample_profile(d, {.points = 237});
  const auto noisy = sample_profile(d, {.points = 237, .noise = 0.01, .seed = 5});
  EXPECT_EQ(planar_points(clean.points).front(), d.pieces.front().points().front());
  EXPECT_EQ(planar_points(clean.points).back(), d.pieces.back().points().back());
  EXPECT_EQ(noisy.points.front(), clean.points.front());
  EXPECT_EQ(noisy.points.back(), clean.points.back());
  double moved = 0;
  for (std::size_t i = 0; i < clean.points.size(); ++i) {
    EXPECT_LE(std::abs(noisy.points[i].x() - clean.points[i].x()), 0.01);
    EXPECT_LE(std::abs(noisy.points[i].y() - clean.points[i].y()), 0.01);
    moved = std::max(moved, (noisy.points[i] - clean.points[i]).norm());
  }
  EXPECT_GT(moved, 0.001);  // the noise is really there
}

TEST(Profiles, SamplesAreEquallySpacedInArcLength) {
  const auto c = sample_profile(human_profile(), {.points = 169});
  double total = 0, shortest = 1e9, longest = 0;
  for (std::size_t i = 1; i < c.points.size(); ++i) {
    const double s = (c.points[i] - c.points[i - 1]).norm();
    total += s;
    shortest = std::min(shortest, s);
    longest = std::max(longest, s);
  }
  // Chords of equal arcs: equal up to the curvature's shortening of the chord.
  EXPECT_GT(shortest, 0.9 * total / 168);
  EXPECT_LT(longest, 1.01 * total / 168 * 1.01);
}

TEST(Profiles, SameSeedSamePointsOtherSeedOtherPoints) {
  const auto a = sample_profile(goblet_profile(), {.points = 100, .noise = 0.01, .seed = 3});
  const auto b = sample_profile(goblet_profile(), {.points = 100, .noise = 0.01, .seed = 3});
  const auto c = sample_profile(goblet_profile(), {.points = 100, .noise = 0.01, .seed = 4});
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
}

TEST(Profiles, BallProfileIsAHalfCircle) {
  const auto c = sample_profile(ball_profile(2.0, 1.0), {.points = 50});
  for (const auto& p : c.points) EXPECT_NEAR(std::hypot(p.x(), p.y() - 1.0), 2.0, 1e-12);
  EXPECT_NEAR(c.points.front().y(), -1.0, 1e-15);
  EXPECT_NEAR(c.points.back().y(), 3.0, 1e-15);
}

TEST(Profiles, RejectsBadOptions) {
  using sculpt::InvalidInput;
  EXPECT_THROW(sample_profile(goblet_profile(), {.points = 1}), InvalidInput);
  EXPECT_THROW(sample_profile(goblet_profile(), {.points = 10, .noise = -1}), InvalidInput);
  EXPECT_THROW(sample_profile(ProfileDesign{"empty", {}}), InvalidInput);
  ProfileDesign broken{"broken", {RationalBezier::polynomial({{0, 0}, {1, 1}}), RationalBezier::polynomial({{2, 2}, {3, 3}})}};
  EXPECT_THROW(sample_profile(broken), InvalidInput);
  EXPECT_THROW(ball_profile(-1, 0), InvalidInput);
}

// The model files are what the designs, the seeded noise and the optimal linearization give
// (tests/bench/revolution/make_profile_models.cpp wrote them): nobody edited them by hand.
TEST(Profiles, ModelFilesAreReproducible) {
  struct Model {
    const char* file;
    ProfileDesign design;
    int points;
  };
  for (const Model& m : {Model{"goblet_profile", goblet_profile(), 237}, Model{"human_profile", human_profile(), 169},
                         Model{"goblet_cavity_profile", goblet_cavity_profile(), 120}}) {
    const DigitizedCurve file = load_curve(sculpt::test::models_dir() + "/" + m.file + ".txt");
    const DigitizedCurve made = sample_profile(m.design, {.points = m.points, .noise = 0.004, .seed = 1990});
    ASSERT_EQ(file.points.size(), made.points.size()) << m.file;
    for (std::size_t i = 0; i < made.points.size(); ++i) EXPECT_EQ(file.points[i], made.points[i]) << m.file << " " << i;
  }
  // The 20-segment goblet: 21 of the sampled points, in order, z increasing.
  const DigitizedCurve sampled = load_curve(sculpt::test::models_dir() + "/goblet_profile.txt");
  const DigitizedCurve lin = load_curve(sculpt::test::models_dir() + "/goblet_profile_20.txt");
  ASSERT_EQ(lin.points.size(), 21u);
  std::size_t at = 0;
  for (const auto& p : lin.points) {
    while (at < sampled.points.size() && sampled.points[at] != p) ++at;
    EXPECT_LT(at, sampled.points.size()) << "vertex " << p.transpose() << " is not a sample, in order";
  }
  for (std::size_t i = 1; i < lin.points.size(); ++i) EXPECT_GT(lin.points[i].y(), lin.points[i - 1].y());
}
