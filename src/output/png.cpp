// PNG through libpng's simplified API, with our own FILE handling for clear errors
#include "output/png.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/error.hpp"

namespace gs {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// the file, or InputError with the system's reason
File open_file(const std::string& path, const char* mode, const char* doing) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f) throw InputError(path, "", std::string("cannot ") + doing + ": " + std::strerror(errno));
  return File(f);
}

}  // namespace

void write_png(const std::string& path, const Image& img) {
  if (img.width < 1 || img.height < 1 ||
      img.rgba.size() != static_cast<std::size_t>(img.width) * img.height * 4)
    throw InputError(path, "", "cannot write an empty or inconsistent image as PNG");
  // drop the alpha channel when it says nothing (smaller files, same pixels when read back)
  bool opaque = true;
  for (std::size_t k = 3; k < img.rgba.size() && opaque; k += 4) opaque = img.rgba[k] == 255;
  std::vector<std::uint8_t> rgb;
  const void* pixels = img.rgba.data();
  if (opaque) {
    rgb.resize(static_cast<std::size_t>(img.width) * img.height * 3);
    for (std::size_t p = 0, n = rgb.size() / 3; p < n; ++p)
      std::memcpy(&rgb[3 * p], &img.rgba[4 * p], 3);
    pixels = rgb.data();
  }
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  im.width = static_cast<png_uint_32>(img.width);
  im.height = static_cast<png_uint_32>(img.height);
  im.format = opaque ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA;
  // an output that cannot be written (no such folder, read-only, disk full) is exit 5
  std::FILE* raw = std::fopen(path.c_str(), "wb");
  if (!raw) throw OutputError(path + ": cannot write PNG: " + std::strerror(errno));
  File f(raw);
  if (!png_image_write_to_stdio(&im, f.get(), 0, pixels, 0, nullptr))
    throw OutputError(path + ": libpng cannot write: " + im.message);
  if (std::fflush(f.get()) != 0)
    throw OutputError(path + ": cannot write PNG: " + std::strerror(errno));
}

Image read_png(const std::string& path) {
  File f = open_file(path, "rb", "read PNG");
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_stdio(&im, f.get()))
    throw InputError(path, "", std::string("not a readable PNG: ") + im.message);
  // everything as 8-bit RGBA, top row first
  im.format = PNG_FORMAT_RGBA;
  Image img(static_cast<int>(im.width), static_cast<int>(im.height));
  if (!png_image_finish_read(&im, nullptr, img.rgba.data(), 0, nullptr)) {
    png_image_free(&im);
    throw InputError(path, "", std::string("corrupt PNG: ") + im.message);
  }
  return img;
}

}  // namespace gs
