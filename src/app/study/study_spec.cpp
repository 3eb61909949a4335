// parsing of study files: every key checked, every error an InputError at file:line and key
#include <algorithm>
#include <fstream>
#include <sstream>

#include "app/study/study.hpp"
#include "scene/reader.hpp"

namespace gs {

using scene_detail::Ctx;
using scene_detail::Range;
using scene_detail::TableReader;

namespace {

// the problem names as written in study files
constexpr std::pair<std::string_view, StudyProblem> kProblems[] = {
    {"two_disk", StudyProblem::TwoDisk},
    {"two_decagon", StudyProblem::TwoDecagon},
    {"gas_energy", StudyProblem::GasEnergy},
    {"haff", StudyProblem::Haff},
    {"pile", StudyProblem::Pile},
    {"tapping", StudyProblem::Tapping},
    {"rfm_temperature", StudyProblem::RfmTemperature}};

// the array at key k (nullptr when absent); any other type fails at the key
const toml::array* array_at(const TableReader& r, std::string_view k) {
  const toml::node* n = r.get(k);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  if (!a) r.fail(k, "must be an array (got " + std::string(scene_detail::type_name(*n)) + ")");
  if (a->empty()) r.fail(k, "must not be empty");
  return a;
}

// an array of strings mapped through `lookup`; unknown words fail with the allowed list
template <class T, class F>
std::vector<T> word_list(const TableReader& r, std::string_view k, std::vector<T> def,
                         const std::string& allowed, F lookup) {
  const toml::array* a = array_at(r, k);
  if (!a) return def;
  std::vector<T> out;
  for (const auto& e : *a) {
    const auto s = e.value<std::string>();
    if (!s) r.fail(k, "must hold strings, one of " + allowed);
    std::optional<T> v = lookup(*s);
    if (!v) r.fail(k, "unknown value " + scene_detail::quote(*s) + "; one of " + allowed);
    if (std::find(out.begin(), out.end(), *v) == out.end()) out.push_back(*v);
  }
  return out;
}

std::optional<StudyProblem> problem_named(const std::string& s) {
  for (const auto& [n, p] : kProblems)
    if (n == s) return p;
  return std::nullopt;
}

std::vector<StudyProblem> problem_list(const TableReader& r, std::string_view k,
                                       std::vector<StudyProblem> def) {
  return word_list<StudyProblem>(
      r, k, std::move(def),
      "two_disk, two_decagon, gas_energy, haff, pile, tapping, rfm_temperature", problem_named);
}

// an array of booleans (switch values to try)
std::vector<bool> bool_list(const TableReader& r, std::string_view k, std::vector<bool> def) {
  const toml::array* a = array_at(r, k);
  if (!a) return def;
  std::vector<bool> out;
  for (const auto& e : *a) {
    const auto b = e.value<bool>();
    if (!b || !e.is_boolean()) r.fail(k, "must hold booleans (true, false)");
    if (std::find(out.begin(), out.end(), *b) == out.end()) out.push_back(*b);
  }
  return out;
}

// a problem's own list of Δt/t_c (empty when the key is absent)
// a contact resolved in at most 10⁴ steps: a finer step only spends the study's time (a Δt of
// 10⁻³⁰⁰ t_c would never see two bodies meet)
constexpr double kMinDtOverTc = 1e-4;
constexpr const char* kDtListRule =
    "must hold numbers from 1e-4 to 100 (time steps in contact times; 1e-4 resolves a contact in "
    "10^4 steps)";

std::vector<double> dt_list(const TableReader& r, std::string_view k) {
  std::vector<double> out;
  if (const toml::array* a = array_at(r, k)) {
    for (const auto& e : *a) {
      const auto v = e.value<double>();
      if (!v || e.is_boolean() || !(*v >= kMinDtOverTc) || *v > 100.0) r.fail(k, kDtListRule);
      out.push_back(*v);
    }
  }
  return out;
}

// the tables of the statistical problems: sizes, and optionally their own Δt lists
void read_stat_sizes(const TableReader& top, StudySpec& s) {
  StudySizes& z = s.sizes;
  if (const toml::table* t = scene_detail::sub_table(top, "tapping")) {
    TableReader r(top.ctx(), *t, "tapping",
                  {"n", "width", "taps", "discard", "g_p", "t1", "period", "settle", "seed",
                   "reference_dt", "dt_over_tc"});
    z.tap_n = static_cast<int>(r.integer("n", z.tap_n, 4, 100000));
    z.tap_width = r.number("width", z.tap_width, {0.04, 10.0, false, false});
    z.tap_taps = static_cast<int>(r.integer("taps", z.tap_taps, 1, 1000000));
    z.tap_discard = static_cast<int>(r.integer("discard", z.tap_discard, 0, 1000000));
    if (z.tap_taps - z.tap_discard < 3)
      r.fail("discard", "must leave at least 3 taps of the " + std::to_string(z.tap_taps));
    z.tap_g_p = r.number("g_p", z.tap_g_p, Range::positive());
    z.tap_t1 = r.number("t1", z.tap_t1, Range::positive());
    z.tap_period = r.number("period", z.tap_period, Range::positive());
    if (z.tap_period <= z.tap_t1) r.fail("period", "must be longer than t1");
    z.tap_settle = r.number("settle", z.tap_settle, Range::non_negative());
    z.tap_seed = static_cast<std::uint64_t>(r.integer("seed", 7, 0, INT64_MAX));
    z.tap_reference_dt = r.number("reference_dt", z.tap_reference_dt, Range::positive());
    s.tap_dt_over_tc = dt_list(r, "dt_over_tc");
  }
  if (const toml::table* t = scene_detail::sub_table(top, "rfm_temperature")) {
    TableReader r(top.ctx(), *t, "rfm_temperature",
                  {"n", "phi", "eps", "D", "duration", "discard", "sample", "blocks", "seed",
                   "reference_dt_over_tc", "dt_over_tc"});
    z.rfm_n = static_cast<int>(r.integer("n", z.rfm_n, 4, 1000000));
    z.rfm_phi = r.number("phi", z.rfm_phi, {0.0, 0.7, true, false});
    z.rfm_eps = r.number("eps", z.rfm_eps, Range::unit_interval_open_closed());
    z.rfm_D = r.number("D", z.rfm_D, Range::positive());
    z.rfm_duration = r.number("duration", z.rfm_duration, Range::positive());
    z.rfm_discard = r.number("discard", z.rfm_discard, Range::non_negative());
    z.rfm_sample = r.number("sample", z.rfm_sample, Range::positive());
    z.rfm_blocks = static_cast<int>(r.integer("blocks", z.rfm_blocks, 2, 10000));
    if (z.rfm_duration < 2 * z.rfm_blocks * z.rfm_sample)
      r.fail("duration", "must hold at least two samples per block (blocks × sample × 2)");
    z.rfm_seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, INT64_MAX));
    z.rfm_reference_dt_over_tc = r.number("reference_dt_over_tc", 0.0, Range::non_negative());
    if (z.rfm_reference_dt_over_tc > 0.0 && z.rfm_reference_dt_over_tc < kMinDtOverTc)
      r.fail("reference_dt_over_tc", "must be 0 (automatic) or from 1e-4 up");
    s.rfm_dt_over_tc = dt_list(r, "dt_over_tc");
  }
}

// a table of problem sizes; absent tables keep the defaults
void read_sizes(const TableReader& top, StudySizes& z) {
  if (const toml::table* t = scene_detail::sub_table(top, "two_disk")) {
    TableReader r(top.ctx(), *t, "two_disk", {"eps", "speed"});
    z.disk_eps = r.number("eps", z.disk_eps, Range::unit_interval_open_closed());
    z.disk_speed = r.number("speed", z.disk_speed, Range::positive());
  }
  if (const toml::table* t = scene_detail::sub_table(top, "two_decagon")) {
    TableReader r(top.ctx(), *t, "two_decagon", {"speed"});
    z.decagon_speed = r.number("speed", z.decagon_speed, Range::positive());
  }
  if (const toml::table* t = scene_detail::sub_table(top, "gas_energy")) {
    TableReader r(top.ctx(), *t, "gas_energy", {"n", "phi", "speed", "duration"});
    z.gas_n = static_cast<int>(r.integer("n", z.gas_n, 2, 1000000));
    z.gas_phi = r.number("phi", z.gas_phi, {0.0, 0.6, true, false});
    z.gas_speed = r.number("speed", z.gas_speed, Range::positive());
    z.gas_duration = r.number("duration", z.gas_duration, Range::positive());
  }
  if (const toml::table* t = scene_detail::sub_table(top, "haff")) {
    TableReader r(top.ctx(), *t, "haff", {"n", "duration"});
    z.haff_n = static_cast<int>(r.integer("n", z.haff_n, 10, 1000000));
    z.haff_duration = r.number("duration", z.haff_duration, Range::positive());
  }
  if (const toml::table* t = scene_detail::sub_table(top, "pile")) {
    TableReader r(top.ctx(), *t, "pile", {"n", "width", "duration"});
    z.pile_n = static_cast<int>(r.integer("n", z.pile_n, 2, 100000));
    z.pile_width = r.number("width", z.pile_width, {0.03, 10.0, false, false});
    z.pile_duration = r.number("duration", z.pile_duration, Range::positive());
  }
}

}  // namespace

std::string_view to_string(StudyProblem p) {
  for (const auto& [n, q] : kProblems)
    if (q == p) return n;
  return "?";
}

std::string study_switches_text(StudyProblem p, const StudySwitches& s) {
  switch (p) {
    case StudyProblem::TwoDisk:
    case StudyProblem::Haff:
      return std::string("clip=") + (s.clip ? "on" : "off");
    case StudyProblem::TwoDecagon:
    case StudyProblem::Pile:
      return std::string("hdot=") + (s.hdot_fd ? "finite_difference" : "analytic") +
             " rocking=" + (s.rocking ? "on" : "off");
    case StudyProblem::Tapping:
      return std::string("hdot=") + (s.hdot_fd ? "finite_difference" : "analytic") +
             " rocking=" + (s.rocking ? "on" : "off") +
             " early_rest=" + (s.early_rest ? "on" : "off");
    case StudyProblem::RfmTemperature:
      return std::string("clip=") + (s.clip ? "on" : "off");
    case StudyProblem::GasEnergy:
      break;
  }
  return "-";
}

StudySpec parse_study_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot read the study file");
  std::stringstream ss;
  ss << in.rdbuf();
  toml::table root;
  try {
    root = toml::parse(ss.str(), path);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(path + ":" + std::to_string(b.line) + ":" + std::to_string(b.column), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  Ctx ctx{path};
  StudySpec s;
  s.file = path;
  TableReader top(
      ctx, root, "",
      {"name", "problems", "matrix", "reference_dt_over_tc", "stability", "stability_problems",
       "stability_start", "stability_factor", "stability_max", "seed", "two_disk", "two_decagon",
       "gas_energy", "haff", "pile", "tapping", "rfm_temperature"});
  s.name = top.string("name", s.name, true);
  s.problems = problem_list(top, "problems", {});
  if (s.problems.empty()) top.fail("problems", "is required: a list of reference problems");
  s.reference_dt_over_tc = top.number("reference_dt_over_tc", 0.0, Range::non_negative());
  if (s.reference_dt_over_tc > 0.0 && s.reference_dt_over_tc < kMinDtOverTc)
    top.fail("reference_dt_over_tc", "must be 0 (automatic) or from 1e-4 up");
  s.sizes.seed = static_cast<std::uint64_t>(top.integer("seed", 7, 0, INT64_MAX));
  read_sizes(top, s.sizes);
  read_stat_sizes(top, s);

  // the matrix: integrators × Δt × broad phase × switches
  const toml::table* m = scene_detail::sub_table(top, "matrix");
  if (!m) top.fail("matrix", "is required: a [matrix] table with integrators and dt_over_tc");
  TableReader mr(ctx, *m, "matrix",
                 {"integrators", "dt_over_tc", "broad_phase", "hdot", "clip", "rocking_damping",
                  "early_rest"});
  s.integrators = word_list<IntegratorKind>(
      mr, "integrators", {}, "gear6, velocity_verlet, position_verlet, semi_implicit_euler",
      [](const std::string& w) -> std::optional<IntegratorKind> {
        IntegratorKind k{};
        return parse_integrator(w, k) ? std::optional(k) : std::nullopt;
      });
  if (s.integrators.empty()) mr.fail("integrators", "is required: a list of integrators");
  if (const toml::array* a = array_at(mr, "dt_over_tc")) {
    for (const auto& e : *a) {
      const auto v = e.value<double>();
      if (!v || e.is_boolean() || !(*v >= kMinDtOverTc) || *v > 100.0)
        mr.fail("dt_over_tc", kDtListRule);
      s.dt_over_tc.push_back(*v);
    }
  } else {
    mr.fail("dt_over_tc", "is required: time steps in units of the contact time");
  }
  s.broad_phases = word_list<BroadPhaseKind>(
      mr, "broad_phase", {BroadPhaseKind::CellGrid}, "box2d_tree, cell_grid",
      [](const std::string& w) -> std::optional<BroadPhaseKind> {
        if (w == "box2d_tree") return BroadPhaseKind::Box2DTree;
        if (w == "cell_grid") return BroadPhaseKind::CellGrid;
        return std::nullopt;
      });
  s.hdot_fd = word_list<bool>(mr, "hdot", {false}, "analytic, finite_difference",
                              [](const std::string& w) -> std::optional<bool> {
                                if (w == "analytic") return false;
                                if (w == "finite_difference") return true;
                                return std::nullopt;
                              });
  s.clip = bool_list(mr, "clip", {false});
  s.rocking = bool_list(mr, "rocking_damping", {true});
  s.early_rest = bool_list(mr, "early_rest", {false});

  // the stability map
  s.stability = top.boolean("stability", false);
  s.stability_problems =
      problem_list(top, "stability_problems", {StudyProblem::TwoDisk, StudyProblem::Pile});
  s.stability_start = top.number("stability_start", s.stability_start, {0.0, 10.0, true, false});
  s.stability_factor = top.number("stability_factor", s.stability_factor, {1.0, 4.0, true, false});
  s.stability_max = top.number("stability_max", s.stability_max, {0.0, 100.0, true, false});
  if (s.stability_max < s.stability_start)
    top.fail("stability_max", "must be at least stability_start");
  return s;
}

}  // namespace gs
