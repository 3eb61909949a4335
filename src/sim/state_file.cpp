#include "sim/state_file.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "output/run_dir.hpp"

namespace gs {

void write_state_file(const World& w, const std::string& path) {
  std::ostringstream o;
  o << "# gransim state v1\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", w.s.t);
  o << "# t=" << buf << " step=" << w.s.step << " n=" << w.size() << "\n";
  o << "id,species,x,y,theta,vx,vy,omega\n";
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
  write_file_atomic(path, o.str());
}

void read_state_file(World& w, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open state file");
  std::string line;
  int lineno = 0;
  double t = 0;
  long long step = 0;
  World fresh = w;
  fresh.clear_particles();
  while (std::getline(in, line)) {
    ++lineno;
    if (line.rfind("# t=", 0) == 0) {
      std::sscanf(line.c_str(), "# t=%lf step=%lld", &t, &step);
      continue;
    }
    if (line.empty() || line[0] == '#' || line.rfind("id,", 0) == 0) continue;
    std::istringstream ls(line);
    std::string id, name, cell;
    std::getline(ls, id, ',');
    std::getline(ls, name, ',');
    double v[6];
    for (double& x : v) {
      if (!std::getline(ls, cell, ',')) throw InputError(path + ":" + std::to_string(lineno), "", "expected 8 columns");
      try {
        x = std::stod(cell);
      } catch (...) {
        throw InputError(path + ":" + std::to_string(lineno), "", "not a number: '" + cell + "'");
      }
    }
    int k = -1;
    for (std::size_t s = 0; s < w.species.size(); ++s)
      if (w.species[s].name == name) k = static_cast<int>(s);
    if (k < 0) throw InputError(path + ":" + std::to_string(lineno), "species", "unknown species '" + name + "' for this scene");
    fresh.add_particle(k, {v[0], v[1]}, v[2], {v[3], v[4]}, v[5]);
  }
  fresh.s.t = t;
  fresh.s.step = step;
  w = std::move(fresh);
}

}  // namespace gs
