#pragma once
/// \file splines.hpp
/// The splines layer's public API in one include (see docs/splines.md).
#include "splines/approximate.hpp"
#include "splines/bspline.hpp"
#include "splines/bspline_surface.hpp"
#include "splines/degree_reduction.hpp"
#include "splines/fit.hpp"
#include "splines/fit_surface.hpp"
#include "splines/foot_point.hpp"
#include "splines/motion.hpp"
#include "splines/offset.hpp"
#include "splines/spline_io.hpp"
#include "splines/surface_curves.hpp"
#include "splines/tessellate_surface.hpp"
