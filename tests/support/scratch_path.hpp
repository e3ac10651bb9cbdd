#pragma once
/// \file scratch_path.hpp
/// Paths under a folder of the system's temporary folder that is this test process's own and is
/// removed when the process ends: ctest runs the tests of one file as separate processes side by
/// side (and CI may run two suites at once), so a fixed name would let one test remove or
/// overwrite another's files.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace sculpt::test {

/// temp/sculpt_test_<pid>/<name>: `name` may be a folder or a file name (its extension is kept).
inline std::filesystem::path scratch_path(const std::string& name) {
  struct Root {
    std::filesystem::path path;
    ~Root() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Root root{[] {
    const auto p = std::filesystem::temp_directory_path() / ("sculpt_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
  }()};
  return root.path / name;
}

}  // namespace sculpt::test
