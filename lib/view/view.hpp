#pragma once
/// \file view.hpp
/// The live view (docs/viewing.md): a browser page fed over a WebSocket with the parts a script
/// or session shows. Umbrella header of lib/view.

#include "view/scene.hpp"
#include "view/scene_message.hpp"
#include "view/view_errors.hpp"
#include "view/view_server.hpp"
