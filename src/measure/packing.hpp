// read-only packing observers: φ in a rectangle (exact clipping), coordination, stress
// (docs/physics.md §2.5)
#pragma once
#include <array>

#include "contact/contact_set.hpp"
#include "world/world.hpp"

namespace gs {

/// grain area inside [x0,x1]×[y0,y1] over the rectangle's area, by exact polygon ∩ rectangle
/// (or disk ∩ rectangle) clipping
double phi_in_rect(const World& w, double x0, double y0, double x1, double y1);

/// mean number of grain–grain contacts per grain (walls not counted)
double mean_coordination(const World& w, const ContactSet& cs);

/// extensive stress (force-moment) tensor S_ab = Σ_contacts Σ_p (s − x_p)_a F_p,b (P.41), N·m,
/// over grain–grain and grain–wall contacts (the grain's side only for walls)
std::array<double, 4> force_moment_tensor(const World& w, const ContactSet& cs);

/// largest speed, m/s
double max_speed(const World& w);

}  // namespace gs
