// observers: read-only measurements hooked into a run. They see the Simulation after every
// step (and decide themselves when to sample), write their own files in the run directory,
// and never change state.
#pragma once
#include <memory>
#include <string>
#include <vector>

namespace gs {

class Simulation;

class Observer {
 public:
  virtual ~Observer() = default;
  /// the run starts; files go into run_dir
  virtual void start(const Simulation& sim, const std::string& run_dir) = 0;
  /// after every step (keep it cheap: sample on your own interval)
  virtual void after_step(const Simulation& sim) = 0;
  /// the run ends (completed, interrupted or stopped by a health check): flush everything
  virtual void finish(const Simulation& sim) = 0;
};

using Observers = std::vector<std::unique_ptr<Observer>>;

}  // namespace gs
