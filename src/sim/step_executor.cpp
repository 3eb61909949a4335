#include "sim/step_executor.hpp"

#include <stdexcept>
#include <vector>

#include "core/parallel.hpp"
#include "integrate/range_stepping.hpp"
#include "sim/stage_trace.hpp"

namespace gs {
namespace {

void lap(StageClock* clock, Stage s) {
  if (clock != nullptr) clock->lap(s);
}

// one stage as a pass of its own (with a test's record of the state after it)
void run_whole(StepStage& s, StepContext& c, StageClock* clock) {
  s.prepare(c);
  if (c.trace != nullptr) c.trace->open(s.id(), c);
  s.pass(c);
  s.finish(c);
  lap(clock, s.id());
  if (c.trace != nullptr) {
    c.trace->take(s.id(), c, 0, c.p().w.size());
    c.trace->close(s.id(), c);
  }
}

// each stage one pass of its own, in the order of the list
class StagedExecutor final : public StepExecutor {
 public:
  ExecutorKind kind() const override { return ExecutorKind::Staged; }
  bool predicts_ahead(const StepParts&) const override { return false; }
  bool kicks_in_pass(const StepParts&) const override { return false; }
  void run(const StageList& list, StepContext& c, StageClock* clock) override {
    c.ahead = false;
    c.predicted = false;
    for (const auto& s : list)
      if (s->runs(c)) run_whole(*s, c, clock);
  }
};

// the by-range stages of a pair loop's particle phase: each over the thread's particles in
// turn, the first thread lapping the clock after each (the pairs' own time up to the first)
class TailPhase final : public ParticlePhase {
 public:
  TailPhase(const std::vector<StepStage*>& stages, StepContext& c, StageClock* clock)
      : stages_(stages), c_(c), clock_(clock) {}
  void run(std::size_t b, std::size_t e) override {
    StageClock* const own = team_thread() == 0 ? clock_ : nullptr;
    lap(own, Stage::Pairs);
    if (c_.trace != nullptr) c_.trace->take(Stage::Pairs, c_, b, e);
    for (StepStage* s : stages_) {
      s->range(c_, b, e);
      lap(own, s->id());
      if (c_.trace != nullptr) c_.trace->take(s->id(), c_, b, e);
    }
  }

 private:
  const std::vector<StepStage*>& stages_;
  StepContext& c_;
  StageClock* clock_;
};

// the stages after the pair loop run by ranges inside its particle phase, as far as each can
class FusedExecutor final : public StepExecutor {
 public:
  ExecutorKind kind() const override { return ExecutorKind::Fused; }
  // the kick predicts (disks), or the integrator by ranges (Gear 6; not on the noisy ring,
  // whose correction is a whole pass)
  bool predicts_ahead(const StepParts& p) const override {
    return kicks_in_pass(p) || (p.integ.ranges().predicts_by_range() && !ring_noise(p));
  }
  bool kicks_in_pass(const StepParts& p) const override { return kick_possible(p); }
  void run(const StageList& list, StepContext& c, StageClock* clock) override;

 private:
  // the stage that runs for s in this step: s, the kick in its place, or none (the kick's)
  StepStage* stand_in(StepStage& s, bool kick) {
    if (!kick) return &s;
    switch (s.id()) {
      case Stage::Accelerate:
        return kick_.get();
      case Stage::Correct:
      case Stage::PredictNext:
        return nullptr;
      default:
        return &s;
    }
  }

  std::unique_ptr<StepStage> kick_ = make_kick_stage();
  std::vector<StepStage*> tail_;  ///< this step's particle phase
  bool predicted_ = false;        ///< the last step predicted the next one
};

void FusedExecutor::run(const StageList& list, StepContext& c, StageClock* clock) {
  c.predicted = predicted_ && !c.start;
  if (c.predicted) ++predicted_steps_;
  predicted_ = false;
  c.ahead = c.may_ahead && !c.start && predicts_ahead(c.p());
  const bool kick = !c.start && kicks_in_pass(c.p());
  for (std::size_t i = 0; i < list.size(); ++i) {
    StepStage* s = stand_in(*list[i], kick);
    if (s == nullptr || !s->runs(c)) continue;
    if (!s->hosts_ranges()) {
      run_whole(*s, c, clock);
      continue;
    }
    // the following stages that run by ranges, up to the first that does not
    tail_.clear();
    std::size_t j = i + 1;
    for (; j < list.size(); ++j) {
      StepStage* t = stand_in(*list[j], kick);
      if (t == nullptr || !t->runs(c)) continue;
      if (!t->by_range(c)) break;
      tail_.push_back(t);
    }
    if (tail_.empty()) {
      run_whole(*s, c, clock);
      continue;
    }
    s->prepare(c);
    for (StepStage* t : tail_) t->prepare(c);
    if (c.trace != nullptr) {
      c.trace->open(s->id(), c);
      for (StepStage* t : tail_) c.trace->open(t->id(), c);
    }
    TailPhase phase(tail_, c, clock);
    s->pass_with(c, phase);
    s->finish(c);
    for (StepStage* t : tail_) t->finish(c);
    lap(clock, s->id());  // the contact set kept, the team's wait at the end of the pass
    if (c.trace != nullptr) c.trace->close(s->id(), c);
    i = j - 1;
  }
  predicted_ = c.ahead;
}

}  // namespace

std::unique_ptr<StepExecutor> make_executor(ExecutorKind k) {
  if (k == ExecutorKind::Staged) return std::make_unique<StagedExecutor>();
  return std::make_unique<FusedExecutor>();
}

}  // namespace gs
