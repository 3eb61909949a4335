// velocity Verlet and position (Störmer) Verlet (T.2.3)
#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "integrate/channel_loop.hpp"
#include "integrate/schemes.hpp"
#include "integrate/vv_kernel.hpp"

namespace gs {

namespace {
// append per-channel arrays to a checkpoint, and read them back
void put(std::vector<double>& out, const std::vector<std::vector<double>>& arr) {
  for (const auto& a : arr) out.insert(out.end(), a.begin(), a.end());
}
void take(const std::vector<double>& in, std::size_t& off, const ChannelLayout& lay,
          std::vector<std::vector<double>>& arr) {
  arr.assign(lay.channels(), {});
  for (std::size_t c = 0; c < lay.channels(); ++c) {
    const std::size_t n = lay.size(c);
    arr[c].assign(in.begin() + static_cast<std::ptrdiff_t>(off),
                  in.begin() + static_cast<std::ptrdiff_t>(off + n));
    off += n;
  }
}
// the velocity Verlet loops over particles [b, e) of one channel, on distinct arrays
// (restrict: they vectorise without run-time overlap checks); kKeep: what correct() needs
// later, v_{n+½} (HalfStepVelocity) or a_n (Kick)
enum class Keep { HalfStepVelocity, OldAcceleration };
template <Keep kKeep, bool kHalf>
void vv_predict(std::size_t b, std::size_t e, double dt, const double* __restrict a,
                double* __restrict kept, double* __restrict q, double* __restrict v) {
  for (std::size_t i = b; i < e; ++i) {
    double qi = q[i], vi = v[i];
    const double h = vv_predict_dof<kHalf>(dt, a[i], qi, vi);
    kept[i] = kKeep == Keep::HalfStepVelocity ? h : a[i];
    q[i] = qi;
    v[i] = vi;
  }
}
template <Keep kKeep>
void vv_predict(std::size_t b, std::size_t e, double dt, bool half, const double* __restrict a,
                double* __restrict kept, double* __restrict q, double* __restrict v) {
  if (half)
    vv_predict<kKeep, true>(b, e, dt, a, kept, q, v);
  else
    vv_predict<kKeep, false>(b, e, dt, a, kept, q, v);
}
void vv_correct(std::size_t b, std::size_t e, double dt, const double* __restrict vh,
                double* __restrict v, const double* __restrict an) {
  for (std::size_t i = b; i < e; ++i) v[i] = vh[i] + an[i] * dt / 2.0;
}
// the kick v_{n+1} = v̂ + c_new·a_{n+1} − c_old·a_n
void vv_kick(std::size_t b, std::size_t e, double c_new, double c_old,
             const double* __restrict a_old, double* __restrict v, const double* __restrict an) {
  for (std::size_t i = b; i < e; ++i) v[i] = vv_kick_dof(v[i], an[i], a_old[i], c_new, c_old);
}
void check_dt(double dt, const char* who) {
  if (!(dt > 0.0)) throw std::invalid_argument(std::string(who) + ": dt must be positive");
}
}  // namespace

// ---- velocity Verlet ----

// start: a_0 is the channels' acceleration, as a_n is at every later step
void VelocityVerlet::init(std::span<const Channel> ch, double dt) {
  check_dt(dt, "VelocityVerlet::init");
  layout_.set(ch);
  dt_ = dt;
  size_history();
}

// v_{n+½} or a_n per channel
void VelocityVerlet::size_history() {
  kept_.assign(layout_.channels(), {});
  for (std::size_t c = 0; c < kept_.size(); ++c) kept_[c].assign(layout_.size(c), 0.0);
}

KickForm VelocityVerlet::form() const {
  const bool half = fv_ == VerletForceVelocity::HalfStep;
  return {0.5, half ? 0.0 : 0.5, half};
}

std::optional<KickForm> VelocityVerlet::kick_form() const {
  if (corr_ != VerletCorrection::Kick) return std::nullopt;
  return form();
}

void VelocityVerlet::set_correction(VerletCorrection corr) { corr_ = corr; }

void VelocityVerlet::predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) {
  layout_.check(ch, "VelocityVerlet::predict");
  check_dt(dt, "VelocityVerlet::predict");
  dt_ = dt;
  const bool half = fv_ == VerletForceVelocity::HalfStep;
  const bool kick = corr_ == VerletCorrection::Kick;
  for_channels(team, ch, kParallelMinCheap, [&](std::size_t c, std::size_t b, std::size_t e) {
    const double* a = ch[c].a.data();
    if (kick)
      vv_predict<Keep::OldAcceleration>(b, e, dt, half, a, kept_[c].data(), ch[c].q.data(),
                                        ch[c].v.data());
    else
      vv_predict<Keep::HalfStepVelocity>(b, e, dt, half, a, kept_[c].data(), ch[c].q.data(),
                                         ch[c].v.data());
  });
}

void VelocityVerlet::check_correct(std::span<const Channel> ch, double dt) const {
  layout_.check(ch, "VelocityVerlet::correct");
  if (dt != dt_) throw std::invalid_argument("VelocityVerlet::correct: dt differs from predict()");
}

void VelocityVerlet::correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) {
  check_correct(ch, dt);
  // a_{n+1} stays in the channels for the next step's kick
  for_channels(team, ch, kParallelMinCheap,
               [&](std::size_t c, std::size_t b, std::size_t e) { correct_dofs(ch[c], c, b, e); });
}

void VelocityVerlet::correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const std::size_t n = ch[c].q.size();
    correct_dofs(ch[c], c, std::min(b, n), std::min(e, n));
  }
}

void VelocityVerlet::correct_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e) {
  if (corr_ == VerletCorrection::Kick) {
    const KickForm f = form();
    vv_kick(b, e, f.new_frac * dt_, f.old_frac * dt_, kept_[c].data(), k.v.data(), k.a.data());
  } else {
    vv_correct(b, e, dt_, kept_[c].data(), k.v.data(), k.a.data());
  }
}

// kinetic damping: v_n = 0; the next kick starts from a_n as at the start
void VelocityVerlet::zero_velocities(std::span<const Channel> ch) {
  layout_.check(ch, "VelocityVerlet::zero_velocities");
  for (const Channel& k : ch) std::fill(k.v.begin(), k.v.end(), 0.0);
}

// v_{n+½} and a_n live within a step: nothing to move, but the permutation must fit
void VelocityVerlet::permute(std::span<const std::uint32_t> perm) {
  for (std::size_t c = 0; c < layout_.channels(); ++c)
    if (perm.size() != layout_.size(c))
      throw std::invalid_argument("Integrator::permute: the permutation does not fit the history");
}

// history: the header only. a_n is the channels' acceleration (the state's, which a checkpoint
// stores); v_{n+½} lives within a step. Older checkpoints have a copy of a_n after the header:
// such a history still loads (the copy equals the state's acceleration and is not needed).
std::vector<double> VelocityVerlet::save() const {
  std::vector<double> out;
  layout_.write_header(out, kind(), dt_);
  return out;
}

void VelocityVerlet::load(const std::vector<double>& data) {
  std::size_t off = layout_.read_header(data, kind(), dt_);
  if (data.size() != off && data.size() != off + layout_.total())
    throw InputError("checkpoint", "integrator.velocity_verlet",
                     "integrator history has wrong length");
  size_history();
}

// ---- position Verlet ----

// start: q_{−1} = q_0 − v_0·Δt + a_0·Δt²/2, so that v_0 = (q_0 − q_{−1})/Δt + a_0·Δt/2
void PositionVerlet::init(std::span<const Channel> ch, double dt) {
  check_dt(dt, "PositionVerlet::init");
  layout_.set(ch);
  dt_ = dt;
  qp_.assign(ch.size(), {});
  qn_.assign(ch.size(), {});
  vn_.assign(ch.size(), {});
  a_.assign(ch.size(), {});
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    qn_[c].assign(k.q.begin(), k.q.end());
    vn_[c].assign(k.v.begin(), k.v.end());
    a_[c].assign(k.a.begin(), k.a.end());
    qp_[c].resize(k.q.size());
    for (std::size_t i = 0; i < k.q.size(); ++i)
      qp_[c][i] = k.q[i] - k.v[i] * dt + k.a[i] * dt * dt / 2.0;
  }
}

void PositionVerlet::predict(std::span<const Channel> ch, double dt, const ThreadTeam&) {
  layout_.check(ch, "PositionVerlet::predict");
  check_dt(dt, "PositionVerlet::predict");
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    auto& qp = qp_[c];
    auto& qn = qn_[c];
    auto& vn = vn_[c];
    const auto& a = a_[c];
    for (std::size_t i = 0; i < k.q.size(); ++i) {
      // caller edits: a shift of q moves the history with it; a change of v moves q_{n−1}
      if (k.q[i] != qn[i]) {
        qp[i] += k.q[i] - qn[i];
        qn[i] = k.q[i];
      }
      if (k.v[i] != vn[i]) {
        qp[i] -= (k.v[i] - vn[i]) * dt_;
        vn[i] = k.v[i];
      }
      // a new Δt: rebuild q_{n−1} from v_n as at the start
      if (dt != dt_) qp[i] = qn[i] - vn[i] * dt + a[i] * dt * dt / 2.0;
      // the Verlet step (T.2.3) and the predicted velocity for the force evaluation
      const double q1 = 2.0 * qn[i] - qp[i] + a[i] * dt * dt;
      k.v[i] = (q1 - qn[i]) / dt + a[i] * dt / 2.0;
      k.q[i] = q1;
      qp[i] = qn[i];
      qn[i] = q1;
    }
  }
  dt_ = dt;
}

void PositionVerlet::check_correct(std::span<const Channel> ch, double dt) const {
  layout_.check(ch, "PositionVerlet::correct");
  if (dt != dt_) throw std::invalid_argument("PositionVerlet::correct: dt differs from predict()");
}

void PositionVerlet::correct(std::span<const Channel> ch, double dt, const ThreadTeam&) {
  check_correct(ch, dt);
  correct_range(ch, 0, static_cast<std::size_t>(-1));
}

void PositionVerlet::correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
  const double dt = dt_;
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    const auto& qp = qp_[c];
    const auto& qn = qn_[c];
    auto& vn = vn_[c];
    auto& a = a_[c];
    // v_{n+1} = (q_{n+2} − q_n)/(2Δt) with q_{n+2} from (T.2.3), written out
    for (std::size_t i = b; i < std::min(e, k.q.size()); ++i) {
      a[i] = k.a[i];
      vn[i] = (qn[i] - qp[i]) / dt + a[i] * dt / 2.0;
      k.v[i] = vn[i];
    }
  }
}

// kinetic damping: v_n = 0 and q_{n−1} rebuilt from it as at the start (a shifted q kept)
void PositionVerlet::zero_velocities(std::span<const Channel> ch) {
  layout_.check(ch, "PositionVerlet::zero_velocities");
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    for (std::size_t i = 0; i < k.q.size(); ++i) {
      qn_[c][i] = k.q[i];
      vn_[c][i] = k.v[i] = 0.0;
      qp_[c][i] = k.q[i] + a_[c][i] * dt_ * dt_ / 2.0;
    }
  }
}

void PositionVerlet::permute(std::span<const std::uint32_t> perm) {
  for (std::size_t c = 0; c < layout_.channels(); ++c)
    for (auto* v : {&qp_[c], &qn_[c], &vn_[c], &a_[c]}) layout_.permute(*v, c, perm, 1, perm_tmp_);
}

// history: header, then q_{n−1}, q_n, v_n, a_n per channel
std::vector<double> PositionVerlet::save() const {
  std::vector<double> out;
  layout_.write_header(out, kind(), dt_);
  put(out, qp_);
  put(out, qn_);
  put(out, vn_);
  put(out, a_);
  return out;
}

void PositionVerlet::load(const std::vector<double>& data) {
  std::size_t off = layout_.read_header(data, kind(), dt_);
  if (data.size() != off + 4 * layout_.total())
    throw InputError("checkpoint", "integrator.position_verlet",
                     "integrator history has wrong length");
  take(data, off, layout_, qp_);
  take(data, off, layout_, qn_);
  take(data, off, layout_, vn_);
  take(data, off, layout_, a_);
}

}  // namespace gs
