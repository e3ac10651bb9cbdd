#pragma once
/// \file source_paths.hpp
/// Where the tests find the source tree's data (scripts/, docs/, models/). The paths live in one
/// generated file (source_paths.cpp.in, configured by tests/CMakeLists.txt), not in every test
/// object as macros: a clone in another folder then differs from the cached objects of an earlier
/// build in that one file alone (docs/building.md, "Compiler cache").

#include <string>

namespace sculpt::test {

/// The source tree's root (the folder of the top-level CMakeLists.txt).
const std::string& source_dir();

/// The source tree's models/ folder.
const std::string& models_dir();

}  // namespace sculpt::test
