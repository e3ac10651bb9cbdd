#pragma once
/// \file mesh_build_options.hpp
/// Internal: the autopartition settings (Thibault & Naylor 1987, expected-depth score) that
/// from_mesh's options stand for; from_mesh and rebuild_from_boundary build with them.

#include "bsp/from_mesh.hpp"
#include "bsp/partition/autopartition.hpp"

namespace sculpt::bsp::detail {

/// The autopartition options for `options` (approximate scores, as from_mesh builds; the caller
/// sets carry_boundary).
AutopartitionOptions mesh_build_options(const FromMeshOptions& options);

}  // namespace sculpt::bsp::detail
