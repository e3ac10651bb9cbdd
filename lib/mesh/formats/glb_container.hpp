#pragma once
/// \file glb_container.hpp
/// The binary glTF container (glTF 2.0 spec, sec. 4.4 "Binary glTF Layout"; internal): a 12-byte
/// header (magic, version, total length), then chunks of (length, type, data), the JSON chunk
/// first and at most one BIN chunk after it; every chunk starts and ends on a 4-byte boundary.
/// All numbers little endian, as the accessors' data.

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace sculpt::mesh::detail::glb {

static_assert(std::endian::native == std::endian::little, "the GLB codec assumes little endian");

constexpr std::uint32_t kMagic = 0x46546C67;  ///< "glTF"
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  ///< "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   ///< "BIN\0"
constexpr std::size_t kHeaderSize = 12;
constexpr std::size_t kChunkHeaderSize = 8;

/// Accessor component types (sec. 3.6.2.2) and buffer view targets (sec. 3.6.1).
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;  ///< mesh primitive mode (sec. 3.7.2.1)

/// The little-endian uint32 at `p` (no alignment needed).
inline std::uint32_t load_u32(const char* p) {
  std::uint32_t x;
  std::memcpy(&x, p, 4);
  return x;
}

/// Appends `x` as four little-endian bytes.
inline void append_u32(std::string& out, std::uint32_t x) {
  char b[4];
  std::memcpy(b, &x, 4);
  out.append(b, 4);
}

}  // namespace sculpt::mesh::detail::glb
