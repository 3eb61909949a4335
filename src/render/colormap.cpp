// colour maps: decode the published 8-bit tables once, look colours up by name
#include "render/colormap.hpp"

#include <cmath>
#include <map>

#include "core/error.hpp"

namespace gs {

namespace detail {
extern const char* const k_viridis_hex;
extern const char* const k_magma_hex;
extern const char* const k_coolwarm_hex;
extern const char* const k_turbo_hex;
extern const char* const k_jet_hex;
}  // namespace detail

namespace {

// one hex digit to its value
int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return c - 'A' + 10;
}

// a table of 256 "rrggbb" entries to a colour map
Colormap from_hex(const char* name, const char* hex) {
  Colormap m;
  m.name = name;
  for (int i = 0; i < 256; ++i) {
    const char* p = hex + 6 * i;
    auto byte = [&](int k) {
      return static_cast<std::uint8_t>(16 * hex_digit(p[2 * k]) + hex_digit(p[2 * k + 1]));
    };
    m.lut[i] = {byte(0), byte(1), byte(2), 255};
  }
  return m;
}

// the linear grey ramp, black at the bottom
Colormap grayscale() {
  Colormap m;
  m.name = "grayscale";
  for (int i = 0; i < 256; ++i) {
    const auto v = static_cast<std::uint8_t>(i);
    m.lut[i] = {v, v, v, 255};
  }
  return m;
}

// all maps, built on first use
const std::map<std::string, Colormap>& registry() {
  static const std::map<std::string, Colormap> maps = [] {
    std::map<std::string, Colormap> r;
    r["viridis"] = from_hex("viridis", detail::k_viridis_hex);
    r["magma"] = from_hex("magma", detail::k_magma_hex);
    r["coolwarm"] = from_hex("coolwarm", detail::k_coolwarm_hex);
    r["turbo"] = from_hex("turbo", detail::k_turbo_hex);
    r["jet"] = from_hex("jet", detail::k_jet_hex);
    r["grayscale"] = grayscale();
    r["gray"] = r["grayscale"];
    return r;
  }();
  return maps;
}

}  // namespace

Rgba8 Colormap::at(double t) const {
  // clamp, then the nearest of the 256 entries (entry i sits at t = i/255)
  if (!(t > 0.0)) return lut[0];
  if (t >= 1.0) return lut[255];
  return lut[static_cast<int>(std::lround(t * 255.0))];
}

const Colormap& colormap(const std::string& name) {
  const auto& maps = registry();
  if (auto it = maps.find(name.empty() ? "viridis" : name); it != maps.end()) return it->second;
  std::string known;
  for (const auto& n : colormap_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("", "colormap", "unknown colour map '" + name + "' (known: " + known + ")");
}

std::vector<std::string> colormap_names() {
  std::vector<std::string> names;
  for (const auto& [n, m] : registry()) names.push_back(n);
  return names;
}

}  // namespace gs
