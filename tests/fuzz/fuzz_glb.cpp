// libFuzzer entry for the binary glTF reader (lib/mesh/formats/glb_reader.cpp): any bytes give an
// IoError or a mesh with valid indices and finite coordinates; anything else aborts. Each input is
// decoded as it is and once more with the header's length set to the input's size, so that
// mutations reach the chunks and the JSON instead of stopping at the length check.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "base/errors.hpp"
#include "mesh/mesh_io.hpp"

namespace {

void decode(const std::string& data) {
  try {
    const sculpt::PolygonMesh mesh = sculpt::decode_mesh(data, sculpt::MeshFormat::Glb, "fuzz.glb");
    for (const auto& face : mesh.faces)
      for (const int v : face)
        if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size()) std::abort();
    for (const auto& p : mesh.vertices)
      if (!p.allFinite()) std::abort();
  } catch (const sculpt::IoError&) {}
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  decode(bytes);
  if (size >= 12) {
    const auto length = static_cast<std::uint32_t>(size);
    std::memcpy(bytes.data() + 8, &length, 4);
    decode(bytes);
  }
  return 0;
}
