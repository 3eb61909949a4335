// the four integrators behind make_integrator(), exposed for tests and for callers that need
// a scheme-specific knob (Gear derivatives, the velocity Verlet force velocity).
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include "integrate/integrator.hpp"
#include "integrate/range_stepping.hpp"

namespace gs {

/// the layout of the channels an integrator was initialised with, and the checkpoint header
class ChannelLayout {
 public:
  /// remember the channel lengths
  void set(std::span<const Channel> ch);
  /// throw std::invalid_argument if ch does not have the remembered layout
  void check(std::span<const Channel> ch, const char* who) const;
  std::size_t channels() const { return sizes_.size(); }
  std::size_t size(std::size_t c) const { return sizes_[c]; }
  /// total degrees of freedom over all channels
  std::size_t total() const;
  /// move the DOFs of one channel's history (`stride` values per DOF, contiguous) as
  /// Integrator::permute says; throws std::invalid_argument when perm's length differs
  void permute(std::vector<double>& v, std::size_t c, std::span<const std::uint32_t> perm,
               std::size_t stride, std::vector<double>& tmp) const;
  /// write [tag, version, dt, nch, sizes...] to out
  void write_header(std::vector<double>& out, IntegratorKind k, double dt) const;
  /// read the header back; returns the offset of the payload. Throws gs::InputError.
  std::size_t read_header(const std::vector<double>& in, IntegratorKind k, double& dt);

 private:
  std::vector<std::size_t> sizes_;
};

/// sixth-order Gear predictor–corrector for q'' = a(q, q') (docs/physics.md §2.3, P: "sixth-order
/// Gear"). Per degree of freedom it keeps the scaled derivatives r_k = Δt^k/k!·d^k q/dt^k, k = 0…5.
/// predict(): Pascal-triangle Taylor step; writes q = r0ᵖ, v = r1ᵖ/Δt.
/// correct(): Δr2 = a·Δt²/2 − r2ᵖ, r_k += c_k·Δr2 with (c0…c5) = (3/16, 251/360, 1, 11/18,
/// 1/6, 1/60) (3/16: forces depend on velocity); writes q = r0, v = r1/Δt.
/// init() sets r3 = r4 = r5 = 0 (the usual start): the O(Δt³) error in r3 leaves an O(Δt²)
/// velocity error that persists, so the observed global order is 2 (integrator_order());
/// with exact higher derivatives (set_derivative) the scheme is fifth order.
/// A new Δt rescales r_k by (Δt_new/Δt_old)^k. zero_velocities() sets r1 = r3 = r4 = r5 = 0 and
/// keeps r0 and r2 (= a·Δt²/2 after correct()): the state init() gives a grain at rest.
class Gear6 final : public Integrator, public RangeStepping {
 public:
  IntegratorKind kind() const override { return IntegratorKind::Gear6; }
  void init(std::span<const Channel> ch, double dt) override;
  void predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void check_correct(std::span<const Channel> ch, double dt) const override;
  void correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) override;
  bool predicts_by_range() const override { return true; }
  void predict_range(std::span<const Channel> ch, std::size_t b, std::size_t e) override;
  void zero_velocities(std::span<const Channel> ch) override;
  void permute(std::span<const std::uint32_t> perm) override;
  std::vector<double> save() const override;
  void load(const std::vector<double>& data) override;
  RangeStepping& ranges() override { return *this; }
  /// after init(): set the k-th time derivative (k = 2…5) of channel c, in units/s^k,
  /// e.g. an exact start for convergence studies
  void set_derivative(std::size_t c, int k, std::span<const double> d);

 private:
  // the corrector on DOFs [b, e) of channel c
  void correct_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e);
  // the predictor on DOFs [b, e) of channel c; `pick_up`: caller edits of q and v first
  void predict_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e, bool pick_up);
  void rescale(double dt);
  void note_velocities();  // vw_ := r1/Δt, after the history changed outside predict/correct
  ChannelLayout layout_;
  std::vector<double> perm_tmp_;  ///< permute()'s buffer, kept between sorts
  double dt_ = 0.0;               ///< the Δt the derivatives are scaled with, s
  /// per channel, the 6 scaled derivatives r_k = Δt^k/k!·q⁽ᵏ⁾, DOF-major (r_k of DOF i at
  /// 6·i + k): a thread's DOFs are one block, so two threads meet at one place per channel
  /// (docs/threads.md), units
  std::vector<std::vector<double>> r_;
  /// per channel, the velocities last written (r1/Δt): a caller's edit of v shows as a
  /// difference without dividing again
  std::vector<std::vector<double>> vw_;
};

/// what velocity velocity Verlet shows the force evaluation
enum class VerletForceVelocity {
  /// v_n + a_n·Δt: a first-order prediction of v_{n+1}; with a velocity-dependent force the
  /// scheme stays second order (default)
  Extrapolated,
  /// the half-step velocity v_{n+1/2} (LAMMPS-style); dashpots then lag by Δt/2 and the
  /// scheme drops to first order for velocity-dependent forces (kept for comparison)
  HalfStep,
};

/// velocity Verlet, kick–drift–kick: predict v_{n+½} = v_n + a_n·Δt/2, q_{n+1} = q_n +
/// v_{n+½}·Δt; correct v_{n+1} = v_{n+½} + a_{n+1}·Δt/2. Symplectic for conservative forces.
/// The velocity written for the force evaluation is chosen by VerletForceVelocity. a_n is
/// read from the channels: between steps they must hold the last correct()'s accelerations.
/// VerletCorrection::Kick corrects as v_{n+1} = v̂ + (a_{n+1} − a_n)·Δt/2 (Extrapolated: v̂ =
/// v_n + a_n·Δt), or v̂ + a_{n+1}·Δt/2 (HalfStep: v̂ = v_{n+½}), with a_n kept by predict()
class VelocityVerlet final : public Integrator, public RangeStepping {
 public:
  explicit VelocityVerlet(VerletForceVelocity fv = VerletForceVelocity::Extrapolated,
                          VerletCorrection corr = VerletCorrection::HalfStepVelocity)
      : fv_(fv), corr_(corr) {}
  IntegratorKind kind() const override { return IntegratorKind::VelocityVerlet; }
  void init(std::span<const Channel> ch, double dt) override;
  void predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void check_correct(std::span<const Channel> ch, double dt) const override;
  void correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) override;
  /// the kick, with VerletCorrection::Kick
  std::optional<KickForm> kick_form() const override;
  /// the correction's form from the next step on (between steps)
  void set_correction(VerletCorrection corr);
  VerletCorrection correction() const { return corr_; }
  void zero_velocities(std::span<const Channel> ch) override;
  void permute(std::span<const std::uint32_t> perm) override;
  std::vector<double> save() const override;
  void load(const std::vector<double>& data) override;
  RangeStepping& ranges() override { return *this; }

 private:
  void size_history();
  KickForm form() const;
  void correct_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e);
  VerletForceVelocity fv_;
  VerletCorrection corr_;
  ChannelLayout layout_;
  std::vector<double> perm_tmp_;  ///< permute()'s buffer, kept between sorts
  double dt_ = 0.0;               ///< Δt of the last step, s
  /// per channel during a step: v_{n+½} (HalfStepVelocity) or a_n (Kick), which correct()
  /// needs once the channels hold a_{n+1}
  std::vector<std::vector<double>> kept_;
};

/// position (Störmer) Verlet (T.2.3): q_{n+1} = 2q_n − q_{n−1} + a_n·Δt². The history is the
/// previous position q_{n−1}, the current q_n and a_n. The step reads, with the force
/// evaluated at the new position:
///   predict: q_{n+1} = 2q_n − q_{n−1} + a_n·Δt²                       (T.2.3)
///            v̂_{n+1} = (q_{n+1} − q_n)/Δt + a_n·Δt/2   (predicted, for dashpots; its error
///                                                      is O(Δt²))
///   force:   a_{n+1} = a(q_{n+1}, v̂_{n+1})
///   correct: v_{n+1} = (q_{n+1} − q_n)/Δt + a_{n+1}·Δt/2
/// The final v_{n+1} is exactly the central difference (q_{n+2} − q_n)/(2Δt), because
/// q_{n+2} = 2q_{n+1} − q_n + a_{n+1}·Δt² is already fixed once a_{n+1} is known: positions
/// and velocities at the end of a step refer to the same time. Start: q_{−1} = q_0 − v_0·Δt +
/// a_0·Δt²/2 (consistent with that velocity definition). In exact arithmetic the positions
/// equal those of velocity Verlet with an extrapolated force velocity; round-off differs.
class PositionVerlet final : public Integrator, public RangeStepping {
 public:
  IntegratorKind kind() const override { return IntegratorKind::PositionVerlet; }
  void init(std::span<const Channel> ch, double dt) override;
  void predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void check_correct(std::span<const Channel> ch, double dt) const override;
  void correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) override;
  void zero_velocities(std::span<const Channel> ch) override;
  void permute(std::span<const std::uint32_t> perm) override;
  std::vector<double> save() const override;
  void load(const std::vector<double>& data) override;
  RangeStepping& ranges() override { return *this; }

 private:
  ChannelLayout layout_;
  std::vector<double> perm_tmp_;         ///< permute()'s buffer, kept between sorts
  double dt_ = 0.0;                      ///< Δt of the last step, s
  std::vector<std::vector<double>> qp_;  ///< per channel, q_{n−1}
  std::vector<std::vector<double>> qn_;  ///< per channel, q_n as last written
  std::vector<std::vector<double>> vn_;  ///< per channel, v_n as last written
  std::vector<std::vector<double>> a_;   ///< per channel, a_n
};

/// semi-implicit (symplectic) Euler: forces at the current state (predict does nothing),
/// correct: v_{n+1} = v_n + a_n·Δt, q_{n+1} = q_n + v_{n+1}·Δt. First order.
class SemiImplicitEuler final : public Integrator, public RangeStepping {
 public:
  IntegratorKind kind() const override { return IntegratorKind::SemiImplicitEuler; }
  void init(std::span<const Channel> ch, double dt) override;
  void predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) override;
  void check_correct(std::span<const Channel> ch, double dt) const override;
  void correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) override;
  void zero_velocities(std::span<const Channel> ch) override;
  void permute(std::span<const std::uint32_t> perm) override;
  std::vector<double> save() const override;
  void load(const std::vector<double>& data) override;
  RangeStepping& ranges() override { return *this; }

 private:
  ChannelLayout layout_;
  double dt_ = 0.0;  ///< Δt of the last step, s
};

}  // namespace gs
