// sixth-order Gear predictor–corrector for second-order equations (SPEC 2.3)
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "integrate/schemes.hpp"

namespace gs {

namespace {
// corrector coefficients for q'' = a(q, q') with velocity-dependent forces (SPEC 2.3)
constexpr double kC[6] = {3.0 / 16.0, 251.0 / 360.0, 1.0, 11.0 / 18.0, 1.0 / 6.0, 1.0 / 60.0};
constexpr int kN = 6;  // values per degree of freedom
}  // namespace

// start: r0 = q, r1 = v·Δt, r2 = a·Δt²/2, higher derivatives unknown and set to zero
void Gear6::init(std::span<const Channel> ch, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("Gear6::init: dt must be positive");
  layout_.set(ch);
  dt_ = dt;
  r_.assign(ch.size(), {});
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    auto& r = r_[c];
    r.assign(kN * k.q.size(), 0.0);
    for (std::size_t i = 0; i < k.q.size(); ++i) {
      r[kN * i + 0] = k.q[i];
      r[kN * i + 1] = k.v[i] * dt;
      r[kN * i + 2] = k.a[i] * dt * dt / 2.0;
    }
  }
}

// an exact higher derivative: r_k = Δt^k/k!·d^k q/dt^k
void Gear6::set_derivative(std::size_t c, int k, std::span<const double> d) {
  if (c >= r_.size() || k < 2 || k > 5 || d.size() != layout_.size(c))
    throw std::invalid_argument("Gear6::set_derivative: bad channel, order or length");
  double scale = 1.0;
  for (int j = 1; j <= k; ++j) scale *= dt_ / j;
  for (std::size_t i = 0; i < d.size(); ++i) r_[c][kN * i + k] = d[i] * scale;
}

// a new Δt: r_k scales as Δt^k
void Gear6::rescale(double dt) {
  const double s = dt / dt_;
  for (auto& r : r_) {
    for (std::size_t i = 0; i < r.size(); i += kN) {
      double f = 1.0;
      for (int k = 1; k < kN; ++k) {
        f *= s;
        r[i + k] *= f;
      }
    }
  }
  dt_ = dt;
}

void Gear6::predict(std::span<const Channel> ch, double dt) {
  layout_.check(ch, "Gear6::predict");
  if (!(dt > 0.0)) throw std::invalid_argument("Gear6::predict: dt must be positive");
  // pick up caller edits since the last correct() (periodic wrap of q, kicks to v)
  auto pick_up = [this](const Channel& k, double* r) {
    for (std::size_t i = 0; i < k.q.size(); ++i, r += kN) {
      if (k.q[i] != r[0]) r[0] = k.q[i];
      if (k.v[i] != r[1] / dt_) r[1] = k.v[i] * dt_;
    }
  };
  const bool rescaled = dt != dt_;
  if (rescaled) {
    for (std::size_t c = 0; c < ch.size(); ++c) pick_up(ch[c], r_[c].data());
    rescale(dt);
  }
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    double* const rr = r_[c].data();
    parallel_ranges(k.q.size(), kParallelMinCheap, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        double* r = rr + kN * i;
        if (!rescaled) {  // the pick-up, as above
          if (k.q[i] != r[0]) r[0] = k.q[i];
          if (k.v[i] != r[1] / dt_) r[1] = k.v[i] * dt_;
        }
        // Taylor step with the Pascal triangle (each line uses the old higher values)
        r[0] += r[1] + r[2] + r[3] + r[4] + r[5];
        r[1] += 2.0 * r[2] + 3.0 * r[3] + 4.0 * r[4] + 5.0 * r[5];
        r[2] += 3.0 * r[3] + 6.0 * r[4] + 10.0 * r[5];
        r[3] += 4.0 * r[4] + 10.0 * r[5];
        r[4] += 5.0 * r[5];
        // the predicted state, where the caller evaluates the forces
        k.q[i] = r[0];
        k.v[i] = r[1] / dt_;
      }
    });
  }
}

void Gear6::correct(std::span<const Channel> ch, double dt) {
  layout_.check(ch, "Gear6::correct");
  if (dt != dt_) throw std::invalid_argument("Gear6::correct: dt differs from predict()");
  const double h2 = dt_ * dt_ / 2.0;
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const auto& k = ch[c];
    double* const rr = r_[c].data();
    parallel_ranges(k.q.size(), kParallelMinCheap, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        double* r = rr + kN * i;
        // the acceleration mismatch Δr2 = a·Δt²/2 − r2ᵖ corrects every derivative
        const double d = k.a[i] * h2 - r[2];
        for (int j = 0; j < kN; ++j) r[j] += kC[j] * d;
        k.q[i] = r[0];
        k.v[i] = r[1] / dt_;
      }
    });
  }
}

// history: header, then the six scaled derivatives of every DOF, channel by channel
std::vector<double> Gear6::save() const {
  std::vector<double> out;
  layout_.write_header(out, kind(), dt_);
  for (const auto& r : r_) out.insert(out.end(), r.begin(), r.end());
  return out;
}

void Gear6::load(const std::vector<double>& data) {
  std::size_t off = layout_.read_header(data, kind(), dt_);
  if (data.size() != off + kN * layout_.total())
    throw InputError("checkpoint", "integrator.gear6", "integrator history has wrong length");
  r_.assign(layout_.channels(), {});
  for (std::size_t c = 0; c < layout_.channels(); ++c) {
    const std::size_t n = kN * layout_.size(c);
    r_[c].assign(data.begin() + static_cast<std::ptrdiff_t>(off),
                 data.begin() + static_cast<std::ptrdiff_t>(off + n));
    off += n;
  }
}

}  // namespace gs
