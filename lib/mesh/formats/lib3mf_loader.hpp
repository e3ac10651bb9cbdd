#pragma once
/// \file lib3mf_loader.hpp
/// Internal to the 3MF codec (threemf_format.cpp): lib3mf's C functions, loaded on first use.
/// Linked at start-up, lib3mf and the libraries it needs (libzip, which needs libcrypto) were
/// about 2.3 MB of every sculpt process's resident memory and part of its start, whether or not
/// it ever read or wrote a 3MF file (docs/mesh_io.md, "3MF").

#include <Model/COM/NMR_DLLInterfaces.h>

namespace sculpt::mesh::detail {

// The functions the codec calls, without their lib3mf_ prefix (a list clang-format would reflow).
// clang-format off
#define SCULPT_LIB3MF_FUNCTIONS(X)                                                                \
  X(builditem_getobjectresource) X(builditem_getobjecttransform) X(builditem_hasobjecttransform)  \
  X(builditem_setuuidutf8) X(builditemiterator_getcurrent) X(builditemiterator_movenext)          \
  X(createmodel) X(getlasterror) X(meshobject_gettrianglecount) X(meshobject_gettriangleindices)  \
  X(meshobject_getvertexcount) X(meshobject_getvertices) X(meshobject_setgeometry)                \
  X(model_addbuilditem) X(model_addmeshobject) X(model_getbuilditems) X(model_getunit)            \
  X(model_queryreader) X(model_querywriter) X(model_setbuilduuidutf8) X(model_setunit)            \
  X(object_ismeshobject) X(object_setuuidutf8) X(reader_readfrombuffer) X(release)                \
  X(writer_getstreamsize) X(writer_writetobuffer)
// clang-format on

/// Pointers to lib3mf's functions: `lib3mf().createmodel(...)` calls NMR::lib3mf_createmodel.
struct Lib3mf {
#define SCULPT_LIB3MF_MEMBER(name) decltype(&NMR::lib3mf_##name) name = nullptr;
  SCULPT_LIB3MF_FUNCTIONS(SCULPT_LIB3MF_MEMBER)
#undef SCULPT_LIB3MF_MEMBER
};

/// lib3mf, loaded by the first call (thread-safe) and kept for the process. Throws InvalidInput
/// naming the library and the loader's message when it cannot be loaded.
const Lib3mf& lib3mf();

}  // namespace sculpt::mesh::detail
