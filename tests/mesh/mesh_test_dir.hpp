#pragma once
// A fresh scratch directory per test process (under the system temp dir).
#include <unistd.h>

#include <filesystem>
#include <string>

namespace sculpt {

inline std::filesystem::path test_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("sculpt_mesh_test_" + std::to_string(::getpid()));
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace sculpt
