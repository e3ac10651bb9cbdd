#include "mesh/formats/lib3mf_loader.hpp"

#include <dlfcn.h>

#include <string>

#include "base/errors.hpp"

namespace sculpt::mesh::detail {
namespace {

// The library by its soname (the runtime package's file), else the file CMake found.
void* open_library(std::string& why) {
  for (const char* name : {"lib3MF.so.1", SCULPT_LIB3MF_PATH}) {
    if (void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL)) return handle;
    const char* error = dlerror();
    why = error ? error : name;
  }
  return nullptr;
}

Lib3mf load() {
  std::string why;
  void* handle = open_library(why);
  if (!handle) throw InvalidInput("3MF files need lib3mf (Debian: lib3mf1), which could not be loaded: " + why);
  Lib3mf api;
  const char* missing = nullptr;
#define SCULPT_LIB3MF_LOAD(name)                                                   \
  api.name = reinterpret_cast<decltype(api.name)>(dlsym(handle, "lib3mf_" #name)); \
  if (!api.name && !missing) missing = "lib3mf_" #name;
  SCULPT_LIB3MF_FUNCTIONS(SCULPT_LIB3MF_LOAD)
#undef SCULPT_LIB3MF_LOAD
  if (missing) throw InvalidInput(std::string("3MF files need lib3mf 1.8; the loaded library has no ") + missing);
  return api;  // the handle stays open for the process
}

}  // namespace

const Lib3mf& lib3mf() {
  static const Lib3mf api = load();
  return api;
}

}  // namespace sculpt::mesh::detail
