#pragma once
/// \file kernel.hpp
/// Umbrella header of lib/kernel: the exact geometric kernel: grid, integer planes, exact predicates, plane-based polygons.
/// Every public header of the layer (the headers directly in lib/kernel/).

#include "kernel/convex_hull.hpp"
#include "kernel/convex_polygon.hpp"
#include "kernel/exact_int.hpp"
#include "kernel/grid.hpp"
#include "kernel/plane.hpp"
#include "kernel/predicates.hpp"
#include "kernel/vertex_approximation.hpp"
#include "kernel/wide_int.hpp"
