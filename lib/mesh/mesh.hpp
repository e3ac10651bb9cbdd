#pragma once
/// \file mesh.hpp
/// Umbrella header of lib/mesh: polygon meshes: exact predicates, triangulation, measures, validation, file I/O.
/// Every public header of the layer (the headers directly in lib/mesh/).

#include "mesh/edge_incidence.hpp"
#include "mesh/mesh_io.hpp"
#include "mesh/mesh_measures.hpp"
#include "mesh/mesh_validation.hpp"
#include "mesh/output_rounding.hpp"
#include "mesh/polygon_mesh.hpp"
#include "mesh/predicates.hpp"
#include "mesh/self_intersection.hpp"
#include "mesh/shell_orientation.hpp"
#include "mesh/triangulate.hpp"
