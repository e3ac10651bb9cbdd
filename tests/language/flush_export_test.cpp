// Issue 35, "flush stays flush": a cylinder's vertex on a box face is exactly there, so the part's
// export reads back (import(export(f))) and rebuild(f) works, in every format that keeps doubles.
#include <gtest/gtest.h>

#include <string>

#include "script_runner.hpp"

namespace sculpt::language {
namespace {

TEST(FlushExport, CylinderOnABoxFaceReadsBackFromEveryFormat) {
  const std::string dir = ::testing::TempDir();
  for (const std::string ext : {"off", "obj", "ply", "stl", "3mf", "om", "glb"}) {
    const std::string file = dir + "sculpt_flush." + ext;
    const auto r = testing::run_script(
        "f = box([5,5,0],[10,10,40]) - translate(cylinder(5, 40, segments=8), [10,10,0])\n"
        "export(f, \"" +
        file +
        "\")\n"
        "g = import(\"" +
        file +
        "\")\n"
        "print(abs(volume(g) - volume(f)) < 1e-9, abs(volume(rebuild(f)) - volume(f)) < 1e-12)\n");
    EXPECT_EQ(r.error, "") << ext;
    EXPECT_EQ(r.out, "true true\n") << ext;
  }
}

}  // namespace
}  // namespace sculpt::language
