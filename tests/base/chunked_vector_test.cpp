// ChunkedVector (base/chunked_vector.hpp): the same sequence as a std::vector under random
// operations, elements that never move while it grows, copies that are deep, the chunks freed by
// shrink_to_fit, and long lists that leave at most one chunk (4096 elements) unused.
#include "base/chunked_vector.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace sculpt {
namespace {

TEST(ChunkedVector, RandomOperationsMatchAStdVector) {
  std::mt19937 rng(7);
  ChunkedVector<std::string> c;
  std::vector<std::string> v;
  for (int step = 0; step < 20000; ++step) {
    const int what = int(rng() % 10);
    if (what < 5) {
      const std::string s = std::to_string(rng() % 1000000) + std::string(rng() % 40, 'x');  // heap strings too
      c.push_back(s);
      v.push_back(s);
    } else if (what < 7 && !v.empty()) {
      c.pop_back();
      v.pop_back();
    } else if (what == 7) {
      const std::size_t n = rng() % (v.size() + 40);
      c.resize(n);
      v.resize(n);
    } else if (what == 8 && !v.empty()) {
      const std::size_t i = rng() % v.size();
      c[i] += "!";
      v[i] += "!";
    } else {
      c.emplace_back(3, 'y');
      v.emplace_back(3, 'y');
    }
    ASSERT_EQ(c.size(), v.size());
    ASSERT_GE(c.capacity(), c.size());
    if (!v.empty()) {
      ASSERT_EQ(c.back(), v.back());
    }
  }
  ASSERT_EQ(std::vector<std::string>(c.begin(), c.end()), v);
  std::sort(c.begin(), c.end());  // random access iterators
  std::sort(v.begin(), v.end());
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(c[i], v[i]);
}

TEST(ChunkedVector, ElementsStayWhereTheyAreWhileItGrows) {
  ChunkedVector<int> c;
  std::vector<const int*> at;
  for (int i = 0; i < 100000; ++i) {
    c.push_back(i);
    at.push_back(&c.back());
  }
  for (int i = 0; i < 100000; ++i) {
    ASSERT_EQ(at[std::size_t(i)], &c[std::size_t(i)]);
    ASSERT_EQ(c[std::size_t(i)], i);
  }
}

TEST(ChunkedVector, LongListsLeaveAtMostOneChunkUnused) {
  // Sizes around the end of the doubling chunks (4080 elements) and far past it.
  for (const std::size_t n : {std::size_t(4079), std::size_t(4080), std::size_t(4081), std::size_t(8176),
                              std::size_t(8177), std::size_t(100000), std::size_t(250001)}) {
    ChunkedVector<std::size_t> c;
    for (std::size_t i = 0; i < n; ++i) c.push_back(i * 7 + 1);
    ASSERT_GE(c.capacity(), n);
    EXPECT_LT(c.capacity() - n, 4096u) << n;
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(c[i], i * 7 + 1) << n;
    c.resize(n / 3);
    c.shrink_to_fit();
    EXPECT_LT(c.capacity() - c.size(), 4096u) << n;
    for (std::size_t i = 0; i < n / 3; ++i) ASSERT_EQ(c[i], i * 7 + 1) << n;
  }
}

TEST(ChunkedVector, CopiesAreDeepMovesTakeTheStorageShrinkFreesChunks) {
  ChunkedVector<std::unique_ptr<int>> owners;
  for (int i = 0; i < 1000; ++i) owners.push_back(std::make_unique<int>(i));
  ChunkedVector<std::unique_ptr<int>> moved = std::move(owners);
  EXPECT_TRUE(owners.empty());
  ASSERT_EQ(moved.size(), 1000u);
  EXPECT_EQ(*moved[999], 999);

  ChunkedVector<std::vector<int>> a(std::vector<std::vector<int>>{{1, 2}, {3}});
  ChunkedVector<std::vector<int>> b = a;
  b[0].push_back(9);
  EXPECT_EQ(a[0].size(), 2u);
  EXPECT_EQ(b[0].size(), 3u);
  b = a;
  EXPECT_EQ(b[0], a[0]);

  ChunkedVector<int> c;
  c.resize(5000);
  const std::size_t big = c.capacity();
  c.resize(10);
  c.shrink_to_fit();
  EXPECT_LT(c.capacity(), big);
  EXPECT_GE(c.capacity(), 10u);
  c.clear();
  c.shrink_to_fit();
  EXPECT_EQ(c.capacity(), 0u);
  c.reserve(100);
  EXPECT_GE(c.capacity(), 100u);
  EXPECT_TRUE(c.empty());
}

}  // namespace
}  // namespace sculpt
