// the analysis of one RFM run directory (app/analyze/rfm_analyze.cpp fits across runs): what
// its rfm.json says and the per-run fits (velocity tail and crossover, D_f from S(k) and from the
// free paths, moments), with their CSV files in the run's analysis folder
#pragma once
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/rfm_freepath.hpp"
#include "analysis/rfm_sk.hpp"
#include "analysis/rfm_tails.hpp"
#include "core/numbers.hpp"

namespace gs::rfm_detail {

// one RFM run directory and what its rfm.json says
struct RfmRun {
  std::filesystem::path dir;
  std::string label;  // unique name of its analysis folder
  std::map<std::string, double> info;
  double get(const std::string& k) const {
    auto it = info.find(k);
    return it == info.end() ? kNaN : it->second;
  }
};

// what one run's analysis found, for the summary and the exponent fits
struct RunResult {
  const RfmRun* run = nullptr;
  std::optional<rfm::TailFit> tail, tail_post;
  std::optional<rfm::CrossoverFit> cross;
  std::optional<rfm::DfFit> df;
  std::optional<rfm::FreePathFit> paths;
  std::vector<double> v_moments, v_errors, r_moments, r_errors;
  std::vector<std::string> notes;
};

/// rfm.json of a run directory: every number field; InputError when it is not an RFM file
RfmRun read_run(const std::filesystem::path& dir);

/// the runs in a directory: itself, or its subdirectories with rfm.json (sorted by name)
std::vector<std::filesystem::path> run_dirs(const std::filesystem::path& d);

/// every per-run fit of `r`, its CSV files written into `out`
RunResult analyze_run(const RfmRun& r, const std::filesystem::path& out);

}  // namespace gs::rfm_detail
