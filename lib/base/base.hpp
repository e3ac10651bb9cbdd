#pragma once
/// \file base.hpp
/// Umbrella header of lib/base: typed errors shared by every layer.
/// Every public header of the layer (the headers directly in lib/base/).

#include "base/errors.hpp"
