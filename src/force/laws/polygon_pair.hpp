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

  /// one candidate; `hint`: where this thread's last history lookup ended (ContactSet::history)
  bool pair(const World& w, PairKey key, const ContactSet& cs, std::size_t& hint, double dt,
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

}  // namespace gs
