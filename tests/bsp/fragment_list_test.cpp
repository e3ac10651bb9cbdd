// FragmentList (bsp/fragment_list.hpp) against a plain vector of fragments doing the same edits:
// random pushes, replacements (from outside and from the list itself), removals, flips,
// renumbering, appends of short and long lists, copies and packing. After every step the two
// must hold the same fragments, corner for corner, to the last bit of every approximation.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bsp/fragment_list.hpp"

namespace sculpt {
namespace {

using kernel::ApproxPoint;
using kernel::ConvexPolygon;
using kernel::Corner;

BoundaryFragment random_fragment(std::mt19937& rng, std::size_t max_corners) {
  std::uniform_int_distribution<int> plane(0, 1000);
  std::uniform_int_distribution<std::size_t> count(0, max_corners);
  std::uniform_real_distribution<double> coordinate(-1e6, 1e6);
  BoundaryFragment f;
  f.polygon.support = plane(rng);
  f.flip = rng() % 2 == 1;
  const std::size_t n = count(rng);
  for (std::size_t i = 0; i < n; ++i)
    f.polygon.corners.push_back(
        Corner(plane(rng), plane(rng), plane(rng),
               ApproxPoint{coordinate(rng), coordinate(rng), coordinate(rng), 1e-9 * double(i)}));
  return f;
}

bool same_corner(const Corner& a, const Corner& b) {
  const ApproxPoint x = a.at(), y = b.at();
  return a.edge == b.edge && a.p == b.p && a.q == b.q && x.x == y.x && x.y == y.y && x.z == y.z && x.err == y.err;
}

void expect_same(const FragmentList& list, const std::vector<BoundaryFragment>& model, int step) {
  ASSERT_EQ(list.size(), model.size()) << "step " << step;
  std::size_t i = 0;
  for (const FragmentRef f : list) {  // the iterator and operator[] agree
    const FragmentRef g = list[i];
    ASSERT_EQ(f.polygon.corners.data(), g.polygon.corners.data());
    const BoundaryFragment& m = model[i];
    ASSERT_EQ(f.polygon.support, m.polygon.support) << "step " << step << " fragment " << i;
    ASSERT_EQ(f.flip, m.flip) << "step " << step << " fragment " << i;
    ASSERT_EQ(f.polygon.corners.size(), m.polygon.corners.size()) << "step " << step << " fragment " << i;
    for (std::size_t k = 0; k < m.polygon.corners.size(); ++k)
      ASSERT_TRUE(same_corner(f.polygon.corners[k], m.polygon.corners[k])) << "step " << step << " fragment " << i;
    ++i;
  }
}

TEST(FragmentList, RandomEditsAgreeWithAVectorOfFragments) {
  std::mt19937 rng(7);
  FragmentList list;
  std::vector<BoundaryFragment> model;
  for (int step = 0; step < 2000; ++step) {
    const int what = int(rng() % 100);
    if (what < 40 || model.empty()) {  // push (now and then a polygon larger than a corner block)
      const BoundaryFragment f = random_fragment(rng, rng() % 50 == 0 ? 1500 : 6);
      list.push_back(f);
      model.push_back(f);
    } else if (what < 55) {  // replace by a new fragment
      const std::size_t i = rng() % model.size();
      const BoundaryFragment f = random_fragment(rng, 8);
      list.replace(i, f.polygon, f.flip);
      model[i] = f;
    } else if (what < 65) {  // replace by the last one and remove that (as the boundary merge does)
      const std::size_t i = rng() % model.size();
      const FragmentRef last = list.back();
      list.replace(i, last.polygon, last.flip);
      list.pop_back();
      model[i] = model.back();
      model.pop_back();
    } else if (what < 72) {
      const std::size_t i = rng() % model.size();
      list.set_flip(i, !list[i].flip);
      model[i].flip = !model[i].flip;
    } else if (what < 78) {  // renumber one fragment, or all
      auto map = [](std::int32_t p) { return 1000 - p; };
      auto apply = [&](BoundaryFragment& f) {
        f.polygon.support = map(f.polygon.support);
        for (Corner& c : f.polygon.corners) c.edge = map(c.edge), c.p = map(c.p), c.q = map(c.q);
      };
      if (rng() % 2) {
        const std::size_t i = rng() % model.size();
        list.renumber_planes(i, map);
        apply(model[i]);
      } else {
        list.renumber_planes(map);
        for (BoundaryFragment& f : model) apply(f);
      }
    } else if (what < 88) {  // append a short list (copied) or a long one (its blocks taken over)
      FragmentList more;
      const std::size_t n = rng() % 2 ? rng() % 5 : 2000 + rng() % 800;  // 3 corners each on average
      for (std::size_t k = 0; k < n; ++k) {
        const BoundaryFragment f = random_fragment(rng, 6);
        more.push_back(f);
        model.push_back(f);
      }
      list.append(std::move(more));
      EXPECT_TRUE(more.empty());
    } else if (what < 93) {
      list.truncate(model.size() / 2);
      model.resize(model.size() / 2);
    } else if (what < 97) {
      list.pack_if_sparse();
    } else {  // copies and moves
      FragmentList copy(list);
      expect_same(copy, model, step);
      FragmentList moved(std::move(copy));
      EXPECT_TRUE(copy.empty());
      list = moved;
    }
    if (step % 4 == 0 || model.size() < 200) expect_same(list, model, step);
    if (testing::Test::HasFatalFailure()) return;
  }
}

TEST(FragmentList, ATriangleTakesItsCornersAndSixteenBytes) {
  // The point of the compact list: no room for a fourth corner, no separate corner vector.
  std::mt19937 rng(3);
  FragmentList list;
  BoundaryFragment triangle = random_fragment(rng, 0);
  for (int i = 0; i < 3; ++i) triangle.polygon.corners.push_back(Corner(1, 2, 3, ApproxPoint{0, 0, 0, 0}));
  constexpr std::size_t n = 100000;
  for (std::size_t i = 0; i < n; ++i) list.push_back(triangle);
  const double per_fragment = double(list.bytes()) / double(n);
  EXPECT_LE(per_fragment, 1.02 * (16 + 3 * sizeof(Corner)) + 1);
  EXPECT_GE(per_fragment, 16 + 3 * sizeof(Corner));
  // A copy packs: an append of blocks taken over and a packing leave no more than the copy.
  FragmentList copy(list);
  EXPECT_LE(copy.bytes(), list.bytes());
}

}  // namespace
}  // namespace sculpt
