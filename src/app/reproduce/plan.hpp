// what `gransim reproduce` runs for each study and budget: a list of sweeps of the shipped
// scenes, each a `gransim sweep` into DIR/sweeps/<name>, and the cost it projects
#pragma once
#include <string>
#include <vector>

namespace gs {

enum class Budget { Smoke, Quick, Standard, Full };

/// "smoke", "quick", … ; throws InputError naming --budget for an unknown word
Budget parse_budget(const std::string& word);
const char* budget_name(Budget b);

/// one sweep of the plan
struct PlannedSweep {
  std::string name;                        ///< folder under DIR/sweeps and its role in the report
  std::string scene;                       ///< scene file, relative to the scenes folder
  std::vector<std::string> params;         ///< --param texts
  std::vector<std::string> sets;           ///< --set texts
  double particle_steps = 0.0;             ///< projected particle-steps of the whole sweep
  double longest_run = 0.0;                ///< projected particle-steps of its longest run
  int runs = 0;                            ///< runs in the sweep
  double seconds_per_particle_step = 0.0;  ///< core-seconds per particle-step of its model
};

/// the study at one budget
struct ReproducePlan {
  std::string study;  ///< "tapping" or "rfm"
  Budget budget = Budget::Quick;
  std::vector<PlannedSweep> sweeps;
  std::string purpose;               ///< what this budget resolves, one sentence
  bool resolves = true;              ///< false: its runs prove the pipeline only, and its
                                     ///< report gives no verdict
  double core_hours() const;         ///< projected core-hours of every sweep
  double longest_run_hours() const;  ///< projected hours of the longest run (one core)
  int widest_sweep() const;          ///< runs in the largest sweep: ranks that can be busy
};

/// the plan of a study ("tapping", "rfm") at a budget; throws InputError for an unknown study
ReproducePlan make_plan(const std::string& study, Budget budget);

}  // namespace gs
