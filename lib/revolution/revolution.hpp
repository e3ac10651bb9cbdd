#pragma once
/// \file revolution.hpp
/// Umbrella header of lib/revolution: solids of revolution as balanced BSP trees (Ihm & Naylor 1990, sec. 6).
/// Every public header of the layer (the headers directly in lib/revolution/).

#include "revolution/revolve.hpp"
#include "revolution/revolve_boundary.hpp"
