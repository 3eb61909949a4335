#include "sim/state_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <fstream>
#include <sstream>

#include "core/input_file.hpp"
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

namespace {

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

}  // namespace

void read_state_file(World& w, const std::string& path) {
  check_input_file(path, "state file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open state file");
  std::ostringstream buf;
  buf << in.rdbuf();
  parse_state_text(w, buf.str(), path);
}

void parse_state_text(World& w, const std::string& text, const std::string& path) {
  if (text.empty()) throw InputError(path, "", "the state file is empty");
  // every row ends with a newline: a last line without one was cut while being written
  if (text.back() != '\n')
    throw InputError(path, "", "truncated: the last line has no line end (a file cut mid-row)");
  static const char* const kColumns[] = {"id", "species", "x", "y", "theta", "vx", "vy", "omega"};
  std::istringstream lines(text);
  std::string line;
  int lineno = 0;
  double t = 0;
  long long step = 0;
  long long declared = -1;  // n= of the header line, when given
  World fresh = w;
  fresh.clear_particles();
  while (std::getline(lines, line)) {
    ++lineno;
    const std::string where = path + ":" + std::to_string(lineno);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.rfind("# t=", 0) == 0) {
      long long n = -1;
      const int got = std::sscanf(line.c_str(), "# t=%lf step=%lld n=%lld", &t, &step, &n);
      if (got < 2 || !std::isfinite(t) || step < 0)
        throw InputError(where, "", "bad header line '" + line + "' (expected # t=T step=S n=N)");
      if (got == 3) declared = n;
      continue;
    }
    if (line.empty() || line[0] == '#' || line.rfind("id,", 0) == 0) continue;
    std::vector<std::string> cells;
    std::istringstream ls(line);
    for (std::string cell; std::getline(ls, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    if (cells.size() != 8)
      throw InputError(where, "", "expected 8 columns (id,species,x,y,theta,vx,vy,omega), got " +
                                      std::to_string(cells.size()));
    double v[6];
    for (int c = 0; c < 6; ++c) v[c] = state_number(cells[c + 2], where, c + 3, kColumns[c + 2]);
    const std::string& name = cells[1];
    int k = -1;
    for (std::size_t s = 0; s < w.species.size(); ++s)
      if (w.species[s].name == name) k = static_cast<int>(s);
    if (k < 0) throw InputError(where, "species", "column 2: unknown species '" + name + "' for this scene");
    fresh.add_particle(k, {v[0], v[1]}, v[2], {v[3], v[4]}, v[5]);
  }
  if (fresh.size() == 0) throw InputError(path, "", "the state file holds no particle rows");
  if (declared >= 0 && static_cast<long long>(fresh.size()) != declared)
    throw InputError(path, "", "truncated or edited: the header says n=" + std::to_string(declared) +
                                   " particles, the file has " + std::to_string(fresh.size()) +
                                   " rows");
  fresh.s.t = t;
  fresh.s.step = step;
  w = std::move(fresh);
}

}  // namespace gs
