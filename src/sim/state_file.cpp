#include "sim/state_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "output/run_dir.hpp"

namespace gs {

namespace {
constexpr const char* kHeader = "id,species,x,y,theta,vx,vy,omega";
}

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
    for (double v : {w.s.x[i], w.s.y[i], w.s.th[i], w.s.vx[i], w.s.vy[i], w.s.w[i]}) {
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
  j["columns"] = {{"id", "particle label"},     {"species", "species name"},
                  {"x", "m"},                   {"y", "m"},
                  {"theta", "rad"},             {"vx", "m/s"},
                  {"vy", "m/s"},                {"omega", "rad/s"}};
  write_file_atomic(state_sidecar_path(path), j.dump(2) + "\n");
  write_file_atomic(path, o.str());
}

StateRows read_state_rows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open state file");
  StateRows r;
  std::string line;
  int lineno = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // the older form's preamble: "# gransim state v1", "# t=… step=… n=…"
    if (line.rfind("# t=", 0) == 0) {
      long long step = 0;
      std::sscanf(line.c_str(), "# t=%lf step=%lld", &r.t, &step);
      r.step = step;
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("id,species,x,y,theta,vx,vy,omega", 0) != 0)
        throw InputError(path + ":" + std::to_string(lineno), "",
                         std::string("not a gransim state file: expected the header ") + kHeader);
      header = true;
      continue;
    }
    std::istringstream ls(line);
    std::string id, name, cell;
    std::getline(ls, id, ',');
    std::getline(ls, name, ',');
    double v[6];
    for (double& x : v) {
      if (!std::getline(ls, cell, ','))
        throw InputError(path + ":" + std::to_string(lineno), "", "expected 8 columns");
      try {
        x = std::stod(cell);
      } catch (...) {
        throw InputError(path + ":" + std::to_string(lineno), "", "not a number: '" + cell + "'");
      }
    }
    r.species.push_back(name);
    r.line.push_back(lineno);
    r.x.push_back(v[0]);
    r.y.push_back(v[1]);
    r.th.push_back(v[2]);
    r.vx.push_back(v[3]);
    r.vy.push_back(v[4]);
    r.w.push_back(v[5]);
  }
  if (!header) throw InputError(path, "", std::string("not a gransim state file: no header ") + kHeader);
  // the newer form keeps time and step in the sidecar
  const std::string side = state_sidecar_path(path);
  if (std::ifstream js(side); js) {
    try {
      const nlohmann::json j = nlohmann::json::parse(js);
      r.t = j.at("t").get<double>();
      r.step = j.at("step").get<std::int64_t>();
    } catch (const nlohmann::json::exception& e) {
      throw InputError(side, "", std::string("not a gransim state sidecar: ") + e.what());
    }
  }
  return r;
}

void read_state_file(World& w, const std::string& path) {
  const StateRows r = read_state_rows(path);
  World fresh = w;
  fresh.clear_particles();
  for (std::size_t i = 0; i < r.size(); ++i) {
    int k = -1;
    for (std::size_t s = 0; s < w.species.size(); ++s)
      if (w.species[s].name == r.species[i]) k = static_cast<int>(s);
    if (k < 0)
      throw InputError(path + ":" + std::to_string(r.line[i]), "species",
                       "unknown species '" + r.species[i] + "' for this scene");
    fresh.add_particle(k, {r.x[i], r.y[i]}, r.th[i], {r.vx[i], r.vy[i]}, r.w[i]);
  }
  fresh.s.t = r.t;
  fresh.s.step = r.step;
  w = std::move(fresh);
}

}  // namespace gs
