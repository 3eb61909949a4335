// the analysis of one RFM run: the velocity histogram (tail scan, crossover), the structure
// (S(k), free paths) and the 1D gaps, each fit with its CSV in the run's analysis folder
#include "app/analyze/rfm_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/rfm_blocks.hpp"
#include "analysis/rfm_csv.hpp"
#include "analysis/rfm_moments.hpp"
#include "app/run/run_info.hpp"
#include "core/error.hpp"
#include "measure/rfm_io.hpp"
#include "models/bisection.hpp"
#include "output/csv.hpp"
#include "output/json_text.hpp"

namespace gs::rfm_detail {

namespace fs = std::filesystem;

namespace {

// a CSV is written anew in the current form (metadata in its sidecar), whichever form it had
void copy_if_there(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  if (!fs::exists(from, ec)) return;
  if (from.extension() != ".csv") {
    fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    return;
  }
  const rfm::CsvTable t = rfm::read_csv(from);
  CsvWriter w(to.string(), t.names, RecordMeta(t.meta.begin(), t.meta.end()));
  const std::size_t rows = t.names.empty() ? 0 : t.column.at(t.names.front()).size();
  std::vector<double> row(t.names.size());
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < t.names.size(); ++c) row[c] = t.column.at(t.names[c])[i];
    w.row(row);
  }
}

// T(t) in 50-ms blocks: the transient's means, and whole blocks of every longer period a
// report averages over (the first second, halves of the run, the ring's 20-s periods)
constexpr double kTemperatureBlock = 0.05;  // s

// temperature_blocks.csv from every sample (rfm_series.csv: the transient too), or from the
// steady ones (temperature.csv) where the run has no series
void write_temperature_blocks(const RfmRun& r, const fs::path& out, RunResult& res) {
  std::error_code ec;
  const bool series = fs::exists(r.dir / "rfm_series.csv", ec);
  if (!series && !fs::exists(r.dir / "temperature.csv", ec)) return;
  try {
    const rfm::CsvTable c = rfm::read_csv(r.dir / (series ? "rfm_series.csv" : "temperature.csv"));
    const std::vector<double>& t = c.col("t");
    const std::vector<double>& temp = c.col("T");
    const std::vector<double> none;
    const std::vector<double>& steady = series ? c.col("steady") : none;
    std::vector<double> st, sv;
    for (std::size_t i = 0; i < temp.size(); ++i)
      if (steady.empty() || steady[i] != 0.0) {
        st.push_back(t[i]);
        sv.push_back(temp[i]);
      }
    rfm::write_temperature_blocks_csv(csv_records(), out / "temperature_blocks.csv",
                                      rfm::time_blocks(t, temp, steady, kTemperatureBlock),
                                      kTemperatureBlock, r.get("dt") * r.get("sample_every"), st,
                                      sv);
  } catch (const InputError& e) {
    res.notes.push_back(std::string("temperature blocks skipped: ") + e.what());
  }
}

// a moments.csv (m, moment, error) as two vectors
void read_moments(const fs::path& p, std::vector<double>& m, std::vector<double>& e) {
  std::error_code ec;
  if (!fs::exists(p, ec)) return;
  const rfm::CsvTable t = rfm::read_csv(p);
  m = t.col("moment");
  e = t.col("error");
}

// P(v) at v = 0: the bin holding 0, or the mean of the two bins meeting there
double density_at_zero(const rfm::Histogram& h) {
  const auto bins = h.bins();
  for (std::size_t i = 0; i < bins.size(); ++i) {
    if (bins[i].lo < 0.0 && bins[i].hi > 0.0) return bins[i].p;
    if (bins[i].lo == 0.0 && i > 0) return 0.5 * (bins[i].p + bins[i - 1].p);
  }
  return kNaN;
}

// the velocity histogram: tail scan, crossover, ln–ln views (appendix A, §5.3)
void analyze_velocities(const fs::path& in, const fs::path& out, RunResult& res) {
  const rfm::Histogram h = rfm::read_histogram_raw(in / "hist_velocity.csv");
  try {
    res.tail = rfm::fit_tail(h);  // counts 50…5000, accept α while χ²_r < 1.2
  } catch (const InputError& e) {
    res.notes.push_back(std::string("velocity tail fit skipped: ") + e.what());
  }
  // T.5.32 with α free; α = 1 (the thesis' asymptote) when the free fit does not converge
  try {
    rfm::CrossoverFit c = rfm::fit_crossover(h, 1.0, true);
    if (!std::isfinite(c.alpha) || c.alpha <= 0.0 || c.alpha >= 2.0)
      c = rfm::fit_crossover(h, 1.0, false);
    res.cross = c;
  } catch (const std::exception& e) {
    res.notes.push_back(std::string("crossover fit skipped: ") + e.what());
  }
  rfm::write_velocity_csv(csv_records(), out / "velocity.csv", h, res.tail ? &*res.tail : nullptr,
                          res.cross ? &*res.cross : nullptr);
  if (res.tail) rfm::write_tail_scan_csv(csv_records(), out / "tail_scan.csv", *res.tail);
  // ln–ln tail plots with the asymptotic amplitude A₀ and with P(0) (§5.3.3)
  double c2 = 0.0, cn = 0.0;
  for (const auto& b : h.bins()) {
    c2 += b.count * b.x * b.x;
    cn += b.count;
  }
  const double vrms = cn > 0 ? std::sqrt(c2 / cn) : kNaN;
  if (res.tail && vrms > 0) {
    const double a0 = res.tail->best.a;
    rfm::write_lnln_csv(csv_records(), out / "lnln_A0.csv", rfm::lnln_tail(h, a0, vrms, 50.0), a0,
                        vrms);
    const double p0 = density_at_zero(h);
    rfm::write_lnln_csv(csv_records(), out / "lnln_P0.csv", rfm::lnln_tail(h, p0, vrms, 50.0), p0,
                        vrms);
  }
  // velocities just after collisions: the same tail scan
  std::error_code ec;
  if (fs::exists(in / "hist_postcollision.csv", ec)) {
    const rfm::Histogram hp = rfm::read_histogram_raw(in / "hist_postcollision.csv");
    try {
      res.tail_post = rfm::fit_tail(hp);
    } catch (const InputError&) {
    }
    rfm::write_velocity_csv(csv_records(), out / "velocity_post.csv", hp,
                            res.tail_post ? &*res.tail_post : nullptr);
  }
}

// 2D structure: D_f from S(k) below k′ (T.4.5–4.9) and free paths (T.4.25)
void analyze_structure(const RfmRun& r, const fs::path& out, RunResult& res) {
  std::error_code ec;
  if (fs::exists(r.dir / "sk.csv", ec)) {
    const rfm::CsvTable t = rfm::read_csv(r.dir / "sk.csv");
    std::vector<rfm::SkShell> shells;
    const auto& k = t.col("k");
    for (std::size_t i = 0; i < k.size(); ++i) {
      rfm::SkShell s;
      s.k = k[i];
      s.n = t.col("n")[i];
      s.s = t.col("S")[i];
      s.s_err = t.col("S_err")[i];
      s.modes = static_cast<long>(t.col("modes")[i]);
      shells.push_back(s);
    }
    rfm::RfmSystem sys;
    sys.box = r.get("box");
    sys.n = static_cast<long>(r.get("particles"));
    sys.diameter = r.get("diameter");
    sys.eps_n = r.get("eps_n");
    sys.eps_t = r.get("eps_t");
    try {
      res.df = rfm::fit_df_rfm(shells, sys);
    } catch (const InputError& e) {
      res.notes.push_back(std::string("D_f fit skipped: ") + e.what());
    }
    rfm::write_sk_csv(csv_records(), out / "sk.csv", shells, res.df ? &*res.df : nullptr);
  }
}

void analyze_free_paths(const RfmRun& r, const fs::path& out, RunResult& res) {
  std::error_code ec;
  if (!fs::exists(r.dir / "hist_freepath.csv", ec)) return;
  const rfm::Histogram h = rfm::read_histogram_raw(r.dir / "hist_freepath.csv");
  // T.4.25 describes the long flights of fast disks through a static fractal background, so the
  // thesis fits the tail only, "the lowest decades of data ... where P < 1" (§4.3.3, P_l in
  // 1/m); below it the body holds re-contacts of disks pressed together (docs/rfm.md)
  const double start = rfm::tail_start(h, 1.0);
  if (!std::isfinite(start)) {
    res.notes.push_back("free-path fit skipped: P_l never falls below 1/m (no tail to fit)");
  } else {
    try {
      res.paths = rfm::fit_free_paths(h, start, 10.0);
    } catch (const std::exception& e) {
      res.notes.push_back(std::string("free-path fit skipped: ") + e.what());
    }
  }
  rfm::write_freepath_csv(csv_records(), out / "freepath.csv", h,
                          res.paths ? &*res.paths : nullptr);
}

// 1D: G₁(R) against the bisection density of n = round(log₂ N) levels (thesis Fig. 3.16) and
// the gaps of N uniform points, (N−1)(1−R)^(N−2) (R in units of L′)
void write_gh_bisection(const RfmRun& r, const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(r.dir / "gh.csv", ec)) return;
  const rfm::CsvTable t = rfm::read_csv(r.dir / "gh.csv");
  const double n = r.get("particles");
  const int levels = std::max(1, static_cast<int>(std::lround(std::log2(n))));
  CsvWriter w((out / "gh_bisection.csv").string(),
              {"R", "G1", "G1_err", "P_bisection", "P_uniform"},
              {{"levels", static_cast<double>(levels)}, {"N", n}});
  const auto& R = t.col("R");
  for (std::size_t i = 0; i < R.size(); ++i)
    w.row({R[i], t.col("G1")[i], t.col("G1_err")[i], models::bisection_density(R[i], levels),
           R[i] < 1.0 ? (n - 1.0) * std::pow(1.0 - R[i], n - 2.0) : 0.0});
}

}  // namespace

// every number field of rfm.json (written by RfmObserver); null reads as NaN
RfmRun read_run(const fs::path& dir) {
  RfmRun r;
  r.dir = dir;
  const std::string path = (dir / "rfm.json").string();
  const auto text = read_text_file(path);
  if (!text) throw InputError(path, "", "cannot be read");
  const nlohmann::json j = parse_json_lenient(*text);
  if (j.is_object())
    for (const auto& [k, v] : j.items()) {
      if (v.is_number()) r.info[k] = v.get<double>();
      if (v.is_null()) r.info[k] = kNaN;
    }
  if (!r.info.count("dimension") || !r.info.count("particles"))
    throw InputError(path, "dimension", "not an RFM observer file");
  return r;
}

// the runs in a directory: itself, or its subdirectories with rfm.json (sorted by name)
std::vector<fs::path> run_dirs(const fs::path& d) {
  std::error_code ec;
  if (fs::exists(d / "rfm.json", ec)) return {d};
  std::vector<fs::path> out;
  if (fs::is_directory(d, ec))
    for (const auto& e : fs::directory_iterator(d, ec))
      if (e.is_directory() && fs::exists(e.path() / "rfm.json")) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

RunResult analyze_run(const RfmRun& r, const fs::path& out) {
  RunResult res;
  res.run = &r;
  fs::create_directories(out);
  for (const char* f : {"temperature.csv", "moments.csv", "moments_components.csv", "gr.csv",
                        "gh.csv", "gap_moments.csv", "rfm.json"})
    copy_if_there(r.dir / f, out / f);
  write_temperature_blocks(r, out, res);
  read_moments(r.dir / "moments.csv", res.v_moments, res.v_errors);
  read_moments(r.dir / "gap_moments.csv", res.r_moments, res.r_errors);
  std::error_code ec;
  if (fs::exists(r.dir / "hist_velocity.csv", ec)) analyze_velocities(r.dir, out, res);
  if (r.get("dimension") == 2.0) analyze_structure(r, out, res);
  analyze_free_paths(r, out, res);
  if (r.get("dimension") == 1.0) write_gh_bisection(r, out);
  return res;
}

}  // namespace gs::rfm_detail
