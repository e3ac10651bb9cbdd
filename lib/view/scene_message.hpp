#pragma once
/// \file scene_message.hpp
/// The messages the view's page receives over its WebSocket (docs/viewing.md, "Protocol").
///
/// A scene is one binary message: the 4 bytes "SCLV", a little-endian uint32 n, n bytes of JSON
/// (padded with spaces to a multiple of 4), then the data. The JSON lists the parts:
///   {"parts": [{"name", "color": [r, g, b], "solid", "volume" (solids; else null), "area",
///               "box": [[x, y, z], [x, y, z]] (null if empty), "triangles",
///               "glb": [offset, length], "edges": [offset, count], "loose": [offset, count]}, ...]}
/// Offsets count from the start of the data and are multiples of 4. "glb" is the part as binary
/// glTF (mesh/mesh_io.hpp's GLB writer: float32 positions, uint32 indices). The feature edges, the
/// edges between faces of the exact boundary that are not coplanar (never a triangulation's
/// diagonal), are "edges": `count` pairs of uint32 indices into the GLB's positions (8 bytes an
/// edge), and "loose": `count` edges as 6 float32 (x, y, z of both ends) for the few whose ends
/// the GLB's output rounding moved.
///
/// A status is one text message: {"type": "status", "ok": true|false, "run": n, "ms": t,
/// "parts": p, "error": "file:line:col: error: ...\n<the line>\n<caret>"}; an error leaves the
/// scene on the page as it was.

#include <string>

#include "view/scene.hpp"

namespace sculpt::view {

/// The binary scene message of `scene`.
/// \throw InvalidInput if a part's mesh has a bad face index or a coordinate beyond float32.
std::string encode_scene(const Scene& scene);

struct Status {
  bool ok = true;
  std::string error{};      ///< the formatted error when !ok
  long long run = 0;        ///< the number of the run (1 for the first)
  double milliseconds = 0;  ///< how long the run took
  std::size_t parts = 0;    ///< parts in the scene sent with it
};

/// The text status message of `status`.
std::string encode_status(const Status& status);

/// `text` as a JSON string literal (quotes included; control characters escaped, invalid UTF-8
/// bytes replaced so the page can parse it).
std::string json_string(const std::string& text);

}  // namespace sculpt::view
