#pragma once
/// \file sculpt.hpp
/// The sculpt library: every layer below the scripting language, through their umbrella headers.
/// Installed as <sculpt/sculpt.hpp> (link sculpt::sculpt after find_package(sculpt)); README.md
/// shows a short program and docs/architecture.md the layers.

#include "base/base.hpp"
#include "kernel/kernel.hpp"
#include "curves/curves.hpp"
#include "splines/splines.hpp"
#include "implicit/implicit.hpp"
#include "mesh/mesh.hpp"
#include "bsp/bsp.hpp"
#include "revolution/revolution.hpp"
#include "reports/reports.hpp"
#include "render/render.hpp"
