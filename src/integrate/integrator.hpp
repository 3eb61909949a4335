// time integrators on flat channels of degrees of freedom. The integrator never sees
// contacts: the step is predict() → (caller computes accelerations at the predicted
// positions and velocities) → correct(). Each channel is one coordinate array (x, y or θ).
//
// contract shared by all four schemes (src/integrate/schemes.hpp has the details):
// - init() fixes the layout (number of channels and their lengths); call it again whenever
//   bodies are added or removed. predict()/correct() with another layout throw
//   std::invalid_argument.
// - between correct() and the next predict() the caller may edit q (periodic wrapping) and
//   v (velocity kicks, centre-of-mass drift removal); every scheme picks such edits up as if
//   the state had been produced by the step.
// - dt may change between steps; each scheme rescales its history to the new dt.
// - save()/load() are valid between steps; together with the caller's q and v they restore
//   the run bitwise. load() throws gs::InputError on data that is not this scheme's.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/integrator_kind.hpp"
#include "core/team.hpp"

namespace gs {

/// one coordinate array: positions q, velocities v (read-write), accelerations a (read-only,
/// filled by the caller at the predicted state before correct())
struct Channel {
  std::span<double> q;
  std::span<double> v;
  std::span<const double> a;
};

/// a correction that is one velocity kick per DOF: v_{n+1} = v̂ + c_new·a_{n+1} − c_old·a_n,
/// v̂ the velocity predict() wrote, c = fraction·Δt
struct KickForm {
  double new_frac = 0.0;
  double old_frac = 0.0;
  /// the scheme's prediction, for a caller that also predicts the next step inside its kick:
  /// vv_predict_dof<predict_half> (integrate/vv_kernel.hpp)
  bool predict_half = false;
};

/// how velocity Verlet corrects: from the half-step velocity v_{n+½} it keeps, or as one kick
/// from the last accelerations (KickForm; what an executor can apply inside its force pass).
/// Equal in exact arithmetic; the round-off differs, so a run keeps one form throughout
enum class VerletCorrection : std::uint8_t { HalfStepVelocity, Kick };

/// what an integrator is built with (make_integrator)
struct IntegratorSettings {
  IntegratorKind kind = IntegratorKind::Gear6;
  VerletCorrection verlet_correction = VerletCorrection::HalfStepVelocity;
};

class RangeStepping;

/// an integrator owns whatever history it needs (Gear derivatives, previous positions)
class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual IntegratorKind kind() const = 0;
  /// start from the current q, v and the accelerations a at that state
  virtual void init(std::span<const Channel> ch, double dt) = 0;
  /// advance q and v to the predicted state at t + dt, where forces are evaluated. `team`: how
  /// a parallel pass splits the particles among the threads (the simulation's, so that each
  /// thread predicts the particles it later sums and corrects; a default ThreadTeam splits
  /// equally); it never changes a result
  virtual void predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) = 0;
  /// given a at the predicted state, produce the final q, v at t + dt (`team`: as predict's)
  virtual void correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) = 0;
  /// between steps: set every velocity of ch to zero and restart the history from rest at
  /// the current positions, as init() would with v = 0 and the last accelerations (kinetic
  /// damping, drive.quench). Positions and the stored accelerations are kept
  virtual void zero_velocities(std::span<const Channel> ch) = 0;
  /// the particles moved between slots (a spatial sort): in every channel, DOF k now holds
  /// what DOF perm[k] held, so the history follows (channels as long as perm)
  virtual void permute(std::span<const std::uint32_t> perm) = 0;
  /// the integrator's internal history as flat doubles (for checkpoints), and back
  virtual std::vector<double> save() const = 0;
  virtual void load(const std::vector<double>& data) = 0;
  /// the same step by ranges of particles, for an executor that corrects each particle where
  /// it has just computed its acceleration (integrate/range_stepping.hpp); every scheme has it
  virtual RangeStepping& ranges() = 0;
};

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings);
inline std::unique_ptr<Integrator> make_integrator(IntegratorKind k) {
  return make_integrator(IntegratorSettings{k});
}

}  // namespace gs
