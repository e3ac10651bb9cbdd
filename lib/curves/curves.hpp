#pragma once
/// \file curves.hpp
/// Umbrella header of lib/curves: digitized curves and their piecewise linear approximation (Ihm & Naylor 1990, sec. 2-4).
/// Every public header of the layer (the headers directly in lib/curves/).

#include "curves/appendix_b_curves.hpp"
#include "curves/curve_measures.hpp"
#include "curves/digitized_curve.hpp"
#include "curves/linearization.hpp"
#include "curves/linearize.hpp"
#include "curves/profiles.hpp"
#include "curves/rational_bezier.hpp"
#include "curves/segment_error.hpp"
