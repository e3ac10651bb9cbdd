#include "splines/bspline.hpp"

#include <gtest/gtest.h>
