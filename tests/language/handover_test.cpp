// Copy on write for solids in scripts: `w = carve(w, ...)`, `w = add(w, ...)` and `w = w - x`
// hand w's value over to the built-in or operator (Interpreter, eval_assigned), which then
// reuses its tree (the in-place set operations) instead of copying it, while every other holder
// of the old value keeps seeing it unchanged (value semantics). Checked by volumes against
// independent analytic values, by set equality with the copying path, and by the planes the
// storage's layout (a copy is compacted: depth-first, every node reached and every plane used).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "bsp/boundary.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/sweep.hpp"
#include "language/interpreter.hpp"
#include "language/solid_values.hpp"
#include "script_runner.hpp"

namespace sculpt::language {
namespace {

using testing::text_source;

struct Session {
  std::ostringstream out;
  Interpreter interpreter{{.out = &out}};
  void run(const std::string& text) { interpreter.run(text_source(text)); }
  const Solid& solid(const std::string& name) {
    const Value* v = interpreter.global(name);
    EXPECT_NE(v, nullptr) << name;
    const SolidValue* s = v ? v->object<SolidValue>() : nullptr;
    EXPECT_NE(s, nullptr) << name;
    static const Solid empty;
    return s ? s->solid : empty;
  }
  std::string error(const std::string& text) {
    try {
      run(text);
    } catch (const ScriptError& e) {
      return format_error(e);
    }
    return {};
  }
};

/// The solid's storage is not laid out as a copy's. A copying operation compacts its result: the
/// root is node 0, the nodes are numbered in depth-first order (positive child first), every node
/// is reached and every plane past the six world-box planes is used. An in-place operation
/// renumbers nothing that was there: the nodes it adds go after the old ones, wherever they hang
/// in the tree, so the depth-first numbering breaks (or unreachable nodes or unused planes remain).
bool worked_in_place(const Solid& s) {
  if (is_leaf(s.root())) return false;
  std::vector<bool> used(std::size_t(s.planes().size()), false);
  auto use_polygon = [&](kernel::PolygonView p) {
    if (p.support >= 0) used[std::size_t(p.support)] = true;
    for (const auto& c : p.corners) used[std::size_t(c.edge)] = used[std::size_t(c.p)] = used[std::size_t(c.q)] = true;
  };
  std::vector<TreeRef> stack{s.root()};
  TreeRef expected = 0;
  bool depth_first = true;
  while (!stack.empty()) {
    const TreeRef r = stack.back();
    stack.pop_back();
    if (is_leaf(r)) continue;
    depth_first = depth_first && r == expected++;
    const BspNode& n = s.nodes()[std::size_t(r)];
    used[std::size_t(n.plane)] = true;
    use_polygon(s.polygons()[std::size_t(r)]);
    stack.push_back(n.negative);
    stack.push_back(n.positive);
  }
  for (const FragmentRef f : s.boundary()) use_polygon(f.polygon);
  const bool all_used = std::count(used.begin() + std::min<std::ptrdiff_t>(6, std::ptrdiff_t(used.size())), used.end(), false) == 0;
  return !depth_first || std::size_t(expected) != s.nodes().size() || !all_used;
}

bool same_set(const Solid& a, const Solid& b) { return (a - b).is_empty() && (b - a).is_empty(); }

// A 6 x 5 x 1.5 block and four unit cubes away from it (so that the workpiece's tree is larger
// than a stroke's: the in-place operation reuses the larger operand); a unit cube tool along an L
// in the plane z = 0 sweeps two slabs (4 x 1 x 1 and 1 x 3 x 1 sharing a unit cube: volume 6),
// half of which (z in [0, 0.5]) is in the block.
constexpr const char* kSetup =
    "b = box([0,0,0],[1,1,1])\n"
    "path = [[0,0,0],[3,0,0],[3,2,0]]\n"
    "fn workpiece() { return box([-1,-1,-1],[5,4,0.5]) | box([10,0,0],[11,1,1]) | box([12,0,0],[13,1,1]) "
    "| box([14,0,0],[15,1,1]) | box([10,2,0],[11,3,1]) }\n"
    "w = workpiece()\n"
    "full = volume(w)\n";
constexpr double kBlock = 6.0 * 5.0 * 1.5 + 4.0;

TEST(Handover, CarveInPlaceWhenTheVariableAloneHoldsTheSolid) {
  Session s;
  s.run(kSetup);
  s.run("w = carve(w, b, path)");
  EXPECT_TRUE(worked_in_place(s.solid("w")));
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
  s.run("w = add(w, b, path)");
  EXPECT_TRUE(worked_in_place(s.solid("w")));
  EXPECT_EQ(volume(s.solid("w")), kBlock + 3.0);  // the whole L, carved half and all
  s.run("w = w - box([-1,-1,-1],[0,0,0])");
  EXPECT_TRUE(worked_in_place(s.solid("w")));
  EXPECT_EQ(volume(s.solid("w")), kBlock + 3.0 - 1.0);
  Session t;  // an operator in place
  t.run(kSetup);
  t.run("w = w - box([-1,-1,-1],[0,0,0])");
  EXPECT_TRUE(worked_in_place(t.solid("w")));
  EXPECT_EQ(volume(t.solid("w")), kBlock - 1.0);
  // The same strokes on the copying path (another variable holds the workpiece) give the same set.
  s.run(
      "x = workpiece()\nkeep = x\nx = carve(x, b, path)\nkeep2 = x\nx = add(x, b, path)\n"
      "keep3 = x\nx = x - box([-1,-1,-1],[0,0,0])");
  EXPECT_FALSE(worked_in_place(s.solid("x")));
  EXPECT_TRUE(same_set(s.solid("w"), s.solid("x")));
}

TEST(Handover, OtherHoldersKeepTheOldValue) {
  Session s;
  s.run(kSetup);
  s.run("v = w\nlist = [w, 1]\nw = carve(w, b, path)");
  EXPECT_EQ(volume(s.solid("v")), kBlock);
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
  EXPECT_FALSE(worked_in_place(s.solid("w")));  // copied: v still holds the block
  const List* list = s.interpreter.global("list")->list();
  ASSERT_NE(list, nullptr);
  EXPECT_EQ(volume((*list)[0].object<SolidValue>()->solid), kBlock);
  // w - w, a variable used twice, and v = w before `w = w - ...`.
  s.run("u = v\nu = u - u\nv2 = v\nv = v | box([10,10,10],[11,11,11])");
  EXPECT_TRUE(s.solid("u").is_empty());
  EXPECT_EQ(volume(s.solid("v2")), kBlock);
  EXPECT_EQ(volume(s.solid("v")), kBlock + 1.0);
  s.run("y = box([0,0,0],[2,2,2])\ny = carve(y, y, [[0,0,0]])");
  EXPECT_TRUE(s.solid("y").is_empty());
}

TEST(Handover, FunctionsAndArgumentsSeeTheValueUntilTheCall) {
  Session s;
  s.run(kSetup);
  // Later arguments read w before it is handed over.
  s.run("fn path_of_w() { return [[0,0,volume(w) - full],[3,0,0],[3,2,0]] }\nw = carve(w, b, path_of_w())");
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
  // In a function, `w = carve(w, ...)` on a global makes a local: the global stays.
  s.run("fn f() { w = carve(w, b, [[0,0,-1]]) \n return volume(w) }\ninner = f()");
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
  EXPECT_EQ(*s.interpreter.global("inner")->get<double>(), kBlock - 3.0 - 1.0);
  // A parameter is a second holder of the caller's value: the caller's variable is unchanged.
  s.run("fn g(p) { p = carve(p, b, [[0,0,-1]]) \n p = p - b \n return volume(p) }\nr = g(w)");
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
  EXPECT_EQ(*s.interpreter.global("r")->get<double>(), kBlock - 3.0 - 1.0);
  // A local workpiece is taken in place.
  s.run("fn h() { q = box([0,0,0],[4,4,4]) \n q = carve(q, b, [[1,1,1]]) \n q = q - b \n return volume(q) }\nt = h()");
  EXPECT_EQ(*s.interpreter.global("t")->get<double>(), 64.0 - 1.0 - 1.0);
}

TEST(Handover, AFailedStatementKeepsTheVariable) {
  Session s;
  s.run(kSetup);
  EXPECT_NE(s.error("w = carve(w, b, [])").find("the path has no points"), std::string::npos);
  EXPECT_EQ(volume(s.solid("w")), kBlock);
  EXPECT_NE(s.error("w = carve(w, 3, path)").find("must be a solid"), std::string::npos);
  EXPECT_EQ(volume(s.solid("w")), kBlock);
  EXPECT_NE(s.error("w = w - 3").find("cannot apply '-'"), std::string::npos);
  EXPECT_EQ(volume(s.solid("w")), kBlock);
  // A solid at another grid cannot be combined (GridMismatch before anything is taken).
  s.run("old = grid()\ngrid(pow(2, -10))\nfine = box([0,0,0],[1,1,1])\ngrid(old)");
  EXPECT_NE(s.error("w = w - fine").find("grid"), std::string::npos);
  EXPECT_EQ(volume(s.solid("w")), kBlock);
  EXPECT_NE(s.error("w = carve(w, fine, path)").find("grid"), std::string::npos);
  EXPECT_EQ(volume(s.solid("w")), kBlock);
  s.run("w = carve(w, b, path)");
  EXPECT_EQ(volume(s.solid("w")), kBlock - 3.0);
}

TEST(Handover, ManyStrokesEqualTheLibraryInPlace) {
  // Twenty strokes of a small box along short paths, through the script and the library.
  Session s;
  s.run(
      "b = box([0,0,0],[0.5,0.5,0.5])\nw = box([-1,-1,-1],[5,4,0.5])\n"
      "for i in range(0, 20) { w = carve(w, b, [[i / 5, 0, 0.25 - i / 40], [i / 5, 3, 0], [i / 4, 3, -0.25]]) }");
  const kernel::Grid grid;
  Solid work = box({-1, -1, -1}, {5, 4, 0.5}, grid);
  const Solid tool = box({0, 0, 0}, {0.5, 0.5, 0.5}, grid);
  for (int i = 0; i < 20; ++i) {
    const std::vector<Eigen::Vector3d> path{{i / 5.0, 0, 0.25 - i / 40.0}, {i / 5.0, 3, 0}, {i / 4.0, 3, -0.25}};
    const Solid swept = sweep(tool, path);
    const double expected = volume(work) - volume(work & swept);
    work = carve(std::move(work), tool, path);
    EXPECT_NEAR(volume(work), expected, 1e-9 * expected) << i;  // volumes of slanted cells round
  }
  EXPECT_TRUE(same_set(s.solid("w"), work));
}

}  // namespace
}  // namespace sculpt::language
