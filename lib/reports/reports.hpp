#pragma once
/// \file reports.hpp
/// Umbrella header of lib/reports: depth-cost statistics of BSP trees and their reports (Ihm & Naylor 1990, sec. 6).
/// Every public header of the layer (the headers directly in lib/reports/).

#include "reports/depth_cost.hpp"
#include "reports/query_cost.hpp"
#include "reports/range_query_tree.hpp"
#include "reports/tree_report.hpp"
