// what `gransim reproduce` runs for each study and budget: a list of sweeps of the shipped
// scenes, each a `gransim sweep` into DIR/sweeps/<name>, and the cost it projects
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "app/reproduce/pile_cost.hpp"

namespace gs {

enum class Budget { Smoke, Quick, Standard, Full };

/// "smoke", "quick", … ; throws InputError naming --budget for an unknown word
Budget parse_budget(const std::string& word);
const char* budget_name(Budget b);

/// one physical system a sweep runs (each with every seed and start of the sweep)
struct PlannedPoint {
  double phi = 0.0;     ///< 2D: Nπr²/L²; 1D: N·d/L, the line's covered fraction
  double eps_n = 0.0;   ///< normal restitution
  double eps_t = 0.0;   ///< tangential restitution (1 on the ring: no tangential motion)
  double length = 0.0;  ///< 2D: the box side L; 1D: the reduced length L′ = L − N·d (m)
  int particles = 0;    ///< N
};

/// the source's conditions a sweep's runs match: what a verdict checks before it judges a claim
struct PlannedConditions {
  int dimension = 2;                 ///< 2: periodic square box, 1: ring
  std::vector<std::string> claims;   ///< the claims these runs are for
  std::vector<PlannedPoint> points;  ///< the systems, each run from every seed and start
  std::vector<std::uint64_t> seeds;  ///< preparation.seed of the runs: placement and noise
  std::vector<std::string> starts;   ///< preparation.placement of the runs
  double duration = 0.0;             ///< simulated seconds of each run
  double discard = 0.0;              ///< seconds discarded before sampling
  double sampled() const { return duration - discard; }  ///< sampled seconds of each run
};

/// one sweep of the plan
struct PlannedSweep {
  std::string name;                 ///< folder under DIR/sweeps and its role in the report
  std::string scene;                ///< scene file, relative to the scenes folder
  std::vector<std::string> params;  ///< --param texts (several: every combination)
  std::vector<std::string> sets;    ///< --set texts
  std::vector<double> run_seconds;  ///< projected core-seconds of each run, in the order the
                                    ///< pool starts them
  PlannedConditions conditions;     ///< what the runs are, for the verdicts (RFM only)
  double core_seconds() const;      ///< projected core-seconds of the whole sweep
};

/// a run of one of the program's auxiliary models (`gransim model …`) into DIR/models/<name>,
/// after the sweeps and their analyses; a folder with its model.json is done
struct PlannedModel {
  std::string name;                 ///< folder under DIR/models
  std::vector<std::string> args;    ///< the arguments after `gransim`, without --out; a
                                    ///< leading "DIR/" stands for the study's folder
  std::vector<std::string> claims;  ///< the claims it serves
  double core_seconds = 0.0;        ///< projected core-seconds (one thread)
  std::string needs;                ///< a file under DIR it reads (an analysis' output): the
                                    ///< model waits, skipped, until it exists; "" none
};

/// the study at one budget
struct ReproducePlan {
  std::string study;  ///< "tapping" or "rfm"
  Budget budget = Budget::Quick;
  std::vector<PlannedSweep> sweeps;
  std::vector<PlannedModel> models;  ///< model runs after the sweeps (RFM)
  std::string purpose;               ///< what this budget resolves, and what it cannot reach
  bool resolves = true;              ///< false: its runs prove the pipeline only, and its
                                     ///< report gives no verdict
  PileCost cost;  ///< the measured cost a particle-step (tapping: the pile; RFM: the ring)
  double core_hours() const;         ///< projected core-hours of every sweep
  double longest_run_hours() const;  ///< projected hours of the longest run (one core)
  int widest_sweep() const;          ///< runs in the largest sweep: ranks that can be busy
  int runs() const;                  ///< runs of every sweep
  /// projected wall hours with `slots` runs at a time, the runs started in the pool's order
  /// (each sweep's runs in turn) as soon as a slot is free
  double wall_hours(int slots) const;
  /// projected wall hours when each sweep spreads over `slots` ranks in turn (under MPI)
  double sweep_by_sweep_wall_hours(int slots) const;
};

/// the plan of a study ("tapping", "rfm") at a budget; `pile_cost`: what a particle-step of the
/// paper pile costs, which scales the tapping runs' projections; throws InputError for an
/// unknown study
ReproducePlan make_plan(const std::string& study, Budget budget, const PileCost& pile_cost = {});

/// simulated seconds of a negative-g tap of the paper pile with early rest and the quench
double neg_tap_seconds(double g_p);
/// the fast paper scenes' time step, s
inline constexpr double kPaperDt = 1.0 / 7500.0;

/// DIR/plan.json: the plan, its projection at `slots` runs at a time, and each RFM sweep's
/// conditions (src/app/reproduce/README.md)
std::string plan_json(const ReproducePlan& p, const std::string& command, int slots);

/// core-seconds per particle-step of the RFM scenes on the machine the plan was measured on:
/// the 2D reference fluid, the dense dissipative one and the ring (L′ = 1 m) at N particles
double rfm_cost_fluid();
double rfm_cost_dense(int particles);
double rfm_cost_ring(int particles);

namespace plan_detail {
/// plan_rfm.cpp; `scale`: this machine's cost over the one that measured the RFM costs
ReproducePlan rfm_plan(Budget b, double scale = 1.0);
}  // namespace plan_detail

}  // namespace gs
