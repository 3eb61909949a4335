// integrator names, orders, the factory, and the channel layout / checkpoint header
#include "integrate/integrator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "integrate/schemes.hpp"

namespace gs {

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings) {
  switch (settings.kind) {
    case IntegratorKind::Gear6:
      return std::make_unique<Gear6>();
    case IntegratorKind::VelocityVerlet:
      return std::make_unique<VelocityVerlet>(VerletForceVelocity::Extrapolated,
                                              settings.verlet_correction);
    case IntegratorKind::PositionVerlet:
      return std::make_unique<PositionVerlet>();
    case IntegratorKind::SemiImplicitEuler:
      return std::make_unique<SemiImplicitEuler>();
  }
  throw std::invalid_argument("make_integrator: unknown integrator kind");
}

// the layout: channel lengths, checked on every call so a stale history is never applied
void ChannelLayout::set(std::span<const Channel> ch) {
  sizes_.clear();
  for (const auto& c : ch) {
    if (c.v.size() != c.q.size() || c.a.size() != c.q.size())
      throw std::invalid_argument("integrator: channel q, v, a lengths differ");
    sizes_.push_back(c.q.size());
  }
}

void ChannelLayout::check(std::span<const Channel> ch, const char* who) const {
  bool ok = ch.size() == sizes_.size();
  for (std::size_t c = 0; ok && c < ch.size(); ++c)
    ok = ch[c].q.size() == sizes_[c] && ch[c].v.size() == sizes_[c] && ch[c].a.size() == sizes_[c];
  if (!ok)
    throw std::invalid_argument(std::string(who) +
                                ": channel layout differs from init(); call init() again "
                                "after adding or removing bodies");
}

void ChannelLayout::permute(std::vector<double>& v, std::size_t c,
                            std::span<const std::uint32_t> perm, std::size_t stride,
                            std::vector<double>& tmp) const {
  if (perm.size() != sizes_.at(c) || v.size() != perm.size() * stride)
    throw std::invalid_argument("Integrator::permute: the permutation does not fit the history");
  tmp.resize(v.size());
  for (std::size_t k = 0; k < perm.size(); ++k)
    for (std::size_t m = 0; m < stride; ++m) tmp[k * stride + m] = v[perm[k] * stride + m];
  v.swap(tmp);
}

std::size_t ChannelLayout::total() const {
  std::size_t n = 0;
  for (auto s : sizes_) n += s;
  return n;
}

// checkpoint header: a tag naming the scheme, a format version, Δt, then the layout
namespace {
constexpr double kTagBase = 7100.0;
constexpr double kVersion = 1.0;
}  // namespace

void ChannelLayout::write_header(std::vector<double>& out, IntegratorKind k, double dt) const {
  out.push_back(kTagBase + static_cast<double>(k));
  out.push_back(kVersion);
  out.push_back(dt);
  out.push_back(static_cast<double>(sizes_.size()));
  for (auto s : sizes_) out.push_back(static_cast<double>(s));
}

std::size_t ChannelLayout::read_header(const std::vector<double>& in, IntegratorKind k,
                                       double& dt) {
  const std::string key = "integrator." + std::string(to_string(k));
  if (in.size() < 4 || in[0] != kTagBase + static_cast<double>(k))
    throw InputError("checkpoint", key, "integrator history is not from this integrator");
  if (in[1] != kVersion)
    throw InputError("checkpoint", key, "unsupported integrator history version");
  dt = in[2];
  const double nch = in[3];
  if (!(nch >= 0.0) || nch != std::floor(nch) || in.size() < 4 + static_cast<std::size_t>(nch))
    throw InputError("checkpoint", key, "truncated integrator history");
  sizes_.clear();
  for (std::size_t c = 0; c < static_cast<std::size_t>(nch); ++c) {
    const double s = in[4 + c];
    if (!(s >= 0.0) || s != std::floor(s))
      throw InputError("checkpoint", key, "bad channel length in integrator history");
    sizes_.push_back(static_cast<std::size_t>(s));
  }
  return 4 + sizes_.size();
}

}  // namespace gs
