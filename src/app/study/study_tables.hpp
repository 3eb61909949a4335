// what a speed-accuracy study writes: study.csv, stability.csv and study.json, one row per
// combination (problem, integrator, Δt, broad phase, switches) and per stability bar
#pragma once
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "app/study/study_problems.hpp"

namespace gs::study_detail {

// one row of study.csv: the combination, its outcome, and the error against its reference
struct StudyRow {
  StudyCase c;
  StudyOutcome o;
  double error = NAN;
  std::string error_kind;
  double reference = NAN;  ///< the value the error is taken against
  // the statistical problems: the spread (σ_φ, σ_T) against the reference's
  double sd_reference = NAN;
  double sd_error = NAN;       ///< |sd − sd_ref| (tapping), relative (rfm)
  double sd_stat_error = NAN;  ///< 95% half-widths of both spreads in quadrature, same units
};

// one bar of the stability map
struct StabilityRow {
  StudyProblem problem;
  IntegratorKind integrator;
  std::string switches;
  double max_stable = 0.0;      ///< largest stable Δt/t_c found (0: none)
  double first_unstable = 0.0;  ///< first unstable Δt/t_c (0: none up to stability_max)
  std::string message;
};

/// a number as the tables write it: six significant digits, "nan" when not finite
std::string num(double v);

/// "box2d_tree" or "cell_grid"
std::string_view bp_name(BroadPhaseKind k);

/// study.csv's header line
extern const char* const kCsvHeader;
/// one line of study.csv
std::string csv_row(const StudyRow& r);
/// stability.csv
std::string stability_csv(const std::vector<StabilityRow>& rows);
/// study.json: the study, its rows and its stability map
std::string study_json(const StudySpec& s, const std::vector<StudyRow>& rows,
                       const std::vector<StabilityRow>& stab, double wall);

}  // namespace gs::study_detail
