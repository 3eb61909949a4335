// a record of the state after each stage of a step, for comparing two executors stage by
// stage (sim/step_inspector.hpp): the executor writes it where a test attached one
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "broadphase/broadphase.hpp"
#include "core/stage_clock.hpp"

namespace gs {

struct StepContext;

class StageTrace {
 public:
  /// the per-particle fields a record keeps: the state, then the contact forces
  static constexpr std::size_t kFields = 12;
  static const std::array<const char*, kFields>& field_names();
  struct Record {
    std::int64_t step = 0;  ///< the step the state belongs to (its count before it)
    /// what the state is after: a stage's prediction for the next step (predict-next, the
    /// kick run back to back) counts as that step's predict
    Stage as = Stage::Predict;
    Stage ran = Stage::Predict;  ///< the stage that ran
    std::array<std::vector<double>, kFields> fields;
    std::vector<PairKey> pairs;  ///< the broad phase's candidates; the pairs' contact set
  };
  /// before stage s runs (outside any parallel region): its record opened (Drive, Health and
  /// PlaceNext, which change no compared field, are not recorded)
  void open(Stage s, const StepContext& c);
  /// particles [b, e) of the state after stage s (disjoint ranges may run at once)
  void take(Stage s, const StepContext& c, std::size_t b, std::size_t e);
  /// after stage s: its pair list, and the record closed
  void close(Stage s, const StepContext& c);
  std::vector<Record>& records() { return records_; }

 private:
  std::vector<Record> records_;
  std::array<int, kStageCount> open_ = [] {
    std::array<int, kStageCount> a{};
    a.fill(-1);
    return a;
  }();
};

/// the first particle (and field, in field_names() order) or pair where two records of the
/// same stage differ in their bits, as "particle i, field f: a vs b"; empty where none
std::string first_difference(const StageTrace::Record& a, const StageTrace::Record& b);

}  // namespace gs
