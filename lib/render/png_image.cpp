#include "render/png_image.hpp"

#include <png.h>
#include "base/cancel.hpp"

#include <fstream>
#include <sstream>

#include "base/errors.hpp"
#include "mesh/mesh_io.hpp"

namespace sculpt::render {

// libpng's simplified API (png_image_*) reports errors through the png_image struct instead of
// longjmp, so no C++ object is skipped by a jump.

std::string encode_png(const Image& image, const PngOptions& options) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw InvalidInput("encode_png: the picture's size does not match its pixels");
  check_cancel();  // Ctrl-C (base/cancel.hpp): the encoding itself cannot be stopped
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  if (options.fast) png.flags = PNG_IMAGE_FLAG_FAST;
  png_alloc_size_t size = 0;
  const png_int_32 stride = 3 * image.width;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), stride, nullptr))
    throw IoError("<png>", std::string("cannot encode PNG: ") + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), stride, nullptr))
    throw IoError("<png>", std::string("cannot encode PNG: ") + png.message);
  bytes.resize(size);
  return bytes;
}

Image decode_png(std::string_view data, const std::string& name) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, data.data(), data.size()))
    throw IoError(name, std::string("not a readable PNG: ") + png.message);
  png.format = PNG_FORMAT_RGB;
  if (png.width > static_cast<png_uint_32>(kMaxImageSide) || png.height > static_cast<png_uint_32>(kMaxImageSide)) {
    png_image_free(&png);
    throw IoError(name, "PNG larger than " + std::to_string(kMaxImageSide) + " pixels per side");
  }
  Image image{.width = static_cast<int>(png.width), .height = static_cast<int>(png.height), .rgb = {}};
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr))
    throw IoError(name, std::string("cannot decode PNG: ") + png.message);
  return image;
}

void write_png(const Image& image, const std::filesystem::path& path, const PngOptions& options) {
  write_file_atomically(path, encode_png(image, options));
}

Image read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return decode_png(buffer.str(), path.string());
}

}  // namespace sculpt::render
