// the [render] section of a scene: its enum spellings, the names its string keys accept, and
// (for parse.cpp / write.cpp) reading and writing it. RenderSpec itself lives in spec.hpp.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/names.hpp"
#include "scene/spec.hpp"

namespace gs {

std::span<const EnumName<RenderSchedule>> enum_names(RenderSchedule);

/// render.color_by: speed, speed_rms, species, vy, contacts, pressure, uniform
std::span<const std::string_view> render_color_by_names();
/// render.colormap: the maps of render/colormap.hpp (tests/app checks the two lists agree)
std::span<const std::string_view> render_colormap_names();
/// render.renderer: auto, gl, software
std::span<const std::string_view> render_renderer_names();
/// render.preset: the x264 speed presets, ultrafast … placebo
std::span<const std::string_view> render_preset_names();

namespace scene_detail {

struct Ctx;
class TableReader;

/// read [render] (after [drive] and [output]: some defaults follow the drive kind)
void read_render(const Ctx& ctx, const TableReader& top, SceneSpec& s);
/// the [render] keys and their TOML values, in the order scene_to_toml writes them
std::vector<std::pair<std::string, std::string>> render_entries(const RenderSpec& r);

}  // namespace scene_detail
}  // namespace gs
