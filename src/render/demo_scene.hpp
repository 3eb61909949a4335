// synthetic scenes for benchmarks, tests and the README picture (no physics: positions are
// placed and relaxed geometrically, velocities are made up)
#pragma once
#include <cstdint>

#include "render/frame.hpp"

namespace gs {

struct DemoScene {
  RenderParticles particles;
  RenderWalls walls;
  BoxExtent box;
  RenderOverlays overlays;
};

/// the tapping paper's pile (docs/physics.md §2.2): n_big decagons of r = 9 mm and n_small of r =
/// 6.36 mm filling a box `width` m wide to ≈ 0.53 m (for 544 + 640 in 0.48 m), walls on three
/// sides, the top layers moving upward as after a tap, the 0.40 m test square drawn
DemoScene demo_decagon_pile(int n_big = 544, int n_small = 640, double width = 0.48,
                            std::uint64_t seed = 1);

/// n disks of area fraction phi at random positions in a periodic square box of side L (m),
/// Maxwell–Boltzmann velocities of unit variance per component
DemoScene demo_disk_gas(int n, double L = 1.0, double phi = 0.3, std::uint64_t seed = 1);

}  // namespace gs
