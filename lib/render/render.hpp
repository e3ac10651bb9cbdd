#pragma once
/// \file render.hpp
/// Umbrella header of the render layer: pictures of solids (PNG) and SVG figures of curves.

#include "render/camera.hpp"
#include "render/picture.hpp"
#include "render/plot.hpp"
#include "render/png_image.hpp"
