// write_mesh replaces files atomically: on any failure the previous file is untouched and
// no temporary file is left behind.
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/errors.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh_test_dir.hpp"
#include "shapes.hpp"

namespace sculpt {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Number of entries in a directory.
size_t entries(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = test_dir() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(AtomicWrite, ReplacesTheFileAndLeavesNoTemporary) {
  const fs::path dir = fresh_dir("replace");
  const fs::path path = dir / "m.off";
  { std::ofstream(path) << "old"; }
  write_mesh(test_shapes::unit_cube(), path);
  EXPECT_EQ(contents(path), encode_mesh(test_shapes::unit_cube(), MeshFormat::Off));
  EXPECT_EQ(entries(dir), 1u);
}

TEST(AtomicWrite, MissingDirectoryIsAnIoErrorNamingThePath) {
  const fs::path path = test_dir() / "no" / "such" / "dir" / "m.off";
  try {
    write_mesh(test_shapes::unit_cube(), path);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), path.string());
    EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot create a temporary file"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("No such file or directory"));
  }
}

TEST(AtomicWrite, UnwritableDirectoryKeepsThePreviousFile) {
  const fs::path dir = fresh_dir("readonly");
  const fs::path path = dir / "m.stl";
  { std::ofstream(path) << "previous"; }
  ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
  // Root ignores directory permissions: find out whether this process can still create files
  // (then a directory of sysfs stands in; the previous file is covered by FailureDuringWrite).
  const bool bypass = ::access(dir.c_str(), W_OK) == 0;
  if (!bypass) {
    EXPECT_THROW(write_mesh(test_shapes::unit_cube(), path), IoError);
    EXPECT_EQ(contents(path), "previous");
    EXPECT_EQ(entries(dir), 1u);
  }
  ::chmod(dir.c_str(), 0755);
  if (bypass) {
    // Root: sysfs refuses new files to everyone.
    if (!fs::is_directory("/sys/kernel")) GTEST_SKIP() << "running as root without /sys: nothing refuses writes";
    try {
      write_mesh(test_shapes::unit_cube(), "/sys/kernel/sculpt_mesh_test.off");
      ADD_FAILURE() << "no error";
    } catch (const IoError& e) {
      EXPECT_EQ(e.path(), "/sys/kernel/sculpt_mesh_test.off");
      EXPECT_THAT(e.what(), ::testing::HasSubstr("cannot create a temporary file in '/sys/kernel'"));
    }
  }
}

TEST(AtomicWrite, FailureDuringWriteKeepsThePreviousFileAndRemovesTheTemporary) {
  // A file size limit makes write() fail with EFBIG part way through (SIGXFSZ ignored):
  // this works for root too.
  const fs::path dir = fresh_dir("fsize");
  const fs::path path = dir / "big.obj";
  { std::ofstream(path) << "previous"; }
  const PolygonMesh big = test_shapes::uv_sphere(64);
  ASSERT_GT(encode_mesh(big, MeshFormat::Obj).size(), 8192u);
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  try {
    write_mesh(big, path);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), path.string());
    EXPECT_THAT(e.what(), ::testing::HasSubstr("write failed after 4096 of"));
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(contents(path), "previous");
  EXPECT_EQ(entries(dir), 1u);
}

TEST(AtomicWrite, TargetThatIsADirectoryIsAnIoError) {
  const fs::path dir = fresh_dir("isdir");
  fs::create_directories(dir / "m.ply");
  EXPECT_THROW(write_mesh(test_shapes::unit_cube(), dir / "m.ply"), IoError);
  EXPECT_TRUE(fs::is_directory(dir / "m.ply"));
  EXPECT_EQ(entries(dir), 1u);
  EXPECT_THROW(read_mesh(dir / "m.ply"), IoError);
}

}  // namespace
}  // namespace sculpt
