#pragma once
/// \file bsp.hpp
/// Umbrella header of lib/bsp: solids as BSP trees: primitives, set operations, transforms, classification, boundaries.
/// Every public header of the layer (the headers directly in lib/bsp/).

#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/classify.hpp"
#include "bsp/convex_path.hpp"
#include "bsp/extrude.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/hull.hpp"
#include "bsp/point_classifier.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/solid.hpp"
#include "bsp/sweep.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree_builder.hpp"
#include "bsp/winding_solid.hpp"
