// Trees built on a branch of an arena (Arena::branch, take_planes; the cell merge's large status
// trees, bsp/local/cell_merge.cpp): the planes and opposites the branch adds, taken over in
// order, make the arena exactly what the same build on the arena itself makes, and the tree's
// planes map onto the same indices.
#include <gtest/gtest.h>

#include <vector>

#include "bsp/partition/autopartition.hpp"
#include "bsp/primitives.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/tree_arena.hpp"

namespace sculpt {
namespace {

using bsp::detail::Arena;

// An arena holding a solid, and its boundary on the arena's planes.
struct Loaded {
  Arena arena;
  FragmentList faces;
  explicit Loaded(const Solid& s) {
    arena.append(s);
    faces = arena.boundary_of(s);
  }
};

void expect_same_arena(Arena& a, Arena& b) {
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (std::int32_t p = 0; p < a.planes.size(); ++p) {
    ASSERT_EQ(a.planes[p], b.planes[p]) << p;
    ASSERT_EQ(a.planes.auxiliary(p), b.planes.auxiliary(p)) << p;
  }
  a.opposite_of.resize(std::size_t(a.planes.size()), -1);
  b.opposite_of.resize(std::size_t(b.planes.size()), -1);
  EXPECT_EQ(a.opposite_of, b.opposite_of);
}

TEST(ArenaBranch, ABuildOnABranchTakenOverIsTheBuildOnTheArena) {
  // A sphere's boundary: a tree of hundreds of fragments adds auxiliary planes (and their
  // opposites), and the flipped fragments' planes get opposites on first use.
  const Solid s = rotate(sphere(1.0, {.segments = 40}), {0.3, 1.0, 0.2}, 17.0);
  Loaded direct(s), branched(s);
  const bsp::detail::AutopartitionOptions options;
  const std::int32_t before = direct.arena.planes.size();
  const bsp::detail::PartitionTree want = bsp::detail::partition_fragments(direct.arena, direct.faces, options, {});
  ASSERT_GT(direct.arena.planes.size(), before) << "the build added no plane: the test tests nothing";

  bsp::detail::PartitionTree got;
  Arena::BranchPlanes added;
  {
    Arena branch = branched.arena.branch();
    got = bsp::detail::partition_fragments(branch, branched.faces, options, {});
    added = branch.added_planes();
  }
  EXPECT_EQ(branched.arena.planes.size(), before) << "the branch wrote into its parent";
  const Arena::PlaneMap map = branched.arena.take_planes(added);
  expect_same_arena(direct.arena, branched.arena);
  ASSERT_EQ(want.nodes.size(), got.nodes.size());
  EXPECT_EQ(want.root, got.root);
  for (std::size_t k = 0; k < want.nodes.size(); ++k) {
    EXPECT_EQ(want.nodes[k].plane, map(got.nodes[k].plane)) << k;
    EXPECT_EQ(want.nodes[k].negative, got.nodes[k].negative) << k;
    EXPECT_EQ(want.nodes[k].positive, got.nodes[k].positive) << k;
    EXPECT_EQ(want.nodes[k].auxiliary, got.nodes[k].auxiliary) << k;
  }
}

TEST(ArenaBranch, OppositesOfParentPlanesAndBranchesTakenInTurn) {
  const Solid s = sphere(1.0, {.segments = 8});
  Loaded direct(s), branched(s);
  // The parent already knows plane 6's opposite; planes 7 and 8 get theirs on the branches.
  direct.arena.opposite(6);
  branched.arena.opposite(6);
  const std::int32_t from = branched.arena.planes.size();
  Arena first = branched.arena.branch(), second = branched.arena.branch();
  EXPECT_EQ(first.opposite(6), direct.arena.opposite_of[6]);
  const std::int32_t o7 = first.opposite(7);
  EXPECT_EQ(o7, from);
  EXPECT_EQ(first.opposite(o7), 7);
  EXPECT_EQ(first.opposite(7), o7) << "made once";
  EXPECT_EQ(first.planes[o7], first.planes[7].opposite());
  EXPECT_EQ(second.opposite(8), from) << "each branch numbers its own planes from the parent's size";
  const Arena::BranchPlanes a = first.added_planes(), b = second.added_planes();
  (void)branched.arena.take_planes(a);
  (void)branched.arena.take_planes(b);
  // In turn: as if the first build, then the second, had run on the arena.
  direct.arena.opposite(7);
  direct.arena.opposite(8);
  expect_same_arena(direct.arena, branched.arena);
}

}  // namespace
}  // namespace sculpt
