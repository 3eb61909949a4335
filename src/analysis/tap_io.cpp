// the tapping analysis' files: reading taps.csv, writing the CSV and JSON results
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "analysis/tap_analysis.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace gs {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\"");
  return s.substr(b, e - b + 1);
}

// cells of a line; sep ' ' splits at runs of blanks (numpy.savetxt's default)
std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  if (sep == ' ') {
    while (ss >> cell) out.push_back(trim(cell));
    return out;
  }
  while (std::getline(ss, cell, sep)) out.push_back(trim(cell));
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// the header's separator: a comma, else a semicolon or a tab (spreadsheets in locales whose
// decimal mark is a comma), else blanks
char detect_separator(const std::string& header) {
  for (char c : {',', ';', '\t'})
    if (header.find(c) != std::string::npos) return c;
  return trim(header).find(' ') != std::string::npos ? ' ' : ',';
}

std::string separator_name(char sep) {
  return sep == ',' ? "','" : sep == ';' ? "';'" : sep == '\t' ? "a tab" : "blanks";
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// a cell as a number; with ';' or tab separators a decimal comma is read as a point
bool parse_number(std::string cell, char sep, double& v) {
  if (sep != ',' && cell.find(',') != std::string::npos && cell.find('.') == std::string::npos)
    for (char& c : cell)
      if (c == ',') c = '.';
  char* end = nullptr;
  v = std::strtod(cell.c_str(), &end);
  return !cell.empty() && end == cell.c_str() + cell.size();
}

// a number for CSV: shortest round-trip form; NaN and infinities as text
std::string num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// a number for JSON: null where JSON has no number (no measurement); a whole value as an
// integer, as the readers have always seen it (a control value 6, not 6.0)
nlohmann::ordered_json jnum(double v) {
  if (!std::isfinite(v)) return nullptr;
  if (v == std::trunc(v) && std::abs(v) < 9007199254740992.0) return static_cast<std::int64_t>(v);
  return v;
}

nlohmann::ordered_json jarr(const std::vector<double>& v) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (double x : v) a.push_back(jnum(x));
  return a;
}

// a JSON document's text: two-space indents; a label that is not UTF-8 is written with U+FFFD
std::string json_document(const nlohmann::ordered_json& j) {
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

// an output file built in memory and written whole by close() (write_file_atomic): a full disk
// is an OutputError naming it and leaves no partial file; never closed, it is never written
class OutFile {
 public:
  explicit OutFile(std::filesystem::path p) : path_(std::move(p)) {}
  template <class T>
  OutFile& operator<<(const T& v) {
    text_ << v;
    return *this;
  }
  void close() { write_file_atomic(path_.string(), text_.str()); }

 private:
  std::filesystem::path path_;
  std::ostringstream text_;
};

// one quadron fit as a JSON object, with the curve φ̄(β), σ_φ(β), Δln Z(β) over the data range
nlohmann::ordered_json quadron_json(const QuadronFit& f, const TapAnalysisResult& r,
                                    const TapAnalysisOptions& opts) {
  nlohmann::ordered_json o;
  o["converged"] = f.converged;
  o["note"] = f.note;
  o["points"] = f.points;
  o["iterations"] = f.iterations;
  o["a"] = jnum(f.a);
  o["a_err"] = jnum(f.a_err);
  o["beta0"] = jnum(f.beta0);
  o["beta0_err"] = jnum(f.beta0_err);
  o["cov_a_beta0"] = jnum(f.cov_a_beta0);
  o["chi2"] = jnum(f.chi2);
  o["dof"] = f.dof;
  o["errors_scaled"] = f.errors_scaled;
  if (f.converged && f.a > 0.0) {
    // the curve over the measured β̂ range, widened by a quarter on each side
    double lo = 0.0, hi = 0.0;
    for (const auto& b : r.beta)
      if (b.valid) lo = std::min(lo, b.dbeta), hi = std::max(hi, b.dbeta);
    const double pad = 0.25 * std::max(hi - lo, 1e-12);
    std::vector<double> bh, ph, sg, lz;
    const double lz0 = quadron_lnz(f.beta0, f.a, r.v_g, opts.quadron);
    for (int i = 0; i <= 200; ++i) {
      const double b = lo - pad + (hi - lo + 2.0 * pad) * i / 200.0;
      bh.push_back(b);
      ph.push_back(quadron_phi(b + f.beta0, f.a, opts.quadron));
      sg.push_back(quadron_sigma_phi(b + f.beta0, f.a, r.v_g, opts.quadron));
      lz.push_back(quadron_lnz(b + f.beta0, f.a, r.v_g, opts.quadron) - lz0);
    }
    o["curve"] = {
        {"beta_hat", jarr(bh)}, {"phi", jarr(ph)}, {"sigma_phi", jarr(sg)}, {"dlnz", jarr(lz)}};
  }
  return o;
}

}  // namespace

TapSeries parse_taps_csv(std::istream& in, const std::string& source) {
  TapSeries s;
  s.source = source;
  std::string line;
  int lineno = 0;
  std::vector<std::string> header;
  char sep = ',';
  bool headerless = false;  // a single column of numbers: φ, one row per tap
  // the header: the first line that is neither blank nor a comment
  while (std::getline(in, line)) {
    ++lineno;
    // a UTF-8 byte-order mark (spreadsheets write one) is not part of the first column's name
    if (lineno == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    sep = detect_separator(line);
    header = split(line, sep);
    break;
  }
  if (header.empty()) throw InputError(source, "", "no header row (is the file empty?)");
  const int header_line = lineno;
  {
    double v = 0.0;
    if (header.size() == 1 && parse_number(header[0], sep, v)) {
      headerless = true;
      header = {"phi"};
    }
  }
  // columns by name, in any case ("Phi", "TAP")
  auto column = [&](const std::string& name, bool required) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (lower(header[i]) == name) return static_cast<int>(i);
    if (required) {
      std::string found;
      for (const auto& h : header) found += (found.empty() ? "'" : ", '") + h + "'";
      throw InputError(source + ":" + std::to_string(header_line), name,
                       "missing column '" + name + "' (any case); the header has " +
                           std::to_string(header.size()) + " column" +
                           (header.size() == 1 ? "" : "s") + " separated by " +
                           separator_name(sep) + ": " + found);
    }
    return -1;
  };
  const int c_tap = column("tap", false);  // absent: the rows are taps 1, 2, …
  const int c_phi = column("phi", true);
  const int c_t = column("t", false);
  const int c_left = column("phi_left", false);
  const int c_right = column("phi_right", false);

  // one row per tap; every used column must hold a number
  auto row = [&](const std::vector<std::string>& cells) {
    auto value = [&](int c) {
      const std::string where = source + ":" + std::to_string(lineno);
      if (c >= static_cast<int>(cells.size()))
        throw InputError(where, header[c],
                         "row has no value for column '" + header[c] + "' (" +
                             std::to_string(cells.size()) + " cells separated by " +
                             separator_name(sep) + ")");
      const std::string& cell = cells[c];
      double v = 0.0;
      const std::string col = "column " + std::to_string(c + 1) + " ('" + header[c] + "')";
      if (!parse_number(cell, sep, v))
        throw InputError(where, header[c], col + ": not a number: '" + cell + "'");
      // NaN or inf would reach the statistics (a KDE of NaN) and fail far from the file
      if (!std::isfinite(v))
        throw InputError(where, header[c], col + ": not finite: '" + cell + "'");
      return v;
    };
    const double tap = c_tap >= 0 ? value(c_tap) : static_cast<double>(s.tap.size() + 1);
    // a tap is a count: whole, not negative, and small enough to be counted exactly
    if (!(tap >= 0.0 && tap <= 1e15 && tap == std::floor(tap)))
      throw InputError(source + ":" + std::to_string(lineno), "tap",
                       "column 'tap': not a tap number (a whole number from 0 to 10^15): '" +
                           cells[static_cast<std::size_t>(c_tap)] + "'");
    // taps count up: a repeated or reversed tap number is two files mixed, or a file edited
    if (!s.tap.empty() && !(tap > s.tap.back()))
      throw InputError(source + ":" + std::to_string(lineno), "tap",
                       "tap numbers must increase (tap " + cells[static_cast<std::size_t>(c_tap)] +
                           " follows tap " + std::to_string(static_cast<long long>(s.tap.back())) +
                           ")");
    s.tap.push_back(tap);
    s.phi.push_back(value(c_phi));
    if (c_t >= 0) s.t.push_back(value(c_t));
    if (c_left >= 0) s.phi_left.push_back(value(c_left));
    if (c_right >= 0) s.phi_right.push_back(value(c_right));
  };
  if (headerless) row(split(line, sep));
  while (std::getline(in, line)) {
    ++lineno;
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    row(split(line, sep));
  }
  return s;
}

TapSeries read_taps_csv(const std::string& path) {
  check_input_file(path, "taps file");
  std::ifstream f(path);
  if (!f) throw InputError(path, "", "cannot open taps file for reading");
  return parse_taps_csv(f, path);
}

TapRunInput load_tap_run(const std::string& path, const std::string& protocol, double control,
                         const std::string& label) {
  TapRunInput r;
  r.label = label;
  r.protocol = protocol;
  r.control = control;
  r.series = read_taps_csv(path);
  return r;
}

void write_tap_analysis(const TapAnalysisResult& r, const std::vector<TapRunInput>& runs,
                        const TapAnalysisOptions& opts, const std::string& out_dir) {
  namespace fs = std::filesystem;
  const fs::path dir(out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(out_dir, "", "cannot create the output folder: " + ec.message());
  const auto& ref = r.runs[r.ref];

  // pairs.csv: two-sample tests of runs at the same protocol and control value
  if (!r.pairs.empty()) {
    OutFile f(dir / "pairs.csv");
    f << "label_a,label_b,protocol,control,n_eff_a,n_eff_b,mean_diff,mean_diff_err,p_mean,"
         "sigma_ratio,p_sigma,ks_d,ks_p\n";
    for (const TapPairTest& p : r.pairs) {
      const auto &a = r.runs[static_cast<std::size_t>(p.a)],
                 &b = r.runs[static_cast<std::size_t>(p.b)];
      const TwoSampleTest& t = p.test;
      f << a.label << ',' << b.label << ',' << a.protocol << ',' << num(a.control) << ','
        << num(t.n_eff_a) << ',' << num(t.n_eff_b) << ',' << num(t.mean_diff) << ','
        << num(t.mean_diff_err) << ',' << num(t.p_mean) << ',' << num(t.sigma_ratio) << ','
        << num(t.p_sigma) << ',' << num(t.ks_d) << ',' << num(t.ks_p) << '\n';
    }
    f.close();
  }

  // summary.csv: one row per run
  {
    OutFile f(dir / "summary.csv");
    f << "label,protocol,control,n_total,n_used,phi_mean,phi_err,phi_mean_lo,phi_mean_hi,"
         "phi_mean_lo_tau,phi_mean_hi_tau,sigma,sigma_lo,sigma_hi,sigma_lo_tau,sigma_hi_tau,"
         "tau_int,tau_err,tau_window,chi2,chi2_bins,chi2_dof,chi2_p,normal,mean_left,"
         "mean_right,sigma_left,sigma_right,ratio_left,ratio_right,discard,steady\n";
    for (const auto& s : r.runs) {
      const double nan = std::nan("");
      f << s.label << ',' << s.protocol << ',' << num(s.control) << ',' << s.n_total << ','
        << s.n_used << ',' << num(s.phi_mean) << ',' << num(s.phi_err) << ','
        << num(s.phi_mean_ci.lo) << ',' << num(s.phi_mean_ci.hi) << ',' << num(s.phi_mean_ci_tau.lo)
        << ',' << num(s.phi_mean_ci_tau.hi) << ',' << num(s.sigma) << ',' << num(s.sigma_ci.lo)
        << ',' << num(s.sigma_ci.hi) << ',' << num(s.sigma_ci_tau.lo) << ','
        << num(s.sigma_ci_tau.hi) << ',' << num(s.tau.tau_int) << ',' << num(s.tau.tau_err) << ','
        << s.tau.window << ',' << num(s.normality.statistic) << ',' << s.normality.bins << ','
        << s.normality.dof << ',' << num(s.normality.p_value) << ',' << (s.normality.normal ? 1 : 0)
        << ',' << num(s.has_halves ? s.mean_left : nan) << ','
        << num(s.has_halves ? s.mean_right : nan) << ',' << num(s.has_halves ? s.sigma_left : nan)
        << ',' << num(s.has_halves ? s.sigma_right : nan) << ','
        << num(s.has_halves ? s.sigma_left / s.sigma : nan) << ','
        << num(s.has_halves ? s.sigma_right / s.sigma : nan) << ',' << s.discard << ','
        << (s.steady ? 1 : 0) << '\n';
    }
    f.close();
  }

  // series.csv: the time series (Fig. 4), with the transient marked
  {
    OutFile f(dir / "series.csv");
    f << "label,protocol,control,tap,phi,used\n";
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const auto& s = runs[i].series;
      for (std::size_t k = 0; k < s.phi.size(); ++k)
        f << r.runs[i].label << ',' << r.runs[i].protocol << ',' << num(r.runs[i].control) << ','
          << num(k < s.tap.size() ? s.tap[k] : static_cast<double>(k)) << ',' << num(s.phi[k])
          << ',' << (static_cast<int>(k) >= r.runs[i].discard ? 1 : 0) << '\n';
    }
    f.close();
  }

  // kde.csv: the three kernels on each run's grid (Figs 7a, 8a, 13)
  {
    OutFile f(dir / "kde.csv");
    f << "label,protocol,control,bandwidth,phi,p_normal,p_epanechnikov,p_box\n";
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      const auto& c = r.kde_normal[i];
      for (std::size_t k = 0; k < c.x.size(); ++k)
        f << r.runs[i].label << ',' << r.runs[i].protocol << ',' << num(r.runs[i].control) << ','
          << num(c.bandwidth) << ',' << num(c.x[k]) << ',' << num(c.density[k]) << ','
          << num(r.kde_epanechnikov[i][k]) << ',' << num(r.kde_box[i][k]) << '\n';
    }
    f.close();
  }

  // q_lines.csv and beta.csv, for each reference (Figs 7b–c, 8b–c, 9, 10); none without β̂
  const bool has_beta = r.beta.size() == r.runs.size();
  auto* all = r.quadron.count("all") ? &r.quadron.at("all") : nullptr;
  const bool fit_ok = all && all->converged;
  if (has_beta) {
    OutFile fq(dir / "q_lines.csv");
    OutFile fb(dir / "beta.csv");
    fq << "reference,label,protocol,control,inv_phi,q,q_err,q_line\n";
    fb << "reference,label,protocol,control,phi_mean,phi_err,sigma,sigma_lo_tau,sigma_hi_tau,"
          "dbeta,dbeta_err,dlnz,dlnz_err,cov,r2,quad,quad_err,chi2,dof,points,valid,beta,"
          "phi_quadron,sigma_quadron,dlnz_quadron\n";
    auto write = [&](int refi, const std::vector<BetaEstimate>& betas) {
      const std::string& rl = r.runs[refi].label;
      const bool primary = refi == r.ref;
      for (std::size_t i = 0; i < betas.size(); ++i) {
        const auto& b = betas[i];
        const auto& s = r.runs[i];
        for (const auto& p : b.fit.points)
          fq << rl << ',' << s.label << ',' << s.protocol << ',' << num(s.control) << ','
             << num(p.x) << ',' << num(p.q) << ',' << num(p.q_err) << ','
             << num(b.valid ? b.fit.intercept + b.fit.slope * p.x : std::nan("")) << '\n';
        // the quadron values (fit over all runs) only against the primary reference
        double beta = std::nan(""), phq = beta, sgq = beta, lzq = beta;
        if (primary && fit_ok && b.valid) {
          beta = b.dbeta + all->beta0;
          phq = quadron_phi(beta, all->a, opts.quadron);
          sgq = quadron_sigma_phi(beta, all->a, r.v_g, opts.quadron);
          lzq = quadron_lnz(beta, all->a, r.v_g, opts.quadron) -
                quadron_lnz(all->beta0, all->a, r.v_g, opts.quadron);
        }
        fb << rl << ',' << s.label << ',' << s.protocol << ',' << num(s.control) << ','
           << num(s.phi_mean) << ',' << num(s.phi_err) << ',' << num(s.sigma) << ','
           << num(s.sigma_ci_tau.lo) << ',' << num(s.sigma_ci_tau.hi) << ',' << num(b.dbeta) << ','
           << num(b.dbeta_err) << ',' << num(b.dlnz) << ',' << num(b.dlnz_err) << ',' << num(b.cov)
           << ',' << num(b.fit.r2) << ',' << num(b.fit.quad) << ',' << num(b.fit.quad_err) << ','
           << num(b.fit.chi2) << ',' << b.fit.dof << ',' << b.fit.points.size() << ','
           << (b.valid ? 1 : 0) << ',' << num(beta) << ',' << num(phq) << ',' << num(sgq) << ','
           << num(lzq) << '\n';
      }
    };
    write(r.ref, r.beta);
    if (r.ref2 >= 0) write(r.ref2, r.beta2);
    fq.close();
    fb.close();
  }

  // beta_multi.csv: β̂ and ln Z directly against the reference, through the chain of
  // neighbours and from the joint multiple-histogram fit, side by side
  if (!r.multi.chain.empty()) {
    OutFile f(dir / "beta_multi.csv");
    f << "label,protocol,control,phi_mean,phi_err,direct_valid,direct_dbeta,direct_dbeta_err,"
         "direct_dlnz,direct_dlnz_err,chain_valid,chain_dbeta,chain_dbeta_err,chain_dlnz,"
         "chain_dlnz_err,joint_valid,joint_dbeta,joint_dbeta_err,joint_dlnz,joint_dlnz_err\n";
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      const auto& s = r.runs[i];
      const auto& d = r.beta[i];
      const auto& c = r.multi.chain[i];
      const auto& j = r.multi.joint[i];
      f << s.label << ',' << s.protocol << ',' << num(s.control) << ',' << num(s.phi_mean) << ','
        << num(s.phi_err) << ',' << (d.valid ? 1 : 0) << ',' << num(d.dbeta) << ','
        << num(d.dbeta_err) << ',' << num(d.dlnz) << ',' << num(d.dlnz_err) << ','
        << (c.valid ? 1 : 0) << ',' << num(c.dbeta) << ',' << num(c.dbeta_err) << ',' << num(c.dlnz)
        << ',' << num(c.dlnz_err) << ',' << (j.valid ? 1 : 0) << ',' << num(j.dbeta) << ','
        << num(j.dbeta_err) << ',' << num(j.dlnz) << ',' << num(j.dlnz_err) << '\n';
    }
    f.close();
  }

  // beta_cov.csv: the bootstrap covariance of the β̂ across runs, a square matrix whose rows and
  // columns are named joint:<label> (joint fit) and direct:<reference>:<label> (direct β̂)
  if (!r.multi.cov.empty()) {
    OutFile f(dir / "beta_cov.csv");
    const std::size_t K = r.runs.size();
    std::vector<std::string> names;
    for (std::size_t q = 0; q < r.multi.cov.size(); ++q) {
      const std::size_t b = q / K;
      const int refb = b == 0 ? -1 : (b == 1 ? r.ref : r.ref2);
      names.push_back((b == 0 ? std::string("joint:") : "direct:" + r.runs[refb].label + ":") +
                      r.runs[q % K].label);
    }
    f << "quantity";
    for (const auto& n : names) f << ',' << n;
    f << '\n';
    for (std::size_t a = 0; a < names.size(); ++a) {
      f << names[a];
      for (double c : r.multi.cov[a]) f << ',' << num(c);
      f << '\n';
    }
    f.close();
  }

  // quadron.json: the fits with their curves
  if (has_beta) {
    nlohmann::ordered_json j;
    j["phi_rlp"] = jnum(opts.quadron.phi_rlp);
    j["phi_rcp"] = jnum(opts.quadron.phi_rcp);
    j["v_g"] = jnum(r.v_g);
    j["reference"] = ref.label;
    j["fits"] = nlohmann::ordered_json::object();
    for (const auto& [name, fit] : r.quadron) j["fits"][name] = quadron_json(fit, r, opts);
    write_file_atomic((dir / "quadron.json").string(), json_document(j));
  }

  // analysis.json: options, references, per-run digest, the two-reference check, notes
  {
    const double nan = std::nan("");
    nlohmann::ordered_json j;
    j["discard"] = opts.discard;
    j["discard_auto"] = opts.discard_auto;
    j["level"] = jnum(opts.level);
    j["alpha"] = jnum(opts.alpha);
    j["test_area"] = jnum(has_beta ? opts.test_area : nan);
    j["v_g"] = jnum(has_beta ? r.v_g : nan);
    j["density_method"] = opts.overlap.method == DensityMethod::Histogram ? "histogram" : "kde";
    j["kernel"] = kernel_name(opts.overlap.kernel);
    j["min_fraction"] = jnum(opts.overlap.min_fraction);
    j["reference"] = ref.label;
    j["reference2"] = r.ref2 >= 0 ? nlohmann::ordered_json(r.runs[r.ref2].label) : nullptr;
    j["bootstrap_replicas"] = r.multi.replicas;
    j["reference_offset"] = {{"dbeta", jnum(r.ref_offset)},
                             {"err", jnum(r.ref_offset_err)},
                             {"chi2", jnum(r.ref_offset_chi2)},
                             {"dof", r.ref_offset_dof}};
    j["runs"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < r.runs.size(); ++i) {
      const auto& s = r.runs[i];
      const bool beta_ok = has_beta && r.beta[i].valid;
      const nlohmann::ordered_json run = {
          {"label", s.label},
          {"protocol", s.protocol},
          {"control", jnum(s.control)},
          {"n_used", s.n_used},
          {"discard", s.discard},
          {"steady", s.steady},
          {"phi_mean", jnum(s.phi_mean)},
          {"sigma", jnum(s.sigma)},
          {"tau_int", jnum(s.tau.tau_int)},
          {"normal", s.normality.normal},
          {"chi2_p", jnum(s.normality.p_value)},
          {"sigma_ratio_halves",
           jnum(s.has_halves ? 0.5 * (s.sigma_left + s.sigma_right) / s.sigma : nan)},
          {"dbeta", jnum(beta_ok ? r.beta[i].dbeta : nan)},
          {"dbeta_err", jnum(beta_ok ? r.beta[i].dbeta_err : nan)}};
      j["runs"].push_back(run);
    }
    std::vector<std::string> files = {"summary.csv", "series.csv", "kde.csv"};
    if (!r.pairs.empty()) files.push_back("pairs.csv");
    if (has_beta) files.insert(files.end(), {"q_lines.csv", "beta.csv", "quadron.json"});
    if (!r.multi.chain.empty()) files.push_back("beta_multi.csv");
    if (!r.multi.cov.empty()) files.push_back("beta_cov.csv");
    j["files"] = files;
    j["notes"] = r.notes;
    write_file_atomic((dir / "analysis.json").string(), json_document(j));
  }
}

}  // namespace gs
