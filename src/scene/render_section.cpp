// [render]: the recorder's outputs, schedule, camera, colouring, overlays, encoder settings and
// the trajectory export; checked once here like every other section (docs/scene-format.md)
#include "scene/render_section.hpp"

#include <array>
#include <climits>
#include <cmath>

#include "scene/reader.hpp"

namespace gs {

namespace {

constexpr EnumName<RenderSchedule> kSchedule[] = {{"time", RenderSchedule::Time},
                                                  {"steps", RenderSchedule::Steps},
                                                  {"taps", RenderSchedule::Taps},
                                                  {"rest", RenderSchedule::Rest}};
constexpr std::string_view kColorBy[] = {"speed",    "speed_rms", "species", "vy",
                                         "contacts", "pressure",  "uniform"};
constexpr std::string_view kColormaps[] = {"viridis", "magma", "coolwarm", "grayscale",
                                           "gray",    "turbo", "jet"};
constexpr std::string_view kRenderers[] = {"auto", "gl", "software"};
constexpr std::string_view kPresets[] = {"ultrafast", "superfast", "veryfast", "faster",  "fast",
                                         "medium",    "slow",      "slower",   "veryslow"};

}  // namespace

std::span<const EnumName<RenderSchedule>> enum_names(RenderSchedule) { return kSchedule; }
std::span<const std::string_view> render_color_by_names() { return kColorBy; }
std::span<const std::string_view> render_colormap_names() { return kColormaps; }
std::span<const std::string_view> render_renderer_names() { return kRenderers; }
std::span<const std::string_view> render_preset_names() { return kPresets; }

namespace scene_detail {

namespace {

// a string key that must be one of a list
std::string one_of(const TableReader& r, std::string_view k, std::string def,
                   std::span<const std::string_view> names) {
  std::string v = r.string(k, def, true);
  std::string list;
  for (auto n : names) {
    if (n == v) return v;
    list += (list.empty() ? "" : ", ") + quote(n);
  }
  r.fail(k, "must be one of " + list + " (got " + quote(v) + ")" +
                suggestion(v, {names.begin(), names.end()}));
}

// an array of n finite numbers; `form` says what is expected
template <std::size_t N>
std::array<double, N> numbers(const TableReader& r, std::string_view k, const toml::node& n,
                              const std::string& form) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != N)
    r.fail(k, form + ", got " +
                  (a ? "an array of " + std::to_string(a->size()) : std::string(type_name(n))));
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    const toml::node& e = (*a)[i];
    std::optional<double> v;
    if (auto f = e.as_floating_point()) v = f->get();
    if (auto q = e.as_integer()) v = static_cast<double>(q->get());
    if (!v) r.fail(k, form + "; element " + std::to_string(i) + " is " + std::string(type_name(e)));
    if (!std::isfinite(*v))
      r.fail(k, "element " + std::to_string(i) + " must be a finite number (got " + node_text(e) +
                    ")");
    out[i] = *v;
  }
  return out;
}

// a key that is either a keyword string or an array of N numbers; nullopt for the keyword
template <std::size_t N>
std::optional<std::array<double, N>> keyword_or_numbers(const TableReader& r, std::string_view k,
                                                        std::string_view keyword,
                                                        const std::string& form) {
  const toml::node* n = r.get(k);
  if (!n) return std::nullopt;
  if (auto s = n->as_string()) {
    if (s->get() == keyword) return std::nullopt;
    r.fail(k, "expected " + quote(keyword) + " or " + form + " (got " + quote(s->get()) + ")");
  }
  return numbers<N>(r, k, *n, "expected " + quote(keyword) + " or " + form);
}

std::string number_list(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += format_double(v[i]) + (i + 1 < n ? ", " : "]");
  return s;
}

}  // namespace

void read_render(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  const toml::table* t = sub_table(top, "render");
  static const toml::table empty;
  TableReader r(ctx, t ? *t : empty, "render",
                {"enabled",
                 "frames",
                 "movie",
                 "schedule",
                 "every",
                 "fps",
                 "slowmo",
                 "start",
                 "size",
                 "msaa",
                 "camera",
                 "margin",
                 "color_by",
                 "colormap",
                 "range",
                 "colorbar",
                 "force_chains",
                 "gravity_arrow",
                 "test_rect",
                 "clock",
                 "title",
                 "crf",
                 "preset",
                 "renderer",
                 "trajectory_every",
                 "trajectory_formats"});
  RenderSpec& o = s.render;
  // outputs: nothing is recorded unless asked (a --set render.* must not start a movie)
  o.enabled = r.boolean("enabled", false);
  o.frames = r.boolean("frames", o.frames);
  o.movie = r.boolean("movie", o.movie);
  if (o.enabled && !o.frames && !o.movie)
    r.fail(r.has("movie") ? "movie" : "frames",
           "with enabled = true at least one of frames, movie must be true");

  // schedule: per simulated time, per steps, or at the tapping protocol's phases
  o.schedule = r.choice("schedule", RenderSchedule::Time);
  const bool tapping = s.drive.kind == DriveKind::NegativeG || s.drive.kind == DriveKind::RotatingG;
  if ((o.schedule == RenderSchedule::Taps || o.schedule == RenderSchedule::Rest) && !tapping)
    r.fail("schedule", "\"" + std::string(scene_name(o.schedule)) +
                           "\" needs a tapping drive (drive.kind = \"negative_g\" or "
                           "\"rotating_g\"; got " +
                           quote(scene_name(s.drive.kind)) + ")");
  o.every = static_cast<int>(r.integer("every", o.every, 1, INT_MAX));
  o.fps = static_cast<int>(r.integer("fps", o.fps, 1, 240));
  o.slowmo = r.number("slowmo", o.slowmo, Range::positive());
  o.start = r.number("start", o.start, Range::non_negative());

  // frame size and camera
  if (const toml::node* n = r.get("size")) {
    const auto wh = numbers<2>(r, "size", *n, "expected [width, height] in px");
    for (int i = 0; i < 2; ++i)
      if (wh[i] != std::floor(wh[i]) || wh[i] < 16 || wh[i] > 8192)
        r.fail("size", std::string(i == 0 ? "width" : "height") +
                           " must be an integer in 16…8192 px (got " + format_double(wh[i]) + ")");
    o.width = static_cast<int>(wh[0]);
    o.height = static_cast<int>(wh[1]);
  }
  o.msaa = static_cast<int>(r.integer("msaa", o.msaa, 1, 16));
  o.region = keyword_or_numbers<4>(r, "camera", "fit", "an array [x0, y0, x1, y1] in m");
  if (o.region && ((*o.region)[2] <= (*o.region)[0] || (*o.region)[3] <= (*o.region)[1]))
    r.fail("camera", "the region [x0, y0, x1, y1] needs x1 > x0 and y1 > y0 (got " +
                         number_list(o.region->data(), 4) + ")");
  o.margin = r.number("margin", o.margin, {0.0, 1.0, false, false});

  // colours
  o.color_by = one_of(r, "color_by", o.color_by, kColorBy);
  o.colormap = one_of(r, "colormap", o.colormap, kColormaps);
  o.range = keyword_or_numbers<2>(r, "range", "auto", "an array [lo, hi]");
  if (o.range && !((*o.range)[1] > (*o.range)[0]))
    r.fail("range", "needs lo < hi (got " + number_list(o.range->data(), 2) + ")");
  o.colorbar = r.boolean("colorbar", o.colorbar);

  // overlays: the gravity arrow and the test rectangle belong to the tapping protocols
  o.force_chains = r.boolean("force_chains", o.force_chains);
  o.gravity_arrow = r.boolean("gravity_arrow", tapping);
  o.test_rect = r.boolean("test_rect", tapping);
  o.clock = r.boolean("clock", o.clock);
  o.title = r.string("title", "", false);

  // encoder and backend
  o.crf = static_cast<int>(r.integer("crf", o.crf, 0, 51));
  o.preset = one_of(r, "preset", o.preset, kPresets);
  o.renderer = one_of(r, "renderer", o.renderer, kRenderers);

  // trajectory export (independent of enabled)
  o.trajectory_every = static_cast<int>(r.integer("trajectory_every", 0, 0, INT_MAX));
  // its formats: a non-empty list of distinct names out of "xyz", "h5md"
  if (const toml::node* n = r.get("trajectory_formats")) {
    const std::string form = "an array of trajectory formats (\"xyz\", \"h5md\")";
    const toml::array* a = n->as_array();
    if (!a)
      r.fail("trajectory_formats", "expected " + form + ", got " + std::string(type_name(*n)));
    o.trajectory_xyz = o.trajectory_h5md = false;
    for (std::size_t i = 0; i < a->size(); ++i) {
      const auto* e = (*a)[i].as_string();
      if (!e)
        r.fail("trajectory_formats",
               form + "; element " + std::to_string(i) + " is " + std::string(type_name((*a)[i])));
      const std::string v = e->get();
      if (v != "xyz" && v != "h5md")
        r.fail("trajectory_formats", "element " + std::to_string(i) +
                                         " must be \"xyz\" or \"h5md\" (got " + quote(v) + ")" +
                                         suggestion(v, {"xyz", "h5md"}));
      bool& flag = v == "xyz" ? o.trajectory_xyz : o.trajectory_h5md;
      if (flag) r.fail("trajectory_formats", "names " + quote(v) + " twice");
      flag = true;
    }
    if (!o.trajectory_xyz && !o.trajectory_h5md)
      r.fail("trajectory_formats", "is empty; name \"xyz\", \"h5md\" or both");
  }
}

std::vector<std::pair<std::string, std::string>> render_entries(const RenderSpec& o) {
  auto flag = [](bool b) { return std::string(b ? "true" : "false"); };
  const std::string wh = "[" + std::to_string(o.width) + ", " + std::to_string(o.height) + "]";
  std::string trajectory_formats = "[";
  if (o.trajectory_xyz) trajectory_formats += "\"xyz\"";
  if (o.trajectory_h5md)
    trajectory_formats += std::string(o.trajectory_xyz ? ", " : "") + "\"h5md\"";
  trajectory_formats += "]";
  return {
      {"enabled", flag(o.enabled)},
      {"frames", flag(o.frames)},
      {"movie", flag(o.movie)},
      {"schedule", quote(scene_name(o.schedule))},
      {"every", std::to_string(o.every)},
      {"fps", std::to_string(o.fps)},
      {"slowmo", format_double(o.slowmo)},
      {"start", format_double(o.start)},
      {"size", wh},
      {"msaa", std::to_string(o.msaa)},
      {"camera", o.region ? number_list(o.region->data(), 4) : quote("fit")},
      {"margin", format_double(o.margin)},
      {"color_by", quote(o.color_by)},
      {"colormap", quote(o.colormap)},
      {"range", o.range ? number_list(o.range->data(), 2) : quote("auto")},
      {"colorbar", flag(o.colorbar)},
      {"force_chains", flag(o.force_chains)},
      {"gravity_arrow", flag(o.gravity_arrow)},
      {"test_rect", flag(o.test_rect)},
      {"clock", flag(o.clock)},
      {"title", quote(o.title)},
      {"crf", std::to_string(o.crf)},
      {"preset", quote(o.preset)},
      {"renderer", quote(o.renderer)},
      {"trajectory_every", std::to_string(o.trajectory_every)},
      {"trajectory_formats", trajectory_formats},
  };
}

}  // namespace scene_detail
}  // namespace gs
