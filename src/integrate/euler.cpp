// semi-implicit (symplectic) Euler: kick with the force at the current state, then drift
#include <algorithm>
#include <stdexcept>

#include "core/error.hpp"
#include "integrate/schemes.hpp"

namespace gs {

// no history beyond the layout
void SemiImplicitEuler::init(std::span<const Channel> ch, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("SemiImplicitEuler::init: dt must be positive");
  layout_.set(ch);
  dt_ = dt;
}

// forces are evaluated at the current q, v: nothing moves
void SemiImplicitEuler::predict(std::span<const Channel> ch, double dt, const ThreadTeam&) {
  layout_.check(ch, "SemiImplicitEuler::predict");
  if (!(dt > 0.0)) throw std::invalid_argument("SemiImplicitEuler::predict: dt must be positive");
  dt_ = dt;
}

// v_{n+1} = v_n + a_n·Δt, then q_{n+1} = q_n + v_{n+1}·Δt
void SemiImplicitEuler::check_correct(std::span<const Channel> ch, double dt) const {
  layout_.check(ch, "SemiImplicitEuler::correct");
  if (dt != dt_)
    throw std::invalid_argument("SemiImplicitEuler::correct: dt differs from predict()");
}

void SemiImplicitEuler::correct(std::span<const Channel> ch, double dt, const ThreadTeam&) {
  check_correct(ch, dt);
  correct_range(ch, 0, static_cast<std::size_t>(-1));
}

void SemiImplicitEuler::correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
  const double dt = dt_;
  for (const auto& k : ch) {
    for (std::size_t i = b; i < std::min(e, k.q.size()); ++i) {
      k.v[i] += k.a[i] * dt;
      k.q[i] += k.v[i] * dt;
    }
  }
}

// kinetic damping: no history, only v
void SemiImplicitEuler::zero_velocities(std::span<const Channel> ch) {
  layout_.check(ch, "SemiImplicitEuler::zero_velocities");
  for (const Channel& k : ch) std::fill(k.v.begin(), k.v.end(), 0.0);
}

// no history beyond the layout: the state is all there is
void SemiImplicitEuler::permute(std::span<const std::uint32_t> perm) {
  for (std::size_t c = 0; c < layout_.channels(); ++c)
    if (perm.size() != layout_.size(c))
      throw std::invalid_argument("Integrator::permute: the permutation does not fit the history");
}

// history: the header only (layout and Δt)
std::vector<double> SemiImplicitEuler::save() const {
  std::vector<double> out;
  layout_.write_header(out, kind(), dt_);
  return out;
}

void SemiImplicitEuler::load(const std::vector<double>& data) {
  const std::size_t off = layout_.read_header(data, kind(), dt_);
  if (data.size() != off)
    throw InputError("checkpoint", "integrator.semi_implicit_euler",
                     "integrator history has wrong length");
}

}  // namespace gs
