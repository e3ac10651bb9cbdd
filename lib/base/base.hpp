#pragma once
/// \file base.hpp
/// Umbrella header of lib/base: typed errors shared by every layer, a container, the memory policy
/// of executables, the thread pool, cancellation (Ctrl-C).
/// Every public header of the layer (the headers directly in lib/base/).

#include "base/assert.hpp"
#include "base/cancel.hpp"
#include "base/chunked_vector.hpp"
#include "base/errors.hpp"
#include "base/memory_policy.hpp"
#include "base/parallel.hpp"
