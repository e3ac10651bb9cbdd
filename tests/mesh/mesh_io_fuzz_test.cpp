// Bad input never crashes: truncated and corrupted files give an IoError or a mesh whose
// indices are valid, never anything else (run under ASan/UBSan too).
#include <gtest/gtest.h>

#include <random>

#include "base/errors.hpp"
#include "mesh/mesh_io.hpp"
#include "shapes.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

struct Variant {
  MeshFormat format;
  bool binary;
  const char* name;
};

void expect_graceful(const std::string& data, MeshFormat format, const std::string& what) {
  try {
    const PolygonMesh m = decode_mesh(data, format, "fuzz");
    EXPECT_TRUE(checks::IndicesValid(m)) << what;
    for (const auto& p : m.vertices) EXPECT_TRUE(p.allFinite()) << what;
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), "fuzz") << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": unexpected " << e.what();
  }
}

TEST(MeshIoFuzz, TruncatedAndCorruptedFiles) {
  const PolygonMesh mesh = test_shapes::merged(test_shapes::octahedron(), test_shapes::unit_cube());
  const Variant variants[] = {{MeshFormat::Off, false, "off"}, {MeshFormat::Obj, false, "obj"},
                              {MeshFormat::Ply, false, "ply"}, {MeshFormat::Ply, true, "ply binary"},
                              {MeshFormat::Stl, false, "stl"}, {MeshFormat::Stl, true, "stl binary"},
                              {MeshFormat::Glb, false, "glb"}};
  std::mt19937 rng(3);
  for (const Variant& v : variants) {
    const std::string good = encode_mesh(mesh, v.format, v.binary);
    for (size_t cut = 0; cut < good.size(); cut += 1 + good.size() / 200)
      expect_graceful(good.substr(0, cut), v.format, std::string(v.name) + " cut at " + std::to_string(cut));
    std::uniform_int_distribution<size_t> pos(0, good.size() - 1);
    const std::string noise = "-+.eE0123456789 \n\t/#xyzOFFvfsolidfacet\xff\x80";
    std::uniform_int_distribution<size_t> pick(0, noise.size() - 1);
    for (int trial = 0; trial < 300; ++trial) {
      std::string bad = good;
      for (int k = 0; k < 1 + trial % 4; ++k) bad[pos(rng)] = trial % 2 ? noise[pick(rng)] : static_cast<char>(rng());
      expect_graceful(bad, v.format, std::string(v.name) + " corrupted, trial " + std::to_string(trial));
    }
  }
}

}  // namespace
}  // namespace sculpt
