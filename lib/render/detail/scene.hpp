#pragma once
/// \file scene.hpp
/// The geometric part of a picture (picture.hpp): the z-buffer of the meshes' front faces seen
/// by a camera, with what each face id stands for. Shading and lines come after.

#include <vector>

#include "mesh/polygon_mesh.hpp"
#include "render/camera.hpp"
#include "render/detail/edges.hpp"
#include "render/detail/rasterizer.hpp"

namespace sculpt::render::detail {

struct Scene {
  DepthBuffer buffer;
  std::vector<FaceInfo> faces;  ///< indexed by the buffer's face ids
};

/// Rasterizes every front face of every mesh (faces valid, convex, counter-clockwise from
/// outside). Mesh k's faces get solid k, or solid `ids[k]` if `ids` is given. Meshes with
/// `two_sided[k]` (if given) also have their back faces drawn, with the normal turned over.
/// `smooth_crease` >= 0: the faces also get their corners' normals for smooth shading, averaged
/// over faces that meet at no more than that many degrees (smooth_normals.hpp).
Scene draw_scene(const std::vector<PolygonMesh>& meshes, const Camera& camera, const std::vector<bool>& two_sided = {},
                 const std::vector<int>& ids = {}, double smooth_crease = -1);

}  // namespace sculpt::render::detail
