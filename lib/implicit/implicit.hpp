#pragma once
/// \file implicit.hpp
/// The implicit layer (Ihm & Naylor 1990, sec. 5): functions R^3 -> R in a compact expression
/// form with values, exact gradients and interval bounds, the tracing of curves f = g = 0
/// (sec. 5.1) and the adaptive polygonization of surface patches f = 0 (sec. 5.2).

#include "implicit/expression.hpp"
#include "implicit/patch.hpp"
#include "implicit/polygonize.hpp"
#include "implicit/trace.hpp"
