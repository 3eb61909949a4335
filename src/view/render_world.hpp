// World → frame data: the adapter between the engine and the GL-free frame builder
// (render/frame.hpp). It is a module of its own because render/ must not depend on world/.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "contact/contact_set.hpp"
#include "render/frame.hpp"
#include "scene/spec.hpp"
#include "world/world.hpp"

namespace gs {

/// what the view takes of a scene beyond its [render] section, taken once: the drive (the
/// tap phase, the protocol's line) and the φ window
struct ViewSettings {
  DriveSpec drive;
  std::array<double, 4> test_rect{};  ///< [output] test_rect: x0, y0, x1, y1, m
  static ViewSettings from(const SceneSpec& scene);
};

/// what a frame shows beyond the particles: the clock, the protocol, gravity, the φ window
struct FrameInfo {
  double time = 0.0;         ///< simulated time, s
  Vec2 gravity{0.0, -9.81};  ///< gravity at that time, m/s²
  std::optional<long> tap;   ///< tap number (1 = the first excitation period), if tapping
  bool settling = false;     ///< before the tapping protocol starts
  bool exciting = false;     ///< inside an excitation window
  std::string protocol;      ///< the tapping protocol's phase in words ("" if not tapping)
  std::optional<std::array<double, 4>> test_rect;  ///< the φ window, m, if known
};

/// particles with their true shapes (regular n-gons or disks), orientations, velocities and
/// species; value_extra is left empty
RenderParticles world_particles(const World& w);
/// the wall polygons (quadrilaterals) of a walled box
RenderWalls world_walls(const World& w);
/// the box extent; periodic boxes are periodic in x and y, a ring in x (its strip in y is
/// fitted to the particles)
BoxExtent world_box(const World& w);

/// contacts per particle (particle–particle and particle–wall) in the last step
std::vector<double> contact_counts(const World& w, const ContactSet& c);
/// per-particle pressure p = −tr(σ)/2, σ_i = (1/A_i) Σ_c (s_c − x_i) ⊗ f_c: positive in
/// compression, N/m (2D stress)
std::vector<double> contact_pressure(const World& w, const ContactSet& c);
/// force-chain segments: centre to centre (walls: centre to contact point), |f_n| in N
std::vector<ContactLine> force_chain_lines(const World& w, const ContactSet& c);

/// the frame builder's settings from a [render] section (size, camera, colours, colour bar)
FrameSpec frame_spec(const RenderSpec& r);
/// does this [render] need the contacts (force chains, colour by contacts or pressure)?
bool needs_contacts(const RenderSpec& r);

/// everything build_frame takes
struct WorldFrame {
  RenderParticles particles;
  RenderWalls walls;
  RenderOverlays overlays;
  BoxExtent box;
  FrameSpec spec;
};

/// the frame of a world: particles, walls, colour values, overlays (clock and tap, gravity
/// arrow, test rectangle, force chains, title) as the [render] section asks. `contacts` may be
/// null when needs_contacts(r) is false; otherwise std::invalid_argument.
WorldFrame world_frame(const World& w, const ContactSet* contacts, const FrameInfo& info,
                       const RenderSpec& r);

/// the FrameInfo of a live world: t, the given gravity, the tap phase and the protocol's
/// line from the drive, the φ window
FrameInfo frame_info(const World& w, const ViewSettings& view, Vec2 gravity);

}  // namespace gs
