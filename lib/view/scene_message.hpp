#pragma once
/// \file scene_message.hpp
/// The messages the view's page receives over its WebSocket (docs/viewing.md, "Protocol").
///
/// A scene is one binary message: the 4 bytes "SCLV", a little-endian uint32 n, n bytes of JSON
/// (padded with spaces to a multiple of 4), then the data. The JSON lists the parts:
///   {"parts": [{"name", "color": [r, g, b], "solid", "volume" (solids; else null), "area",
///               "box": [[x, y, z], [x, y, z]] (null if empty), "triangles",
///               "glb": [offset, length], "edges": [offset, count, creases], "features",
///               "depth": [offset, count] or null,
///               "curve": [offset, count] or null, "length"}, ...]}
/// Offsets count from the start of the data and are multiples of 4. "glb" is the part as binary
/// glTF (mesh/mesh_io.hpp's encode_glb_for_display: the part's vertices as float32 in order,
/// uint32 indices). A solid's part is its exact boundary (to_mesh without output rounding). The
/// feature edges, the edges between faces of that boundary that are not coplanar (never a
/// triangulation's diagonal), are "edges": `count` pairs of uint32 indices into the GLB's
/// positions (8 bytes an edge). The first `creases` edges are the creases
/// (detail/feature_edges.hpp): the page splits smooth vertex normals there and draws only them
/// when it shades smooth. "features" counts all feature edges: a part with more than
/// kDenseFeatureEdges that are not creases (a finely faceted curved surface, whose facets' edges
/// would cover it in black) is sent with its creases only (`count` = `creases`). "depth" (solids, and only when asked
/// for: SceneOptions::depth) is one uint16 per GLB triangle, in the GLB's order: the depth of the tree's leaf cell
/// behind the triangle (detail/cell_depths.hpp; 65535 at most), padded to 4 bytes. "curve" (curves, splines,
/// linearizations, motion paths, lists of points) is `count` points as 3 float32 each, a polyline drawn in the part's
/// colour (a closed curve's last point is its first); such a part has an empty GLB and its "length" is the polyline's.
///
/// A status is one text message: {"type": "status", "ok": true|false, "run": n, "ms": t,
/// "script_ms": s, "script_end": e, "scene_sent": t, "parts": p, "error": "file:line:col: error: ...\n<the
/// line>\n<caret>"}; an error leaves the scene on the page as it was.
///
/// The page sends one kind of text message: "depth:1" when it enters the depth mode, "depth:0"
/// when it leaves it (view_server.hpp: ViewServer::depth_wanted).

#include <string>

#include "view/scene.hpp"

namespace sculpt::view {

/// Feature edges that are not creases beyond which a part's are not sent (see above).
inline constexpr std::size_t kDenseFeatureEdges = 200000;

struct SceneOptions {
  /// Send each solid's cell depths (the depth mode). Builds the trees of solids whose tree is
  /// deferred (bsp/solid.hpp): ask only when a page shows them, on the thread that owns the values.
  bool depth = false;
};

/// The binary scene message of `scene`.
/// \throw InvalidInput if a part's mesh has a bad face index or a coordinate beyond float32.
std::string encode_scene(const Scene& scene, const SceneOptions& options = {});

struct Status {
  bool ok = true;
  std::string error{};      ///< the formatted error when !ok
  long long run = 0;        ///< the number of the run (1 for the first)
  double milliseconds = 0;  ///< how long the run took
  /// How much of it the script itself took (the rest made and sent the scene); 0 in the REPL.
  double script_milliseconds = 0;
  /// When the script ended, in milliseconds since the Unix epoch (the system clock), so that a
  /// page or a test on the same machine can tell how long after it the scene arrived; 0 unknown.
  double script_end = 0;
  /// When the scene message was made and handed to the server to send (the same clock); 0 unknown.
  double scene_sent = 0;
  std::size_t parts = 0;  ///< parts in the scene sent with it
};

/// The text status message of `status`.
std::string encode_status(const Status& status);

/// `text` as a JSON string literal (quotes included; control characters escaped, invalid UTF-8
/// bytes replaced so the page can parse it).
std::string json_string(const std::string& text);

}  // namespace sculpt::view
