// the stages of a step other than the accelerations (sim/accelerate.cpp): each a whole pass
// and, where a particle's result is its own, a pass by ranges with the same bits
#include "sim/stages.hpp"

#include <stdexcept>
#include <string>

#include "integrate/range_stepping.hpp"

namespace gs {

void StepStage::pass_with(StepContext&, ParticlePhase&) {
  throw std::logic_error(std::string(stage_name(id())) + ": no particle phase");
}

void StepStage::range(StepContext&, std::size_t, std::size_t) {
  throw std::logic_error(std::string(stage_name(id())) + ": no pass by ranges");
}

namespace {

// positions and velocities at t + Δt, unless the last step's correction predicted them
class PredictStage final : public StepStage {
 public:
  Stage id() const override { return Stage::Predict; }
  bool runs(const StepContext& c) const override { return !c.start && !c.predicted; }
  void pass(StepContext& c) override { c.p().integ.predict(c.ch, c.p().dt, c.p().team); }
};

class BroadPhaseStage final : public StepStage {
 public:
  Stage id() const override { return Stage::BroadPhase; }
  bool runs(const StepContext&) const override { return true; }
  void pass(StepContext& c) override { c.candidates = &c.p().broad.update(c.p().w, c.p().team); }
};

// the pair loop over the candidates: contacts, laws, the contact set, each particle's sums
class PairsStage final : public StepStage {
 public:
  Stage id() const override { return Stage::Pairs; }
  bool runs(const StepContext&) const override { return true; }
  bool hosts_ranges() const override { return true; }
  void pass(StepContext& c) override { evaluate(c, nullptr); }
  void pass_with(StepContext& c, ParticlePhase& then) override { evaluate(c, &then); }

 private:
  static void evaluate(StepContext& c, ParticlePhase* then) {
    const StepParts& p = c.p();
    p.stats = p.model.evaluate(p.w, *c.candidates, p.contacts, p.forces, p.dt, p.team,
                               p.broad.generation(), then);
  }
};

class CorrectStage final : public StepStage {
 public:
  Stage id() const override { return Stage::Correct; }
  bool runs(const StepContext& c) const override { return !c.start; }
  bool by_range(const StepContext&) const override { return true; }
  void prepare(StepContext& c) override { c.p().integ.ranges().check_correct(c.ch, c.p().dt); }
  void pass(StepContext& c) override { c.p().integ.correct(c.ch, c.p().dt, c.p().team); }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    c.p().integ.ranges().correct_range(c.ch, b, e);
  }
};

// run back to back: the next step's prediction right after the correction (the next step's
// predict stage then does not run)
class PredictNextStage final : public StepStage {
 public:
  Stage id() const override { return Stage::PredictNext; }
  bool runs(const StepContext& c) const override { return c.ahead; }
  bool by_range(const StepContext& c) const override {
    return c.p().integ.ranges().predicts_by_range();
  }
  void pass(StepContext& c) override { c.p().integ.predict(c.ch, c.p().dt, c.p().team); }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    c.p().integ.ranges().predict_range(c.ch, b, e);
  }
};

// run back to back: the next step's polygons placed while their state is at hand (the next
// pair pass does not place them again)
class PlaceNextStage final : public StepStage {
 public:
  Stage id() const override { return Stage::PlaceNext; }
  bool runs(const StepContext& c) const override { return c.ahead && c.p().w.polygons(); }
  bool by_range(const StepContext&) const override { return true; }
  void pass(StepContext& c) override { range(c, 0, c.p().w.size()); }
  void range(StepContext& c, std::size_t b, std::size_t e) override {
    c.p().model.place_ahead(c.p().w, b, e);
  }
  void finish(StepContext& c) override { c.p().model.placed_ahead(); }
};

}  // namespace

std::unique_ptr<StepStage> make_predict_stage() { return std::make_unique<PredictStage>(); }
std::unique_ptr<StepStage> make_broad_phase_stage() { return std::make_unique<BroadPhaseStage>(); }
std::unique_ptr<StepStage> make_pairs_stage() { return std::make_unique<PairsStage>(); }
std::unique_ptr<StepStage> make_correct_stage() { return std::make_unique<CorrectStage>(); }
std::unique_ptr<StepStage> make_predict_next_stage() {
  return std::make_unique<PredictNextStage>();
}
std::unique_ptr<StepStage> make_place_next_stage() { return std::make_unique<PlaceNextStage>(); }

}  // namespace gs
