// Model P's pair evaluator (docs/physics.md §2.2): polygons by their exact overlap, the
// overlap-area normal force with its dashpot (and the dashpot's moment along the contact line),
// Cundall–Strack friction carried from step to step (force/laws/pair_evaluator.hpp)
#pragma once
#include <cstddef>
#include <vector>

#include "contact/contact_set.hpp"
#include "contact/narrow.hpp"
#include "contact/placement.hpp"
#include "force/laws/pair_evaluator.hpp"
#include "force/laws/polygon_law.hpp"
#include "world/world.hpp"

namespace gs {

class PolygonPairEvaluator {
 public:
  static constexpr BodyKind kShape = BodyKind::Polygon;
  static constexpr bool kTorque = true;
  static constexpr bool kHistory = true;
  static constexpr bool kCheap = false;
  static constexpr std::size_t kChunk = 16;

  /// the world's species, materials and walls; throws std::logic_error where a polygon grain's
  /// radius, mass or inertia is not its species' (the pair constants stand for every grain)
  PolygonPairEvaluator(const World& w, const ContactSettings& settings);

  /// the walls placed and room for every grain; how many grains the pass must place
  std::size_t begin(const World& w, std::uint64_t /*generation*/) { return placed_.begin(w); }
  void place(const World& w, std::size_t b, std::size_t e) { placed_.place(w, b, e); }
  /// every grain placed ahead (place()) for the next pass
  void placed_ahead() { placed_.placed_ahead(); }
  static constexpr double common_radius() { return 0.0; }  // (radii are read per contact)

  /// one candidate; `history`: this thread's cursor over the last step's contacts. Inline: the
  /// pair loop keeps the contact's frame and force in registers
  [[gnu::always_inline]] bool pair(const World& w, PairKey key, HistoryCursor& history, double dt,
                                   PairForce& pf, PairResult& pr) const;

  /// the material constants of species a against b (b = species: a wall)
  const law::PolyLawParams& params(std::size_t a, std::size_t b) const {
    return params_[pair_index(nsp_, a, b)];
  }
  /// the binary contact time of a flat face, k ≈ E·side/l (linearised), s
  double contact_time(const World& w, std::size_t a, std::size_t b) const;

 private:
  /// the quantities of P.29–P.36 that depend on masses and radii only (every grain of a
  /// species has its values)
  struct PairConst {
    double l = 0, m_perp = 0, m_par = 0;  ///< l (m), m⊥ and m∥ (kg)
    double damp_n = 0;                    ///< γ·√(E·m⊥), kg/s
    double damp_t = 0;                    ///< √((2/7)·E·m∥), kg/s
  };
  PairConst pair_const(const World& w, std::size_t a, std::size_t b,
                       const law::PolyLawParams& p) const;
  std::size_t nsp_ = 0;
  std::vector<law::PolyLawParams> params_;  ///< pair_index layout
  std::vector<PairConst> const_;            ///< the same layout
  bool hdot_fd_ = false;
  bool rocking_ = true;
  PlacedPolygons placed_;
};

inline bool PolygonPairEvaluator::pair(const World& w, PairKey key, HistoryCursor& history,
                                       double dt, PairForce& pf, PairResult& pr) const {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  const std::uint32_t i = key_i(key), j = key_j(key);
  const bool wall = j >= N;
  const Vec2 xi{w.s.x[i], w.s.y[i]};
  const PolyRef& pi = placed_.grain(i);
  const PlacedBody a{xi, 0.0, &pi, {}, nullptr};
  ContactGeom g;
  Vec2 xj;
  if (wall) {
    const PolyRef& pw = placed_.wall(j - N);
    g = narrow<kShape, BodyKind::Wall>(a, PlacedBody{{}, 0.0, &pw, {}, &w.walls[j - N]});
  } else {
    xj = image_pos(w, j, key_image(key));
    const PolyRef& pj = placed_.grain(j);
    // a periodic image: the shift from j's polygon to the image (else none)
    const Vec2 shift = key_image(key) == kNoImage ? Vec2{} : xj - Vec2{w.s.x[j], w.s.y[j]};
    g = narrow<kShape, kShape>(a, PlacedBody{xj, 0.0, &pj, shift, nullptr});
  }
  if (!g.touching) return false;

  // the contact's history, if it touched last step
  ContactState state = history.find(key);

  // geometry of the pair (P.29–P.33): l, m⊥, m∥
  const std::size_t pk = pair_index(nsp_, w.sp[i], wall ? nsp_ : w.sp[j]);
  const law::PolyLawParams& p = params_[pk];
  const PairConst& pc = const_[pk];
  const double l = pc.l;

  // relative velocity of i against j at the contact point
  const Vec2 ri_s = g.s - xi;
  Vec2 vrel = Vec2{w.s.vx[i], w.s.vy[i]} + cross(w.s.omega[i], ri_s);
  if (!wall) vrel -= Vec2{w.s.vx[j], w.s.vy[j]} + cross(w.s.omega[j], g.s - xj);
  const Vec2 t = perp(g.n);
  const double vn = dot(vrel, g.n), vt = dot(vrel, t);

  // normal force (P.34) with ḣ_eff analytic (chord × approach speed / l) or by difference
  const double h = g.overlap / l;
  const double hdot = hdot_fd_ ? (h - state.h_prev) / dt  // h_prev = 0 before first touch
                               : g.chord * vn / l;
  state.h_prev = h;
  const double fn = law::poly_normal_force_damped(p, h, hdot, pc.damp_n);
  // tangential force (P.35–P.36); the force on i opposes its sliding: −F∥·t
  const double ft = law::cundall_strack_damped(p, state.spring, vt, fn, pc.damp_t, dt);

  // the same dashpot spread along the contact line: its moment about s damps relative
  // rotation, ∫ x·(γ√(E m⊥)/l)·ω_rel·x dx = γ√(E m⊥)·L³/(12 l)·ω_rel (only while pressing)
  double couple = 0.0;
  if (rocking_ && fn > 0.0) {
    const double w_rel = w.s.omega[i] - (wall ? 0.0 : w.s.omega[j]);
    couple = pc.damp_n * g.chord * g.chord * g.chord / (12.0 * l) * w_rel;
  }
  // j gets +fn·n + ft·t, i the opposite; torques about each centre
  const Vec2 F = g.n * fn + perp(g.n) * ft;
  pf = {F.x, F.y, cross(g.s - xi, F) + couple, wall ? 0.0 : cross(g.s - xj, F) + couple};
  pr = {g.degenerate, g.s, g.n, fn, ft, g.overlap, h, state};
  return true;
}

}  // namespace gs
