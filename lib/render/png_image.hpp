#pragma once
/// \file png_image.hpp
/// PNG encoding and decoding of pictures through libpng (its simplified API), and the atomic
/// write of a picture file. The bytes depend only on the pixels (no time stamp, fixed settings).

#include <filesystem>
#include <string>
#include <string_view>

#include "render/picture.hpp"

namespace sculpt::render {

struct PngOptions {
  /// libpng's PNG_IMAGE_FLAG_FAST: one filter and fast compression. About 4 to 5 times faster
  /// on shaded pictures, files about 1.5 times larger (docs/benchmarks.md, "Pictures"); the
  /// session's :show uses it, render() does not.
  bool fast = false;
};

/// PNG bytes of an RGB picture (the same bytes for the same pixels and options).
/// \throw InvalidInput if the size does not match the pixels; IoError if libpng fails.
std::string encode_png(const Image& image, const PngOptions& options = {});

/// Decodes PNG bytes to 8-bit RGB (any PNG libpng reads; alpha composited on black).
/// `name` stands for the source in messages. \throw IoError if the data is not a readable PNG.
Image decode_png(std::string_view data, const std::string& name = "<png>");

/// Writes the picture as PNG to `path` atomically (mesh/mesh_io.hpp's write_file_atomically).
/// \throw IoError naming the path.
void write_png(const Image& image, const std::filesystem::path& path, const PngOptions& options = {});

/// Reads a PNG file. \throw IoError naming the path.
Image read_png(const std::filesystem::path& path);

}  // namespace sculpt::render
