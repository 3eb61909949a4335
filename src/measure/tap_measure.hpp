// the per-tap measurements of the tapping study (docs/physics.md §2.5): one record of a pile at
// rest, taken just before the next excitation; pure functions of the World and its contacts
#pragma once
#include <array>
#include <string>
#include <vector>

#include "contact/contact_set.hpp"
#include "world/world.hpp"

namespace gs {

/// one pile at rest, measured
struct TapMeasurement {
  double phi = 0.0;               ///< volume fraction of the test rectangle, dimensionless
  double phi_left = 0.0;          ///< φ of its left half
  double phi_right = 0.0;         ///< φ of its right half
  double kinetic_energy = 0.0;    ///< translation + rotation, J (proof of rest)
  double max_speed = 0.0;         ///< largest grain speed, m/s (proof of rest)
  double z_mean = 0.0;            ///< mean height of the grain centres, m
  std::vector<double> z_species;  ///< mean height of each species' centres, m
  double coordination = 0.0;      ///< grain–grain contacts per grain
  std::array<double, 4> S{};      ///< force-moment tensor S_xx, S_xy, S_yx, S_yy (P.41), N·m
};

/// measure the pile in the test rectangle rect = {x0, y0, x1, y1} (m); halves split at the
/// rectangle's vertical centre line
TapMeasurement measure_tap(const World& w, const ContactSet& cs, const double rect[4]);

/// the fixed height grid of the segregation curves: h_k = k·dh for k = 1 … ⌈top/dh⌉, m
std::vector<double> height_grid(double top, double dh);

/// segregation (docs/physics.md §2.5): n_s(h) = number of grains of species s with centre height y
/// < h, for every h of the grid; species-major (all h of species 0, then species 1, …)
std::vector<double> cumulative_counts(const World& w, const std::vector<double>& grid);

/// the column names of cumulative_counts: "<species>@<h>" with h in mm ("big@10", …)
std::vector<std::string> cumulative_count_names(const World& w, const std::vector<double>& grid);

}  // namespace gs
