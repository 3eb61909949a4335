// the GL-free description of one frame: what the World adapter fills in (RenderParticles,
// RenderWalls, RenderOverlays), how to draw it (FrameSpec), and what any backend draws (FrameData).
//
// FrameData lives in "canvas" coordinates: pixels, origin at the bottom-left corner of the image,
// y up (so a world angle stays an angle on the canvas). Image pixel (col, row) with row 0 at the
// top covers canvas [col, col+1] × [H-1-row, H-row].
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/vec.hpp"
#include "render/colormap.hpp"

namespace gs {

// ---------------------------------------------------------------------------------------------
// input: the simulation state as plain arrays (SI units)

/// particles as structure of arrays; all arrays have the same length except value_extra
struct RenderParticles {
  std::vector<double> x, y;         ///< centre, m
  std::vector<double> theta;        ///< orientation (vertex 0 at angle θ), rad
  std::vector<double> radius;       ///< circumradius (n-gon) or radius (disk), m
  std::vector<int> sides;           ///< 0 = disk, n >= 3 = regular n-gon
  std::vector<double> vx, vy;       ///< velocity, m/s
  std::vector<int> species;         ///< species index (0, 1, …)
  std::vector<double> value_extra;  ///< optional scalar per particle (contacts, …); may be empty

  std::size_t size() const { return x.size(); }
};

/// fixed walls as quads (any convex quadrilateral, corners in order), m
struct RenderWalls {
  std::vector<std::array<Vec2, 4>> rects;
};

/// one contact of a force chain: the segment between the two centres and its normal force
struct ContactLine {
  Vec2 a, b;           ///< end points, m
  double force = 0.0;  ///< magnitude of the normal force, N
};

/// optional overlays
struct RenderOverlays {
  double time = 0.0;                               ///< simulated time, s
  bool show_time = true;                           ///< print "t = … s"
  int tap = 0;                                     ///< tap (excitation) counter
  bool has_tap = false;                            ///< print "tap N"
  Vec2 gravity{0.0, -9.81};                        ///< gravity vector, m/s²
  bool show_gravity = false;                       ///< draw the gravity arrow (rotating g)
  std::optional<std::array<double, 4>> test_rect;  ///< measurement rectangle x0, y0, x1, y1, m
  std::vector<ContactLine> force_chains;           ///< contacts to draw as force chains
  std::string title;                               ///< a line above everything else
  std::vector<std::string> lines;  ///< extra text lines under the time (e.g. "φ = 0.81")
};

/// the extent of the simulation box (inner region), m; periodic directions draw image copies
struct BoxExtent {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;  ///< m
  bool periodic_x = false;
  bool periodic_y = false;
};

// ---------------------------------------------------------------------------------------------
// how to draw

/// what the particle colour shows
enum class ColorBy {
  speed,      ///< |v|, m/s (default)
  speed_rms,  ///< |v| / v_rms, v_rms = sqrt(<|v|²>) over the frame
  species,    ///< species index, one colour each
  vy,         ///< vertical velocity, m/s (automatic range symmetric about 0)
  extra,      ///< RenderParticles::value_extra
  uniform     ///< one colour (FrameSpec::uniform_color), no colour bar
};
/// "speed", "speed_rms" (or "v/vrms"), "species", "vy", "extra", "uniform"; else InputError
ColorBy parse_color_by(const std::string& name);
std::string to_string(ColorBy c);

/// which part of the world fills the frame
struct CameraSpec {
  double margin = 0.04;  ///< empty border around the box, fraction of its larger side
  std::optional<std::array<double, 4>> region;  ///< show x0, y0, x1, y1 (m) instead of the box
};

struct FrameSpec {
  int width = 1280;  ///< image width, px
  int height = 720;  ///< image height, px
  int msaa = 4;      ///< samples per pixel (GL backend; 1 = off)
  ColorBy color_by = ColorBy::speed;
  std::string colormap = "viridis";
  std::optional<std::pair<double, double>> range;  ///< fixed colour range; automatic when empty
  bool colorbar = true;               ///< draw the colour bar (not for ColorBy::uniform)
  std::string extra_label = "value";  ///< colour-bar label for ColorBy::extra
  std::string extra_unit;             ///< its unit ("" = dimensionless)
  CameraSpec camera;
  double outline_px = -1.0;  ///< particle outline width, px (< 0: automatic from size)
  double font_px = 0.0;      ///< text height, px (0: automatic, height / 40)
  Rgba8 background{250, 250, 250, 255};
  Rgba8 outline_color{25, 25, 25, 255};
  Rgba8 wall_color{120, 120, 128, 255};
  Rgba8 uniform_color{70, 130, 180, 255};
  Rgba8 text_color{20, 20, 20, 255};
};

// ---------------------------------------------------------------------------------------------
// output: what a backend draws

/// world → canvas map: canvas = (ox + scale·x, oy + scale·y)
struct Camera {
  double scale = 1.0;  ///< px/m
  double ox = 0.0;     ///< canvas x of world x = 0, px
  double oy = 0.0;     ///< canvas y of world y = 0, px
  Vec2 to_canvas(Vec2 w) const { return {ox + scale * w.x, oy + scale * w.y}; }
  Vec2 to_world(Vec2 c) const { return {(c.x - ox) / scale, (c.y - oy) / scale}; }
};

/// one particle on the canvas (layout shared with the GL instance buffer)
struct ShapeInstance {
  float cx = 0, cy = 0;  ///< centre, px
  float radius = 0;      ///< circumradius, px
  float angle = 0;       ///< orientation, rad (counter-clockwise)
  Rgba8 fill;
  std::int32_t sides = 0;  ///< 0 = disk
};

/// a coloured triangle-list vertex, px
struct ColorVertex {
  float x = 0, y = 0;  ///< px
  Rgba8 color;
};

enum class HAlign : std::uint8_t { left, center, right };
enum class VAlign : std::uint8_t { baseline, middle, top };

/// a line of text (UTF-8) anchored at (x, y), px
struct TextItem {
  std::string text;
  float x = 0, y = 0;  ///< anchor, px
  float size = 14;     ///< nominal pixel height of the font
  HAlign halign = HAlign::left;
  VAlign valign = VAlign::baseline;
  Rgba8 color;
};

/// what the colour bar shows (also handy for tests)
struct ColorBarInfo {
  bool shown = false;
  std::array<float, 4> rect{};  ///< bar x0, y0, x1, y1, px (bottom = range low)
  double lo = 0.0, hi = 1.0;    ///< value range, in the quantity's unit
  std::vector<double> ticks;    ///< tick values
  std::string label;            ///< e.g. "speed (m/s)"
};

struct FrameData {
  int width = 0, height = 0;  ///< px
  int msaa = 4;               ///< samples per pixel wanted
  Rgba8 background;
  Camera camera;
  std::array<float, 4> view_clip{};      ///< the world view x0, y0, x1, y1, px: walls and
                                         ///< world overlays are clipped to it
  std::array<float, 4> particle_clip{};  ///< particles are clipped to x0, y0, x1, y1, px
  float outline_px = 1.0f;               ///< particle outline width, px (0 = none)
  Rgba8 outline_color;
  std::vector<ShapeInstance> polygons;  ///< regular n-gons
  std::vector<ShapeInstance> disks;
  std::vector<ColorVertex> walls;          ///< triangles, drawn first (hatched), view-clipped
  std::vector<ColorVertex> world_overlay;  ///< force chains, test rectangle: over the particles,
                                           ///< view-clipped
  std::vector<ColorVertex> overlay;        ///< colour bar, arrow, panels: on top, not clipped
  std::vector<TextItem> text;              ///< drawn last
  ColorBarInfo colorbar;
  std::string colormap;
  double value_lo = 0.0, value_hi = 1.0;  ///< colour range used
};

/// build the frame: camera fit, particle instances and colours, walls, overlays, colour bar
FrameData build_frame(const RenderParticles& particles, const RenderWalls& walls,
                      const RenderOverlays& overlays, const FrameSpec& spec, const BoxExtent& box);

/// "nice" tick values (1, 2, 2.5 or 5 × 10^k apart) inside [lo, hi], at most max_count of them
std::vector<double> nice_ticks(double lo, double hi, int max_count = 6);

/// tick labels with a common number of decimals fitting the step, e.g. {"0", "0.5", "1"}
std::vector<std::string> tick_labels(const std::vector<double>& ticks);

/// the colour value of each particle for the chosen quantity (m/s, 1, index, …)
std::vector<double> particle_values(const RenderParticles& p, ColorBy by);

}  // namespace gs
