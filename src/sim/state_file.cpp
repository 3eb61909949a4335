#include "sim/state_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace gs {

namespace {

constexpr const char* kHeader = "id,species,x,y,theta,vx,vy,omega";

// a whole cell as one finite number, or an InputError naming line and column
double state_number(const std::string& cell, const std::string& where, int column,
                    const char* name) {
  const std::string col = "column " + std::to_string(column) + " ('" + name + "')";
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(cell.c_str(), &end);
  if (cell.empty() || end != cell.c_str() + cell.size() || errno == ERANGE)
    throw InputError(where, "", col + ": not a number: '" + cell + "'");
  if (!std::isfinite(v)) throw InputError(where, "", col + ": not finite: '" + cell + "'");
  return v;
}

// the rows of a state file's text (either form); `declared` gets n= of the older header
StateRows parse_state_rows(const std::string& text, const std::string& path, long long& declared) {
  if (text.empty()) throw InputError(path, "", "the state file is empty");
  // every row ends with a newline: a last line without one was cut while being written
  if (text.back() != '\n')
    throw InputError(path, "", "truncated: the last line has no line end (a file cut mid-row)");
  static const char* const kColumns[] = {"id", "species", "x", "y", "theta", "vx", "vy", "omega"};
  StateRows r;
  std::istringstream lines(text);
  std::string line;
  int lineno = 0;
  bool header = false;
  while (std::getline(lines, line)) {
    ++lineno;
    const std::string where = path + ":" + std::to_string(lineno);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // the older form's preamble: "# gransim state v1", "# t=… step=… n=…"
    if (line.rfind("# t=", 0) == 0) {
      long long step = 0, n = -1;
      const int got = std::sscanf(line.c_str(), "# t=%lf step=%lld n=%lld", &r.t, &step, &n);
      if (got < 2 || !std::isfinite(r.t) || step < 0)
        throw InputError(where, "", "bad header line '" + line + "' (expected # t=T step=S n=N)");
      r.step = step;
      if (got == 3) declared = n;
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind(kHeader, 0) != 0)
        throw InputError(where, "",
                         std::string("not a gransim state file: expected the header ") + kHeader);
      header = true;
      continue;
    }
    std::vector<std::string> cells;
    std::istringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (cells.size() != 8)
      throw InputError(where, "",
                       "expected 8 columns (id,species,x,y,theta,vx,vy,omega), got " +
                           std::to_string(cells.size()));
    double v[6];
    for (int c = 0; c < 6; ++c) v[c] = state_number(cells[c + 2], where, c + 3, kColumns[c + 2]);
    r.species.push_back(cells[1]);
    r.line.push_back(lineno);
    r.x.push_back(v[0]);
    r.y.push_back(v[1]);
    r.th.push_back(v[2]);
    r.vx.push_back(v[3]);
    r.vy.push_back(v[4]);
    r.omega.push_back(v[5]);
  }
  if (!header)
    throw InputError(path, "", std::string("not a gransim state file: no header ") + kHeader);
  if (r.size() == 0) throw InputError(path, "", "the state file holds no particle rows");
  return r;
}

void check_count(const StateRows& r, long long declared, const std::string& path) {
  if (declared >= 0 && static_cast<long long>(r.size()) != declared)
    throw InputError(path, "",
                     "truncated or edited: n=" + std::to_string(declared) +
                         " particles declared, the file has " + std::to_string(r.size()) + " rows");
}

// replace the particles of `w` with the rows, species by name
void place_rows(World& w, const StateRows& r, const std::string& path) {
  World fresh = w;
  fresh.clear_particles();
  for (std::size_t i = 0; i < r.size(); ++i) {
    int k = -1;
    for (std::size_t s = 0; s < w.species.size(); ++s)
      if (w.species[s].name == r.species[i]) k = static_cast<int>(s);
    if (k < 0)
      throw InputError(path + ":" + std::to_string(r.line[i]), "species",
                       "column 2: unknown species '" + r.species[i] + "' for this scene");
    fresh.add_particle(k, {r.x[i], r.y[i]}, r.th[i], {r.vx[i], r.vy[i]}, r.omega[i]);
  }
  fresh.s.t = r.t;
  fresh.s.step = r.step;
  w = std::move(fresh);
}

}  // namespace

std::string state_sidecar_path(const std::string& csv_path) {
  std::filesystem::path p(csv_path);
  p.replace_extension(".json");
  return p.string();
}

void write_state_file(const World& w, const std::string& path) {
  std::ostringstream o;
  o << kHeader << "\n";
  char buf[64];
  // one row per particle in label order (a spatial sort moves particles between slots)
  const std::vector<std::uint32_t> slot = w.slots_by_id();
  for (std::size_t k = 0; k < w.size(); ++k) {
    const std::size_t i = slot.size() == w.size() ? slot[k] : k;
    o << k << ',' << w.species[w.sp[i]].name;
    for (double v : {w.s.x[i], w.s.y[i], w.s.th[i], w.s.vx[i], w.s.vy[i], w.s.omega[i]}) {
      std::snprintf(buf, sizeof buf, ",%.17g", v);
      o << buf;
    }
    o << '\n';
  }
  // the sidecar first: a state file is never newer than what describes it
  nlohmann::ordered_json j;
  j["format"] = "gransim state";
  j["version"] = 2;
  j["t"] = w.s.t;
  j["step"] = w.s.step;
  j["particles"] = w.size();
  j["columns"] = {{"id", "particle label"},
                  {"species", "species name"},
                  {"x", "m"},
                  {"y", "m"},
                  {"theta", "rad"},
                  {"vx", "m/s"},
                  {"vy", "m/s"},
                  {"omega", "rad/s"}};
  write_file_atomic(state_sidecar_path(path), j.dump(2) + "\n");
  write_file_atomic(path, o.str());
}

StateRows read_state_rows(const std::string& path) {
  check_input_file(path, "state file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open state file");
  std::ostringstream buf;
  buf << in.rdbuf();
  long long declared = -1;
  StateRows r = parse_state_rows(buf.str(), path, declared);
  // the newer form keeps time, step and the particle count in the sidecar
  const std::string side = state_sidecar_path(path);
  if (std::ifstream js(side); js) {
    try {
      const nlohmann::json j = nlohmann::json::parse(js);
      r.t = j.at("t").get<double>();
      r.step = j.at("step").get<std::int64_t>();
      if (j.contains("particles")) declared = j.at("particles").get<long long>();
    } catch (const nlohmann::json::exception& e) {
      throw InputError(side, "", std::string("not a gransim state sidecar: ") + e.what());
    }
    if (!std::isfinite(r.t) || r.step < 0) throw InputError(side, "", "bad time or step");
  }
  check_count(r, declared, path);
  return r;
}

void read_state_file(World& w, const std::string& path) {
  place_rows(w, read_state_rows(path), path);
}

void parse_state_text(World& w, const std::string& text, const std::string& path) {
  long long declared = -1;
  const StateRows r = parse_state_rows(text, path, declared);
  check_count(r, declared, path);
  place_rows(w, r, path);
}

}  // namespace gs
