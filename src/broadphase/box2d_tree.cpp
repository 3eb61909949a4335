// Box2D 2.4.1's b2BroadPhase (dynamic AABB tree with fat AABBs) with a persistent pair set
// pruned by TestOverlap, as Box2D's own b2ContactManager does. Coordinates are scaled so a
// grain is about one unit, because the fattening margin is a fixed 0.1 units. Walled boxes only.
#include <box2d/b2_broad_phase.h>

#include <algorithm>
#include <cmath>

#include "broadphase/broadphase.hpp"

namespace gs {
namespace {

class Box2DTree final : public BroadPhase {
 public:
  const char* name() const override { return "box2d_tree"; }

  using BroadPhase::update;
  const std::vector<PairKey>& update(const World& w, const ThreadTeam&) override {
    std::vector<PairKey>& out = out_;
    const std::size_t n = w.size();
    if (!built_ || n != n_) build(w);

    // move every particle's proxy (Box2D skips those still inside their fat AABB)
    for (std::size_t i = 0; i < n; ++i) {
      const b2Vec2 c(static_cast<float>(w.s.x[i] * inv_scale_),
                     static_cast<float>(w.s.y[i] * inv_scale_));
      const b2Vec2 disp = c - last_pos_[i];
      last_pos_[i] = c;
      bp_->MoveProxy(proxy_[i], aabb_of(w, i), disp);
    }

    // new pairs from the tree, merged into the persistent set
    fresh_.clear();
    bp_->UpdatePairs(this);
    std::sort(fresh_.begin(), fresh_.end());
    merged_.clear();
    std::set_union(pairs_.begin(), pairs_.end(), fresh_.begin(), fresh_.end(),
                   std::back_inserter(merged_));

    // prune pairs whose fat AABBs no longer overlap; emit those whose bounding circles do
    pairs_.clear();
    out.clear();
    const std::uint32_t N = static_cast<std::uint32_t>(n);
    for (PairKey k : merged_) {
      const std::uint32_t i = key_i(k), j = key_j(k);
      if (!bp_->TestOverlap(proxy_of(i), proxy_of(j))) continue;
      pairs_.push_back(k);
      const Vec2 pi{w.s.x[i], w.s.y[i]};
      if (j >= N) {
        const Wall& wl = w.walls[j - N];
        if (circle_box_overlap(pi, w.radius[i], wl.lo, wl.hi)) out.push_back(k);
      } else {
        const double dx = w.s.x[j] - pi.x, dy = w.s.y[j] - pi.y, rr = w.radius[i] + w.radius[j];
        if (dx * dx + dy * dy < rr * rr) out.push_back(k);
      }
    }
    if (out != last_) {
      new_generation();
      last_ = out;
    }
    return out;
  }

  // b2BroadPhase::UpdatePairs callback: user data carries the body index + 1
  void AddPair(void* a, void* b) {
    auto ia = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(a) - 1);
    auto ib = static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(b) - 1);
    if (ia >= n_ && ib >= n_) return;  // wall–wall
    if (ia > ib) std::swap(ia, ib);
    fresh_.push_back(make_key(ia, ib, kNoImage));
  }

 private:
  b2AABB aabb_of(const World& w, std::size_t i) const {
    const double r = w.radius[i];
    b2AABB box;
    box.lowerBound.Set(static_cast<float>((w.s.x[i] - r) * inv_scale_),
                       static_cast<float>((w.s.y[i] - r) * inv_scale_));
    box.upperBound.Set(static_cast<float>((w.s.x[i] + r) * inv_scale_),
                       static_cast<float>((w.s.y[i] + r) * inv_scale_));
    return box;
  }
  int proxy_of(std::uint32_t body) const {
    return body < n_ ? proxy_[body] : wall_proxy_[body - n_];
  }

  // one proxy per particle and per wall; scale = largest grain diameter
  void build(const World& w) {
    bp_ = std::make_unique<b2BroadPhase>();
    n_ = w.size();
    inv_scale_ = 1.0 / (2.0 * w.max_radius);
    proxy_.resize(n_);
    last_pos_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      proxy_[i] = bp_->CreateProxy(aabb_of(w, i), reinterpret_cast<void*>(i + 1));
      last_pos_[i].Set(static_cast<float>(w.s.x[i] * inv_scale_),
                       static_cast<float>(w.s.y[i] * inv_scale_));
    }
    wall_proxy_.clear();
    for (std::size_t k = 0; k < w.walls.size(); ++k) {
      b2AABB box;
      box.lowerBound.Set(static_cast<float>(w.walls[k].lo.x * inv_scale_),
                         static_cast<float>(w.walls[k].lo.y * inv_scale_));
      box.upperBound.Set(static_cast<float>(w.walls[k].hi.x * inv_scale_),
                         static_cast<float>(w.walls[k].hi.y * inv_scale_));
      wall_proxy_.push_back(bp_->CreateProxy(box, reinterpret_cast<void*>(n_ + k + 1)));
    }
    pairs_.clear();
    built_ = true;
  }

  std::unique_ptr<b2BroadPhase> bp_;
  bool built_ = false;
  std::size_t n_ = 0;
  double inv_scale_ = 1.0;
  std::vector<int> proxy_, wall_proxy_;
  std::vector<b2Vec2> last_pos_;
  std::vector<PairKey> pairs_, fresh_, merged_;
  std::vector<PairKey> out_, last_;  ///< this update's candidates, and the previous ones
};

}  // namespace

std::unique_ptr<BroadPhase> make_box2d_tree() { return std::make_unique<Box2DTree>(); }

}  // namespace gs
