// PNG files through libpng: RGBA8 images in and out
#pragma once
#include <string>

#include "core/image.hpp"

namespace gs {

/// write the image as an 8-bit PNG (RGB when every pixel is opaque, else RGBA);
/// throws InputError naming the path when it cannot be written
void write_png(const std::string& path, const Image& image);

/// read any PNG as RGBA8 (grey, palette, 16-bit and RGB are converted; opaque alpha = 255);
/// throws InputError naming the path when it is missing or not a readable PNG
Image read_png(const std::string& path);

}  // namespace gs
