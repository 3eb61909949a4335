// the stages of a time step and a clock that charges the wall time between two of its laps to
// a stage: a per-stage profile at a few clock reads per step (never one per pair or particle)
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace gs {

/// a step's stages, in the order a step runs them (docs/architecture.md, "One step")
enum class Stage : std::uint8_t {
  Drive,        ///< the time, the gravity of the moment, the random force's streams
  Predict,      ///< the integrator's prediction at t + Δt
  BroadPhase,   ///< candidate pairs
  NarrowPhase,  ///< each candidate's contact geometry and contact law; the new contact set
  Laws,         ///< each particle's contact forces summed, body forces, accelerations
  Correct,      ///< the integrator's correction (run back to back: and the next prediction)
  Health,       ///< drift removal, spatial sort, health checks, periodic re-wrapping
};
inline constexpr std::size_t kStageCount = 7;

/// the stage's name in run.json and in `gransim run --profile`
constexpr std::string_view stage_name(Stage s) {
  constexpr std::array<std::string_view, kStageCount> names{
      "drive", "predict", "broad_phase", "narrow_phase", "laws", "correct", "health"};
  return names[static_cast<std::size_t>(s)];
}

/// wall time spent in each stage, summed over the steps since the profile was cleared
struct StepProfile {
  std::array<double, kStageCount> seconds{};  ///< per stage, s
  std::uint64_t steps = 0;
  double& operator[](Stage s) { return seconds[static_cast<std::size_t>(s)]; }
  double operator[](Stage s) const { return seconds[static_cast<std::size_t>(s)]; }
  double total() const {
    double t = 0.0;
    for (double s : seconds) t += s;
    return t;
  }
};

/// laps of one step: lap(s) charges the time since the last lap (or since construction) to s,
/// so the stages' times add up to the step's wall time
class StageClock {
 public:
  explicit StageClock(StepProfile& p) : profile_(&p), last_(Clock::now()) {}
  void lap(Stage s) {
    const Clock::time_point t = Clock::now();
    (*profile_)[s] += std::chrono::duration<double>(t - last_).count();
    last_ = t;
  }

 private:
  using Clock = std::chrono::steady_clock;
  StepProfile* profile_;
  Clock::time_point last_;
};

}  // namespace gs
