// what a step costs on this machine: a few steps of the paper's settled pile, timed in CPU
// seconds, scale the tapping study's projections; a few of the ring's, the RFM study's (plan.cpp)
#pragma once
#include <functional>
#include <string>

#include "core/parallel.hpp"

namespace gs {

/// core-seconds per particle-step of the 1184-decagon pile when nothing has been measured
/// (a 2021 server core; it only scales printed projections)
inline constexpr double kPileCostReference = 1.1e-6;
/// core-seconds per particle-step of the 1000-disk ring of rfm1d_reference.toml from its start
/// (the simulation alone) on the core that measured the RFM study's costs (plan_rfm.cpp): the
/// ring measured here over this gives the factor on them
inline constexpr double kRingCostReference = 1.9e-8;

/// a measured cost and how it was measured
struct PileCost {
  double seconds = kPileCostReference;  ///< core-seconds per particle-step
  bool measured = false;                ///< false: kPileCostReference
  int steps = 0;                        ///< steps timed
  int particles = 0;                    ///< grains of the pile
};

/// `steps` steps of `scene` started from the state file `state` (the paper pile's settled
/// state), or as the scene prepares its grains when `state` is empty, on one thread, timed by
/// `cpu_seconds` after one untimed warm-up step; throws InputError when a file is unreadable
PileCost measure_pile_cost(const std::string& scene, const std::string& state, int steps,
                           const std::function<double()>& cpu_seconds = process_cpu_seconds);

}  // namespace gs
