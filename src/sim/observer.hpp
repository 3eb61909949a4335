// observers: read-only measurements hooked into a run. They see the Simulation after every
// step (decide themselves when to sample) and never change state; what they record goes into
// the run directory (measure/'s observers hand their rows to a RecordSink, core/records.hpp).
// A run that checkpoints asks each observer for its state (save) and a resumed run hands it
// back (resume instead of start); see docs/robustness.md.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/bytes.hpp"

namespace gs {

class Simulation;

class Observer {
 public:
  virtual ~Observer() = default;
  /// a stable name: the key of this observer's state in a checkpoint
  virtual const char* name() const = 0;
  /// the run starts; what it records goes into run_dir
  virtual void start(const Simulation& sim, const std::string& run_dir) = 0;
  /// after every step (keep it cheap: sample on your own interval)
  virtual void after_step(const Simulation& sim) = 0;
  /// how many of the coming steps after_step may miss (it is then called after a later one):
  /// the run loop lets the simulation run that many steps at once (Simulation::run). 0, the
  /// default: every step. May answer low, never high
  virtual std::int64_t quiet_steps(const Simulation& sim) const {
    (void)sim;
    return 0;
  }
  /// the run ends (completed, interrupted, stopped by a health check or a failed write): write
  /// the end-of-run tables and summaries
  virtual void finish(const Simulation& sim) = 0;
  /// checkpoint (between two steps, files flushed): everything needed to continue exactly —
  /// accumulators, counters. Files are not saved: the run stores their sizes and truncates
  /// them to those sizes on resume.
  virtual void save(ByteWriter& out) const = 0;
  /// continue a run from a checkpoint instead of start(): continue its tables (appending) and
  /// take back what save() wrote. `sim` is the restored simulation.
  virtual void resume(const Simulation& sim, const std::string& run_dir, ByteReader& in) = 0;
};

using Observers = std::vector<std::unique_ptr<Observer>>;

}  // namespace gs
