// what a tap of the paper's pile costs on this machine: a few steps of the settled pile, timed
// in CPU seconds, scale the tapping study's projections (plan.cpp)
#pragma once
#include <functional>
#include <string>

#include "core/parallel.hpp"

namespace gs {

/// core-seconds per particle-step of the 1184-decagon pile when nothing has been measured
/// (a 2021 server core; it only scales printed projections)
inline constexpr double kPileCostReference = 1.1e-6;

/// a measured cost and how it was measured
struct PileCost {
  double seconds = kPileCostReference;  ///< core-seconds per particle-step
  bool measured = false;                ///< false: kPileCostReference
  int steps = 0;                        ///< steps timed
  int particles = 0;                    ///< grains of the pile
};

/// `steps` steps of `scene` (a scene of the paper pile) started from the settled pile in
/// `state` (a state file), on one thread, timed by `cpu_seconds` after one untimed warm-up
/// step; throws InputError when either file is unreadable
PileCost measure_pile_cost(const std::string& scene, const std::string& state, int steps,
                           const std::function<double()>& cpu_seconds = process_cpu_seconds);

}  // namespace gs
