// The public entry point: every method's contract, the monotonicity truths, bad input.
#include "curves/linearize.hpp"

#include <gtest/gtest.h>

#include <random>

#include "base/errors.hpp"
#include "curve_testing.hpp"
#include "curves/appendix_b_curves.hpp"

using namespace sculpt;
using namespace sculpt::curves;
using Vec = Eigen::Vector3d;

namespace {

const Method kCountMethods[] = {Method::Length, Method::Image,   Method::Init,         Method::Iter,
                                Method::Dynamic, Method::Optimal, Method::Fast, Method::CenterOfMass,
                                Method::DouglasPeucker};

void expect_contract(const DigitizedCurve& curve, const Linearization& la) {
  const int last = static_cast<int>(path_points(curve).size()) - 1;
  ASSERT_GE(la.indices.size(), 2u);
  EXPECT_EQ(la.indices.front(), 0);
  EXPECT_EQ(la.indices.back(), last);
  for (std::size_t k = 0; k + 1 < la.indices.size(); ++k) ASSERT_LT(la.indices[k], la.indices[k + 1]);
  EXPECT_EQ(la.error, linearization_error(curve, la));
}

DigitizedCurve small_curve(std::initializer_list<Vec> points, bool closed = false) {
  DigitizedCurve c;
  c.points = points;
  c.closed = closed;
  c.name = "small";
  return c;
}

}  // namespace

TEST(Linearize, EveryCountMethodGivesExactlyMSegments) {
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 150});
    for (Method method : kCountMethods)
      for (int m : {1, 2, 5, 16, 64}) {
        const Linearization la = linearize(curve, {.segments = m, .method = method});
        expect_contract(curve, la);
        EXPECT_EQ(la.segments(), m) << method_name(method) << " " << appendix_b_curve_name(which);
      }
  }
}

TEST(Linearize, NothingBeatsTheOptimum) {
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 30; ++trial) {
    const DigitizedCurve curve = curve_testing::random_curve(rng, 60, trial % 2 ? 3 : 2, trial % 3 == 0);
    for (int m : {3, 7, 20}) {
      const double optimum = linearize(curve, {.segments = m}).error;
      EXPECT_EQ(optimum, linearize(curve, {.segments = m, .method = Method::Dynamic}).error);
      for (Method method : kCountMethods) EXPECT_GE(linearize(curve, {.segments = m, .method = method}).error, optimum);
    }
  }
}

TEST(Linearize, IterNeverEndsWorseThanInit) {
  std::mt19937_64 rng(4);
  for (AppendixBCurve which : all_appendix_b_curves())
    for (double alpha : {0.0, 0.3, 0.5, 0.8, 1.0})
      for (int m : {4, 8, 16, 32, 64}) {
        const DigitizedCurve curve = make_appendix_b_curve(which, {.noise = alpha * 0.01, .seed = 3});
        const auto init = linearize(curve, {.segments = m, .method = Method::Init, .alpha = alpha});
        const auto iter = linearize(curve, {.segments = m, .method = Method::Iter, .alpha = alpha});
        EXPECT_LE(iter.error, init.error);
        expect_contract(curve, iter);
      }
}

TEST(Linearize, LengthAndImageAreInitWithAlphaOneAndZero) {
  const DigitizedCurve curve = make_appendix_b_curve(AppendixBCurve::Folium);
  EXPECT_EQ(linearize(curve, {.segments = 9, .method = Method::Length}).indices,
            linearize(curve, {.segments = 9, .method = Method::Init, .alpha = 1.0}).indices);
  EXPECT_EQ(linearize(curve, {.segments = 9, .method = Method::Image}).indices,
            linearize(curve, {.segments = 9, .method = Method::Init, .alpha = 0.0}).indices);
}

TEST(Linearize, LengthSubdividesAStraightEvenlySampledLineEvenly) {
  DigitizedCurve line;
  for (int k = 0; k <= 100; ++k) line.points.push_back({k * 0.5, k * 0.25, 0.0});
  const auto la = linearize(line, {.segments = 3, .method = Method::Length});
  // Each piece is the largest j with L_seg < total / m = 33.3 steps.
  EXPECT_EQ(la.indices, (std::vector<int>{0, 33, 66, 100}));
}

TEST(Linearize, BestOverAtMostMNeverGrowsWithM) {
  std::mt19937_64 rng(8);
  for (int trial = 0; trial < 20; ++trial) {
    const DigitizedCurve curve = curve_testing::random_curve(rng, 40, 2 + trial % 2);
    double best = 1e300;
    double previous_best = 1e300;
    for (int m = 1; m < 40; ++m) {
      best = std::min(best, linearize(curve, {.segments = m}).error);
      EXPECT_LE(best, previous_best);
      previous_best = best;
      EXPECT_LE(linearize(curve, {.tolerance = best}).segments(), m);
    }
  }
}

TEST(Linearize, ToleranceMethodsMeetTheTolerance) {
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 300, .noise = 0.002, .seed = 9});
    for (double tol : {0.0, 1e-3, 1e-2, 0.1, 1.0}) {
      const auto fewest = linearize(curve, {.tolerance = tol});
      expect_contract(curve, fewest);
      EXPECT_LE(fewest.error, tol);
      for (Method method : {Method::CenterOfMass, Method::DouglasPeucker}) {
        const auto la = linearize(curve, {.tolerance = tol, .method = method});
        expect_contract(curve, la);
        EXPECT_LE(la.error, tol);
        EXPECT_GE(la.segments(), fewest.segments());
      }
    }
  }
}

TEST(Linearize, ClosedCurveEndsAtTheFirstPointAgain) {
  const DigitizedCurve square = small_curve({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, true);
  const auto la = linearize(square, {.segments = 4});
  EXPECT_EQ(la.indices, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(la.error, 0.0);
  EXPECT_EQ(linearization_points(square, la).back(), Vec(0, 0, 0));
  // One segment of a closed curve: a degenerate chord, error = farthest distance from p0.
  EXPECT_DOUBLE_EQ(linearize(square, {.segments = 1}).error, std::sqrt(2.0));
}

TEST(Linearize, RepeatedAndCollinearPointsAreWellDefined) {
  const DigitizedCurve repeated = small_curve({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  for (Method method : kCountMethods) {
    const auto la = linearize(repeated, {.segments = 2, .method = method});
    EXPECT_EQ(la.error, 0.0);
    expect_contract(repeated, la);
  }
  EXPECT_EQ(linearize(repeated, {.tolerance = 0.0}).segments(), 1);
  DigitizedCurve line;
  for (int k = 0; k < 50; ++k) line.points.push_back({k * 1.0, 2.0 * k, -1.0 * k});
  EXPECT_EQ(linearize(line, {.tolerance = 0.0}).segments(), 1);
  for (Method method : kCountMethods) {
    const auto la = linearize(line, {.segments = 7, .method = method});
    EXPECT_EQ(la.segments(), 7);
    EXPECT_LE(la.error, 1e-12);
  }
}

TEST(Linearize, BadInputGivesClearErrors) {
  DigitizedCurve empty;
  EXPECT_THROW((void)linearize(empty, {.segments = 1}), InvalidInput);
  const DigitizedCurve one = small_curve({{1, 2, 3}});
  EXPECT_THROW((void)linearize(one, {.segments = 1}), InvalidInput);
  const DigitizedCurve three = small_curve({{0, 0, 0}, {1, 1, 0}, {2, 0, 0}});
  EXPECT_THROW((void)linearize(three, {.segments = 0, .method = Method::Optimal}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.segments = -3}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.segments = 3}), InvalidInput);  // at most 2
  EXPECT_NO_THROW((void)linearize(three, {.segments = 2}));
  EXPECT_THROW((void)linearize(three, {.segments = 1, .tolerance = 0.1}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.tolerance = -1.0}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.tolerance = std::nan("")}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.tolerance = 0.1, .method = Method::Iter}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.segments = 1, .method = Method::MinCount}), InvalidInput);
  EXPECT_THROW((void)linearize(three, {.segments = 1, .method = Method::Init, .alpha = 1.5}), InvalidInput);
  DigitizedCurve bad = three;
  bad.points[1].x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)linearize(bad, {.segments = 1}), InvalidInput);
  DigitizedCurve big;
  for (int k = 0; k < 2000; ++k) big.points.push_back({k * 1.0, std::sin(k * 0.1), 0.0});
  EXPECT_THROW((void)linearize(big, {.segments = 4, .method = Method::Dynamic}), InvalidInput);
  try {
    (void)linearize(three, {.segments = 5});
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("at most 2"), std::string::npos) << e.what();
  }
}

TEST(Linearize, MethodNamesRoundTrip) {
  for (Method method : kCountMethods) EXPECT_EQ(method_from_name(method_name(method)), method);
  EXPECT_EQ(method_from_name("ITER"), Method::Iter);
  EXPECT_EQ(method_from_name("dp"), Method::DouglasPeucker);
  EXPECT_EQ(method_from_name("mincount"), Method::MinCount);
  EXPECT_FALSE(method_from_name("bogus").has_value());
}

TEST(Linearize, L2NormIsHonouredEverywhere) {
  const DigitizedCurve curve = make_appendix_b_curve(AppendixBCurve::Sextic, {.points = 80});
  const double optimum = linearize(curve, {.segments = 6, .norm = Norm::L2}).error;
  EXPECT_EQ(optimum, linearize(curve, {.segments = 6, .method = Method::Dynamic, .norm = Norm::L2}).error);
  for (Method method : kCountMethods) {
    const auto la = linearize(curve, {.segments = 6, .method = method, .norm = Norm::L2});
    EXPECT_EQ(la.error, linearization_error(curve, la, Norm::L2));
    EXPECT_GE(la.error, optimum);
  }
}
