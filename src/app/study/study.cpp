#include "app/study/study.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/run/run_info.hpp"
#include "app/study/study_problems.hpp"
#include "app/study/study_tables.hpp"
#include "app/subprocess.hpp"
#include "app/version.hpp"
#include "core/error.hpp"
#include "output/json_text.hpp"
#include "output/run_dir.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs {

namespace fs = std::filesystem;
using study_detail::bp_name;
using study_detail::csv_row;
using study_detail::kCsvHeader;
using study_detail::num;
using study_detail::stability_csv;
using study_detail::StabilityRow;
using study_detail::study_json;
using study_detail::StudyRow;

namespace {

// the switch sets that matter for a problem (others would only repeat the same run)
std::vector<StudySwitches> switch_sets(const StudySpec& s, StudyProblem p) {
  std::vector<StudySwitches> out;
  switch (p) {
    case StudyProblem::TwoDisk:
    case StudyProblem::Haff:
      for (bool c : s.clip) out.push_back({false, true, c});
      break;
    case StudyProblem::TwoDecagon:
    case StudyProblem::Pile:
      for (bool h : s.hdot_fd)
        for (bool r : s.rocking) out.push_back({h, r, false});
      break;
    case StudyProblem::GasEnergy:
      out.push_back({});
      break;
    // the statistical problems are costly: only their own switch varies, the others take the
    // matrix's first value
    case StudyProblem::Tapping:
      for (bool e : s.early_rest) out.push_back({s.hdot_fd.front(), s.rocking.front(), false, e});
      break;
    case StudyProblem::RfmTemperature:
      out.push_back({false, true, s.clip.front(), false});
      break;
  }
  return out;
}

// what the error measures, per problem
std::string_view error_kind(StudyProblem p) {
  switch (p) {
    case StudyProblem::TwoDisk:
      return "restitution_rel_error_vs_exact";
    case StudyProblem::TwoDecagon:
      return "restitution_rel_error_vs_reference";
    case StudyProblem::GasEnergy:
      return "energy_drift_per_s";
    case StudyProblem::Haff:
      return "haff_slope_rel_error_vs_enskog";
    case StudyProblem::Pile:
      return "phi_abs_error_vs_reference";
    case StudyProblem::Tapping:
      return "phi_mean_abs_error_vs_reference";
    case StudyProblem::RfmTemperature:
      return "temperature_rel_error_vs_reference";
  }
  return "";
}

// problems measured against a small-Δt Gear 6 run of the same model
bool needs_reference(StudyProblem p) {
  return p == StudyProblem::TwoDecagon || p == StudyProblem::Pile || p == StudyProblem::Tapping ||
         p == StudyProblem::RfmTemperature;
}

// problems whose value scatters from run to run: the reference's own error counts
bool statistical(StudyProblem p) {
  return p == StudyProblem::Tapping || p == StudyProblem::RfmTemperature;
}

// the switches of a problem's reference run: tapping is always compared with the
// paper-faithful protocol (full relaxations), so early rest's effect shows as an error
StudySwitches reference_switches(StudyProblem p, StudySwitches sw) {
  if (p == StudyProblem::Tapping) sw.early_rest = false;
  return sw;
}

// the reference Δt/t_c of a problem: tapping at an absolute Δt (paper check step 1e-5 s),
// rfm at its own value when given, the others at the study's
double reference_dt_over_tc(const StudySpec& s, StudyProblem p, double study_ref) {
  if (p == StudyProblem::Tapping) return s.sizes.tap_reference_dt / study_contact_time(s.sizes, p);
  if (p == StudyProblem::RfmTemperature && s.sizes.rfm_reference_dt_over_tc > 0)
    return s.sizes.rfm_reference_dt_over_tc;
  return study_ref;
}

// the Δt list of a problem: its own when its table gives one, else the matrix's
const std::vector<double>& dt_list(const StudySpec& s, StudyProblem p) {
  if (p == StudyProblem::Tapping && !s.tap_dt_over_tc.empty()) return s.tap_dt_over_tc;
  if (p == StudyProblem::RfmTemperature && !s.rfm_dt_over_tc.empty()) return s.rfm_dt_over_tc;
  return s.dt_over_tc;
}

void set_error(const StudySpec& s, StudyRow& r, const StudyOutcome& ref) {
  r.error_kind = std::string(error_kind(r.c.problem));
  const double v = r.o.value;
  switch (r.c.problem) {
    case StudyProblem::TwoDisk:
      r.reference = s.sizes.disk_eps;
      r.error = std::abs(v - r.reference) / r.reference;
      break;
    case StudyProblem::TwoDecagon:
      r.error = std::abs(v - r.reference) / r.reference;
      break;
    case StudyProblem::GasEnergy:
      r.error = v;
      break;
    case StudyProblem::Haff:
      r.reference = 1.0;
      r.error = std::abs(v - 1.0);
      break;
    case StudyProblem::Pile:
      r.error = std::abs(v - r.reference);
      break;
    case StudyProblem::Tapping:
    case StudyProblem::RfmTemperature: {
      // relative for T, absolute for φ̄; the band: both 95% half-widths in quadrature
      const double scale = r.c.problem == StudyProblem::Tapping ? 1.0 : r.reference;
      r.error = std::abs(v - r.reference) / scale;
      r.o.stat_error = std::hypot(r.o.stat_error, ref.stat_error) / scale;
      r.sd_reference = ref.sd;
      const double sd_scale = r.c.problem == StudyProblem::Tapping ? 1.0 : ref.sd;
      r.sd_error = std::abs(r.o.sd - ref.sd) / sd_scale;
      r.sd_stat_error = std::hypot(r.o.sd_stat, ref.sd_stat) / sd_scale;
      break;
    }
  }
  if (!r.o.stable) r.error = r.sd_error = NAN;
}

// run gransim.charts.study on the study directory; "" on success, else what went wrong
std::string draw_charts(const std::string& out) {
  return run_python_module("gransim.charts.study", {out});
}

// the largest stable Δt of one integrator and switch set: sweep up until blow-up
StabilityRow stability_sweep(const StudySpec& s, StudyProblem p, IntegratorKind integ,
                             const StudySwitches& sw, bool quiet) {
  StabilityRow r{p, integ, study_switches_text(p, sw), 0.0, 0.0, ""};
  for (double x = s.stability_start; x <= s.stability_max * (1 + 1e-12); x *= s.stability_factor) {
    StudyCase c{p, integ, x, BroadPhaseKind::CellGrid, sw};
    if (study_problem_walled(p)) c.broad_phase = BroadPhaseKind::Box2DTree;
    const StudyOutcome o = run_study_case(s.sizes, c);
    if (!o.stable) {
      r.first_unstable = x;
      r.message = o.note;
      break;
    }
    r.max_stable = x;
  }
  if (!quiet)
    std::fprintf(stderr, "  stability %-12s %-20s %-36s max stable dt/tc %s\n",
                 std::string(to_string(p)).c_str(), std::string(to_string(integ)).c_str(),
                 r.switches.c_str(), num(r.max_stable).c_str());
  return r;
}

}  // namespace

int study_command(const StudyOptions& opt) {
  const StudySpec s = parse_study_file(opt.file);
  const std::string out = opt.out.empty() ? "runs/study-" + s.name : opt.out;
  prepare_run_dir(out, opt.force).discard();
  const auto t0 = std::chrono::steady_clock::now();

  double dt_min = s.dt_over_tc.front();
  for (double d : s.dt_over_tc) dt_min = std::min(dt_min, d);
  const double ref_dt = s.reference_dt_over_tc > 0 ? s.reference_dt_over_tc : dt_min / 2;

  // the matrix, one row at a time; study.csv is flushed after every row
  std::ofstream csv(out + "/study.csv");
  if (!csv) throw InputError(out, "", "cannot write study.csv");
  csv << kCsvHeader << std::flush;
  std::vector<StudyRow> rows;
  std::map<std::string, StudyOutcome> refs;  // (problem, reference switches) → reference run
  for (StudyProblem p : s.problems) {
    for (const StudySwitches& sw : switch_sets(s, p)) {
      const std::string sw_text = study_switches_text(p, sw);
      StudyOutcome ref;
      ref.value = NAN;
      if (needs_reference(p)) {
        const StudySwitches rsw = reference_switches(p, sw);
        const auto key = std::string(to_string(p)) + "|" + study_switches_text(p, rsw);
        if (!refs.count(key)) {
          const double rdt = reference_dt_over_tc(s, p, ref_dt);
          const BroadPhaseKind rbp =
              study_problem_walled(p) ? s.broad_phases.front() : BroadPhaseKind::CellGrid;
          StudyOutcome o = run_study_case(s.sizes, {p, IntegratorKind::Gear6, rdt, rbp, rsw});
          if (!o.stable) o.value = NAN;
          refs[key] = o;
          if (!opt.quiet)
            std::fprintf(stderr, "study: reference %s %s (gear6, dt/tc = %s): %s%s%s\n",
                         std::string(to_string(p)).c_str(), study_switches_text(p, rsw).c_str(),
                         num(rdt).c_str(), num(o.value).c_str(), statistical(p) ? " +- " : "",
                         statistical(p) ? num(o.stat_error).c_str() : "");
        }
        ref = refs[key];
      }
      // the broad phase varies only on the pile; tapping takes the first one
      std::vector<BroadPhaseKind> bps{BroadPhaseKind::CellGrid};
      if (p == StudyProblem::Pile)
        bps = s.broad_phases;
      else if (study_problem_walled(p))
        bps = {s.broad_phases.front()};
      for (BroadPhaseKind bp : bps)
        for (IntegratorKind integ : s.integrators)
          for (double x : dt_list(s, p)) {
            StudyRow r;
            r.c = {p, integ, x, bp, sw};
            r.o = run_study_case(s.sizes, r.c);
            r.reference = ref.value;
            set_error(s, r, ref);
            csv << csv_row(r) << std::flush;
            if (!opt.quiet)
              std::fprintf(stderr, "study: %-11s %-19s dt/tc %-7s %-10s %-34s error %-10s %s\n",
                           std::string(to_string(p)).c_str(), std::string(to_string(integ)).c_str(),
                           num(x).c_str(), std::string(bp_name(bp)).c_str(), sw_text.c_str(),
                           num(r.error).c_str(), r.o.stable ? "" : "UNSTABLE");
            rows.push_back(std::move(r));
          }
    }
  }

  // the stability map
  std::vector<StabilityRow> stab;
  if (s.stability) {
    for (StudyProblem p : s.stability_problems)
      for (const StudySwitches& sw : switch_sets(s, p))
        for (IntegratorKind integ : s.integrators)
          stab.push_back(stability_sweep(s, p, integ, sw, opt.quiet));
    write_file_atomic(out + "/stability.csv", stability_csv(stab));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_file_atomic(out + "/study.json", study_json(s, rows, stab, wall));
  std::fprintf(stderr, "gransim study: %zu combinations%s in %.1f s, results in %s\n", rows.size(),
               s.stability ? " and the stability map" : "", wall, out.c_str());

  // the charts; without python the CSV and JSON stand
  const std::string err = draw_charts(out);
  if (!err.empty())
    std::fprintf(stderr, "gransim study: charts skipped: %s. study.csv and study.json are in %s\n",
                 err.c_str(), out.c_str());
  return kExitOk;
}

}  // namespace gs
