// the stages of a time step and a clock that charges the wall time between two of its laps to
// a stage: a per-stage profile at a few clock reads per step (never one per pair or particle)
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace gs {

/// a step's stages, in the order a step runs them (docs/architecture.md, "One step"): each a
/// slot of the profile, charged with the time of exactly what its name says
enum class Stage : std::uint8_t {
  Drive,        ///< the time, the gravity of the moment, the random force's streams
  Predict,      ///< the integrator's prediction at t + Δt
  BroadPhase,   ///< candidate pairs
  Pairs,        ///< each candidate's contact geometry and law, the new contact set, each
                ///< particle's contact forces summed
  Accelerate,   ///< body forces and each particle's acceleration
  Kick,         ///< accelerations, velocity Verlet's kick and (run back to back) the next
                ///< step's prediction in one pass over each block of disks
  Correct,      ///< the integrator's correction
  PredictNext,  ///< run back to back: the next step's prediction, made by the correction
  PlaceNext,    ///< run back to back: the next step's polygons placed
  Health,       ///< drift removal, spatial sort, health checks, periodic re-wrapping
};
inline constexpr std::size_t kStageCount = 10;

/// a monotonic clock in seconds: the profile's time source (a test gives its own, so that no
/// test depends on how busy the machine is)
using ClockSeconds = double (*)();
inline double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// the stage's name in run.json and in `gransim run --profile`
constexpr std::string_view stage_name(Stage s) {
  constexpr std::array<std::string_view, kStageCount> names{
      "drive", "predict", "broad_phase",  "pairs",      "accelerate",
      "kick",  "correct", "predict_next", "place_next", "health"};
  return names[static_cast<std::size_t>(s)];
}

/// wall time spent in each stage, summed over the steps since the profile was cleared.
/// Short steps are sampled: a step's ten or so clock reads cost about as much as a 1D ring's
/// step does in a few per cent, so where steps are shorter than kTimedStepMin one step in
/// `stride` is timed and counts for `stride` (an unbiased estimate of the sum). The timed steps
/// are picked by a hash of the step index, so that no period of the run (sorts, health
/// checks, taps) lines up with them.
struct StepProfile {
  std::array<double, kStageCount> seconds{};  ///< per stage, s
  std::uint64_t steps = 0;                    ///< steps taken
  std::uint64_t timed = 0;                    ///< of them timed
  std::uint32_t stride = 1;                   ///< one step in `stride` is timed (a power of 2)
  /// a step shorter than this is sampled (the clock reads stay under ~0.5 % of the time), s
  static constexpr double kTimedStepMin = 50e-6;
  static constexpr std::uint32_t kMaxStride = 64;
  double timed_step_min = kTimedStepMin;  ///< 0: every step timed
  ClockSeconds now = steady_seconds;      ///< the clock the stages are timed on
  /// the sums back to zero, the sampling and the clock kept
  void clear() {
    const double m = timed_step_min;
    const ClockSeconds c = now;
    *this = StepProfile{};
    timed_step_min = m;
    now = c;
  }
  double& operator[](Stage s) { return seconds[static_cast<std::size_t>(s)]; }
  double operator[](Stage s) const { return seconds[static_cast<std::size_t>(s)]; }
  double total() const {
    double t = 0.0;
    for (double s : seconds) t += s;
    return t;
  }
  /// is step `step` timed?
  bool times(std::int64_t step) const {
    return (mix(static_cast<std::uint64_t>(step)) & (stride - 1)) == 0;
  }
  /// after a timed step of `seconds`: the stride that brings stride × step to timed_step_min
  void adapt(double step_seconds) {
    std::uint32_t k = 1;
    while (k < kMaxStride && static_cast<double>(k) * step_seconds < timed_step_min) k *= 2;
    stride = k;
  }

 private:
  // splitmix64's finaliser: neighbouring step indices give unrelated bits
  static std::uint64_t mix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
};

/// laps of one step: lap(s) charges the time since the last lap (or since construction) to s,
/// so the stages' times add up to the step's wall time. A step the profile does not time
/// (StepProfile::times) reads no clock
class StageClock {
 public:
  StageClock(StepProfile& p, std::int64_t step)
      : profile_(p.times(step) ? &p : nullptr), weight_(p.stride) {
    if (profile_ != nullptr) first_ = last_ = p.now();
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;
  /// the step is over: count it, and after a timed one set the stride from its duration
  ~StageClock() {
    if (profile_ == nullptr) return;
    ++profile_->timed;
    profile_->adapt(last_ - first_);
  }
  void lap(Stage s) {
    if (profile_ == nullptr) return;
    const double t = profile_->now();
    (*profile_)[s] += weight_ * (t - last_);
    last_ = t;
  }

 private:
  StepProfile* profile_;
  double weight_;
  double first_ = 0.0, last_ = 0.0;  ///< clock reads, s
};

}  // namespace gs
