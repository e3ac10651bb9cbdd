#pragma once
/// \file implicit.hpp
/// The implicit layer (Ihm & Naylor 1990, sec. 5): functions R^3 -> R in a compact expression
/// form with values, exact gradients and interval bounds, and the tracing of curves f = g = 0.

#include "implicit/expression.hpp"
#include "implicit/trace.hpp"
