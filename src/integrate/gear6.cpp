// sixth-order Gear predictor–corrector for second-order equations (docs/physics.md §2.3)
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "integrate/channel_loop.hpp"
#include "integrate/schemes.hpp"

namespace gs {

namespace {
// corrector coefficients for q'' = a(q, q') with velocity-dependent forces (docs/physics.md §2.3)
constexpr double kC[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
constexpr int kN = 6;  // values per degree of freedom

// per-DOF loops run in parallel from this many DOFs on: six derivatives per DOF make them
// dearer than the plain particle loops (kParallelMinCheap)
constexpr std::size_t kParallelMinGear = kParallelMin;

}  // namespace

// start: r0 = q, r1 = v·Δt, r2 = a·Δt²/2, higher derivatives unknown and set to zero
void Gear6::init(std::span<const Channel> ch, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("Gear6::init: dt must be positive");
  layout_.set(ch);
  dt_ = dt;
  r_.assign(ch.size(), {});
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    const std::size_t n = k.q.size();
    auto& r = r_[c];
    r.assign(kN * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      r[kN * i] = k.q[i];
      r[kN * i + 1] = k.v[i] * dt;
      r[kN * i + 2] = k.a[i] * dt * dt / 2.0;
    }
  }
  note_velocities();
}

void Gear6::note_velocities() {
  vw_.assign(r_.size(), {});
  for (std::size_t c = 0; c < r_.size(); ++c) {
    const std::size_t n = r_[c].size() / kN;
    vw_[c].resize(n);
    for (std::size_t i = 0; i < n; ++i) vw_[c][i] = r_[c][kN * i + 1] / dt_;
  }
}

// an exact higher derivative: r_k = Δt^k/k!·d^k q/dt^k
void Gear6::set_derivative(std::size_t c, int k, std::span<const double> d) {
  if (c >= r_.size() || k < 2 || k > 5 || d.size() != layout_.size(c))
    throw std::invalid_argument("Gear6::set_derivative: bad channel, order or length");
  double scale = 1.0;
  for (int j = 1; j <= k; ++j) scale *= dt_ / j;
  const std::size_t n = d.size();
  for (std::size_t i = 0; i < n; ++i) r_[c][kN * i + static_cast<std::size_t>(k)] = d[i] * scale;
}

// a new Δt: r_k scales as Δt^k
void Gear6::rescale(double dt) {
  const double s = dt / dt_;
  for (auto& r : r_) {
    const std::size_t n = r.size() / kN;
    for (std::size_t i = 0; i < n; ++i) {
      double f = 1.0;
      for (int k = 1; k < kN; ++k) {
        f *= s;
        r[kN * i + static_cast<std::size_t>(k)] *= f;
      }
    }
  }
  dt_ = dt;
}

void Gear6::predict(std::span<const Channel> ch, double dt, const ThreadTeam& team) {
  layout_.check(ch, "Gear6::predict");
  if (!(dt > 0.0)) throw std::invalid_argument("Gear6::predict: dt must be positive");
  // pick up caller edits since the last correct() (periodic wrap of q, kicks to v): v counts
  // as edited when it differs from r1/Δt, which vw_ holds
  const bool rescaled = dt != dt_;
  if (rescaled) {
    for (std::size_t c = 0; c < ch.size(); ++c) {
      const auto& k = ch[c];
      const std::size_t n = k.q.size();
      double* r = r_[c].data();
      for (std::size_t i = 0; i < n; ++i) {
        if (k.q[i] != r[kN * i]) r[kN * i] = k.q[i];
        if (k.v[i] != vw_[c][i]) r[kN * i + 1] = k.v[i] * dt_;
      }
    }
    rescale(dt);
  }
  for_channels(team, ch, kParallelMinGear, [&](std::size_t c, std::size_t b, std::size_t e) {
    predict_dofs(ch[c], c, b, e, !rescaled);
  });
}

void Gear6::predict_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const std::size_t n = ch[c].q.size();
    // right after correct_dofs() q and v are r0 and r1/Δt: nothing to pick up
    predict_dofs(ch[c], c, std::min(b, n), std::min(e, n), false);
  }
}

void Gear6::predict_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e,
                         bool pick_up) {
  const double h = dt_;
  double* const r = r_[c].data();  // DOF i's six values at r[kN·i…kN·i + 5]
  double* const q = k.q.data();
  double* const v = k.v.data();
  double* const vw = vw_[c].data();
  for (std::size_t i = b; i < e; ++i) {
    double* const x = r + kN * i;
    double a0 = x[0], a1 = x[1];
    if (pick_up) {  // the pick-up, as in predict()
      if (q[i] != a0) a0 = q[i];
      if (v[i] != vw[i]) a1 = v[i] * h;
    }
    const double a2 = x[2], a3 = x[3], a4 = x[4], a5 = x[5];
    // Taylor step with the Pascal triangle (each line uses the old higher values)
    a0 += a1 + a2 + a3 + a4 + a5;
    a1 += 2.0 * a2 + 3.0 * a3 + 4.0 * a4 + 5.0 * a5;
    x[2] = a2 + (3.0 * a3 + 6.0 * a4 + 10.0 * a5);
    x[3] = a3 + (4.0 * a4 + 10.0 * a5);
    x[4] = a4 + 5.0 * a5;
    x[0] = a0;
    x[1] = a1;
    // the predicted state, where the caller evaluates the forces
    q[i] = a0;
    v[i] = vw[i] = a1 / h;
  }
}

void Gear6::check_correct(std::span<const Channel> ch, double dt) const {
  layout_.check(ch, "Gear6::correct");
  if (dt != dt_) throw std::invalid_argument("Gear6::correct: dt differs from predict()");
}

void Gear6::correct(std::span<const Channel> ch, double dt, const ThreadTeam& team) {
  check_correct(ch, dt);
  for_channels(team, ch, kParallelMinGear,
               [&](std::size_t c, std::size_t b, std::size_t e) { correct_dofs(ch[c], c, b, e); });
}

void Gear6::correct_range(std::span<const Channel> ch, std::size_t b, std::size_t e) {
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const std::size_t n = ch[c].q.size();
    correct_dofs(ch[c], c, std::min(b, n), std::min(e, n));
  }
}

void Gear6::correct_dofs(const Channel& k, std::size_t c, std::size_t b, std::size_t e) {
  const double h = dt_;
  const double h2 = h * h / 2.0;
  double* const r = r_[c].data();  // DOF i's six values at r[kN·i…kN·i + 5]
  const double* const a = k.a.data();
  double* const q = k.q.data();
  double* const v = k.v.data();
  double* const vw = vw_[c].data();
  for (std::size_t i = b; i < e; ++i) {
    double* const x = r + kN * i;
    // the acceleration mismatch Δr2 = a·Δt²/2 − r2ᵖ corrects every derivative
    const double d = a[i] * h2 - x[2];
    const double a0 = x[0] + kC[0] * d, a1 = x[1] + kC[1] * d;
    x[0] = a0;
    x[1] = a1;
    x[2] += kC[2] * d;
    x[3] += kC[3] * d;
    x[4] += kC[4] * d;
    x[5] += kC[5] * d;
    q[i] = a0;
    v[i] = vw[i] = a1 / h;
  }
}

// kinetic damping: the grains at rest where they are. r1 and the unknown higher derivatives
// go to zero as in init(); r2 already holds a·Δt²/2 of the last force evaluation
void Gear6::zero_velocities(std::span<const Channel> ch) {
  layout_.check(ch, "Gear6::zero_velocities");
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const std::size_t n = ch[c].q.size();
    double* const r = r_[c].data();
    for (std::size_t i = 0; i < n; ++i) {
      // a caller's edit of q since the last correct() is kept, as predict() would
      double* const x = r + kN * i;
      if (ch[c].q[i] != x[0]) x[0] = ch[c].q[i];
      x[1] = x[3] = x[4] = x[5] = 0.0;
      ch[c].v[i] = vw_[c][i] = 0.0;
    }
  }
}

void Gear6::permute(std::span<const std::uint32_t> perm) {
  for (std::size_t c = 0; c < layout_.channels(); ++c) {
    layout_.permute(r_[c], c, perm, kN, perm_tmp_);
    layout_.permute(vw_[c], c, perm, 1, perm_tmp_);
  }
}

// history: header, then the six scaled derivatives of every DOF, channel by channel
std::vector<double> Gear6::save() const {
  std::vector<double> out;
  layout_.write_header(out, kind(), dt_);
  // the six derivatives of each DOF together, as in memory
  for (const auto& r : r_) out.insert(out.end(), r.begin(), r.end());
  return out;
}

void Gear6::load(const std::vector<double>& data) {
  std::size_t off = layout_.read_header(data, kind(), dt_);
  if (data.size() != off + kN * layout_.total())
    throw InputError("checkpoint", "integrator.gear6", "integrator history has wrong length");
  r_.assign(layout_.channels(), {});
  for (std::size_t c = 0; c < layout_.channels(); ++c) {
    const std::size_t n = layout_.size(c);
    const auto first = data.begin() + static_cast<std::ptrdiff_t>(off);
    r_[c].assign(first, first + static_cast<std::ptrdiff_t>(kN * n));
    off += kN * n;
  }
  note_velocities();
}

}  // namespace gs
