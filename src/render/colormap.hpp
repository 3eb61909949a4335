// named colour maps as 256-entry 8-bit lookup tables, and the RGBA colour type of the renderer
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gs {

/// an 8-bit sRGB colour with straight (non-premultiplied) alpha
struct Rgba8 {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  constexpr bool operator==(const Rgba8&) const = default;
};

/// a colour map: 256 colours from the bottom (t = 0) to the top (t = 1) of the scale
struct Colormap {
  std::string name;
  std::array<Rgba8, 256> lut{};

  /// the colour at t in [0, 1] (clamped; NaN maps to the bottom), nearest of the 256 entries
  Rgba8 at(double t) const;
};

/// the map called `name`: viridis (default), magma, coolwarm, grayscale (or gray), turbo, jet.
/// An unknown name throws gs::InputError naming the key "colormap" and the known names.
const Colormap& colormap(const std::string& name);

/// the names colormap() accepts
std::vector<std::string> colormap_names();

}  // namespace gs
