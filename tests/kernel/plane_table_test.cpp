// PlaneTable's blocks shared between copies (kernel/plane_table.hpp): every table reads as a plain
// list would, whatever it shares, across block boundaries, and writes never reach another table.
// The reference is a std::vector<Plane> kept beside each table and changed the same way.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "kernel/plane_table.hpp"

namespace sculpt::kernel {
namespace {

Plane plane(int i) { return {1 + i % 7, 2 + i % 11, 3 + i, -Int128(i) * 1000}; }

// The world box's six planes, as a plain list.
std::vector<Plane> world() { return PlaneTable().to_vector(); }

void expect_same(const PlaneTable& table, const std::vector<Plane>& want, const std::vector<bool>& aux) {
  ASSERT_EQ(table.size(), std::int32_t(want.size()));
  for (std::int32_t i = 0; i < table.size(); ++i) {
    ASSERT_EQ(table[i], want[std::size_t(i)]) << "plane " << i;
    ASSERT_EQ(table.auxiliary(i), aux[std::size_t(i)]) << "plane " << i;
  }
}

TEST(PlaneTable, StartsWithTheWorldBoxAndReadsBackWhatWasAddedAcrossBlocks) {
  PlaneTable t;
  ASSERT_EQ(t.size(), 6);
  EXPECT_EQ(t[0], Plane(1, 0, 0, -PlaneTable::kWorld));
  EXPECT_EQ(t[5], Plane(0, 0, -1, -PlaneTable::kWorld));
  std::vector<Plane> want = world();
  std::vector<bool> aux(6, false);
  for (int i = 0; i < 3 * PlaneTable::kBlock + 17; ++i) {
    EXPECT_EQ(t.add(plane(i), i % 5 == 0), std::int32_t(want.size()));
    want.push_back(plane(i));
    aux.push_back(i % 5 == 0);
  }
  expect_same(t, want, aux);
  EXPECT_EQ(t.to_vector(), want);
}

TEST(PlaneTable, CopiesShareBlocksAndWritesNeverReachTheOtherTable) {
  PlaneTable a;
  std::vector<Plane> wa = world();
  std::vector<bool> xa(6, false);
  for (int i = 0; i < PlaneTable::kBlock + 100; ++i) a.add(plane(i)), wa.push_back(plane(i)), xa.push_back(false);
  PlaneTable b = a;
  std::vector<Plane> wb = wa;
  std::vector<bool> xb = xa;
  EXPECT_TRUE(b.shares_storage_with(a));
  // b writes into the shared partial last block, into a full shared block, and drops planes;
  // a adds where b's writes went.
  b.add(plane(-1), true), wb.push_back(plane(-1)), xb.push_back(true);
  b.replace(10, plane(-2), true), wb[10] = plane(-2), xb[10] = true;
  a.add(plane(-3)), wa.push_back(plane(-3)), xa.push_back(false);
  expect_same(a, wa, xa);
  expect_same(b, wb, xb);
  b.truncate(50), wb.resize(50), xb.resize(50);
  b.add(plane(-4)), wb.push_back(plane(-4)), xb.push_back(false);
  expect_same(a, wa, xa);
  expect_same(b, wb, xb);
  // A table truncated into a block it shares, then grown again, copies it first.
  PlaneTable c = a;
  c.truncate(PlaneTable::kBlock + 3);
  std::vector<Plane> wc(wa.begin(), wa.begin() + PlaneTable::kBlock + 3);
  std::vector<bool> xc(xa.begin(), xa.begin() + PlaneTable::kBlock + 3);
  for (int i = 0; i < 5; ++i) c.add(plane(100 + i)), wc.push_back(plane(100 + i)), xc.push_back(false);
  expect_same(a, wa, xa);
  expect_same(c, wc, xc);
}

TEST(PlaneTable, AppendCopiesFromAnyIndexOverBlockBoundaries) {
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    PlaneTable a, b;
    std::vector<Plane> wa = world(), wb = world();
    std::vector<bool> xa(6, false), xb(6, false);
    const int na = int(rng() % (2 * PlaneTable::kBlock)), nb = int(rng() % (3 * PlaneTable::kBlock));
    for (int i = 0; i < na; ++i) a.add(plane(i), i % 3 == 0), wa.push_back(plane(i)), xa.push_back(i % 3 == 0);
    for (int i = 0; i < nb; ++i) b.add(plane(-i), i % 4 == 0), wb.push_back(plane(-i)), xb.push_back(i % 4 == 0);
    const auto first = std::int32_t(rng() % std::uint32_t(b.size() + 1));
    PlaneTable before = a;
    EXPECT_EQ(a.append(b, first), std::int32_t(wa.size()));
    wa.insert(wa.end(), wb.begin() + first, wb.end());
    xa.insert(xa.end(), xb.begin() + first, xb.end());
    expect_same(a, wa, xa);
    expect_same(b, wb, xb);
    EXPECT_EQ(before.size(), std::int32_t(6 + na));  // the copy taken before is unchanged
  }
}

TEST(PlaneTable, AppendSharedPadsToABlockAndSharesTheOtherTablesBlocks) {
  for (const int na : {0, 5, PlaneTable::kBlock - 6, PlaneTable::kBlock + 1}) {
    PlaneTable a, b;
    std::vector<Plane> wa = world(), wb = world();
    std::vector<bool> xa(6, false), xb(6, false);
    for (int i = 0; i < na; ++i) a.add(plane(i)), wa.push_back(plane(i)), xa.push_back(false);
    for (int i = 0; i < PlaneTable::kBlock + 30; ++i)
      b.add(plane(-i), i % 2 == 0), wb.push_back(plane(-i)), xb.push_back(i % 2 == 0);
    const std::int32_t at = a.append_shared(b);
    EXPECT_EQ(at % PlaneTable::kBlock, 0);
    EXPECT_GE(at, std::int32_t(wa.size()));
    EXPECT_LT(at, std::int32_t(wa.size()) + PlaneTable::kBlock);
    while (std::int32_t(wa.size()) < at) wa.push_back(wa[0]), xa.push_back(false);  // the padding: plane 0
    wa.insert(wa.end(), wb.begin(), wb.end());
    xa.insert(xa.end(), xb.begin(), xb.end());
    expect_same(a, wa, xa);
    EXPECT_TRUE(a.shares_storage_with(b));
    // Writes on either side after the sharing stay on that side.
    a.add(plane(1000)), wa.push_back(plane(1000)), xa.push_back(false);
    a.replace(at + 7, plane(1001), true), wa[std::size_t(at + 7)] = plane(1001), xa[std::size_t(at + 7)] = true;
    b.add(plane(1002)), wb.push_back(plane(1002)), xb.push_back(false);
    b.replace(9, plane(1003), false), wb[9] = plane(1003), xb[9] = false;
    expect_same(a, wa, xa);
    expect_same(b, wb, xb);
  }
}

}  // namespace
}  // namespace sculpt::kernel
