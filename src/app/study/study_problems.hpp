// the reference problems of `gransim study`: build the scene of one combination, run it,
// time it, and return the measured quantity (the error is taken against it in study.cpp)
#pragma once
#include <cmath>
#include <cstdint>
#include <string>

#include "app/study/study.hpp"

namespace gs {

/// one combination of the matrix for one problem
struct StudyCase {
  StudyProblem problem = StudyProblem::TwoDisk;
  IntegratorKind integrator = IntegratorKind::Gear6;
  double dt_over_tc = 0.05;
  BroadPhaseKind broad_phase = BroadPhaseKind::CellGrid;
  StudySwitches switches;
};

/// what one run measured
struct StudyOutcome {
  double tc = 0.0;  ///< contact time of the stiffest binary contact, s
  double dt = 0.0;  ///< time step, s
  int particles = 0;
  std::int64_t steps = 0;
  double sim_time = 0.0;  ///< simulated time, s
  double wall_s = 0.0;    ///< wall time of the stepping (setup excluded), s
  /// the measured quantity: realised restitution (two-body), relative energy drift per
  /// simulated second (gas_energy), measured/predicted Haff slope (haff), φ (pile)
  double value = 0.0;
  double final_ke = 0.0;    ///< kinetic energy at the end, J
  double stat_error = 0.0;  ///< statistical error of the value where one exists (haff;
                            ///< tapping, rfm: 95% half-width of the mean)
  // the statistical problems (tapping, rfm_temperature)
  double sd = NAN;            ///< spread of the samples: σ_φ (tapping), σ_T (rfm)
  double sd_stat = NAN;       ///< 95% half-width of sd (chi-square, τ_int-corrected)
  double tau_int = NAN;       ///< integrated autocorrelation time of the samples, samples
  int samples = 0;            ///< samples in the mean (taps after the discarded ones)
  double wall_per_tap = NAN;  ///< tapping: wall time per tap after settling, s
  bool stable = true;
  std::string note;  ///< health message, or what else is worth knowing
};

/// contact time (s) of a problem's stiffest binary contact (independent of Δt)
double study_contact_time(const StudySizes& z, StudyProblem p);

/// run one combination; a HealthError (or any failure of the run) gives stable = false with
/// the message, never an exception
StudyOutcome run_study_case(const StudySizes& z, const StudyCase& c);

/// does a problem use walls (the only ones where the broad phase can be chosen)?
bool study_problem_walled(StudyProblem p);

// the statistical problems (app/study/study_problems_stat.cpp)
/// contact time of tapping / rfm_temperature, s
double stat_problem_contact_time(const StudySizes& z, StudyProblem p);
/// run one tapping / rfm_temperature combination (exceptions are left to run_study_case)
void run_stat_problem(const StudySizes& z, const StudyCase& c, StudyOutcome& o);

}  // namespace gs
