#pragma once
/// \file png_image.hpp
/// PNG encoding and decoding of pictures through libpng (its simplified API), and the atomic
/// write of a picture file. The bytes depend only on the pixels (no time stamp, fixed settings).

#include <filesystem>
#include <string>
#include <string_view>

#include "render/picture.hpp"

namespace sculpt::render {

/// PNG bytes of an RGB picture. \throw IoError if libpng fails (out of memory).
std::string encode_png(const Image& image);

/// Decodes PNG bytes to 8-bit RGB (any PNG libpng reads; alpha composited on black).
/// `name` stands for the source in messages. \throw IoError if the data is not a readable PNG.
Image decode_png(std::string_view data, const std::string& name = "<png>");

/// Writes the picture as PNG to `path` atomically (mesh/mesh_io.hpp's write_file_atomically).
/// \throw IoError naming the path.
void write_png(const Image& image, const std::filesystem::path& path);

/// Reads a PNG file. \throw IoError naming the path.
Image read_png(const std::filesystem::path& path);

}  // namespace sculpt::render
