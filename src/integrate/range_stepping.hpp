// an integrator's step by ranges of particles: for an executor that corrects (and predicts)
// each thread's particles inside its force pass, right where their accelerations are computed
// (sim/step_executor.hpp); bitwise what Integrator::correct() and predict() make
#pragma once
#include <cstddef>
#include <optional>
#include <span>

#include "integrate/integrator.hpp"

namespace gs {

class RangeStepping {
 public:
  virtual ~RangeStepping() = default;
  /// once before the ranges, outside the parallel region: throws what correct() would
  virtual void check_correct(std::span<const Channel> ch, double dt) const = 0;
  /// correct() over particles [b, e) (clipped to each channel's length); ranges that together
  /// cover every particle once give correct()'s result, and disjoint ones may run at once
  virtual void correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) = 0;
  /// can predict_range() follow correct_range()? (Gear 6)
  virtual bool predicts_by_range() const { return false; }
  /// where predicts_by_range(), right after correct_range() of [b, e) and with nothing edited
  /// in between: the next step's prediction of those particles, bitwise what the next
  /// predict() would make there (the executor then skips that predict())
  virtual void predict_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
    (void)ch;
    (void)b;
    (void)e;
  }
  /// where the correction is one kick per DOF (velocity Verlet, VerletCorrection::Kick): its
  /// form, which a caller may apply itself inside its acceleration pass while a_n is still in
  /// the channels, instead of correct_range() (integrate/vv_kernel.hpp: vv_kick_dof)
  virtual std::optional<KickForm> kick_form() const { return std::nullopt; }
};

}  // namespace gs
