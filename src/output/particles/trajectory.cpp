// extended XYZ: write frames of a World, read them back for `gransim movie` and `render`
#include "output/particles/trajectory.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "core/input_file.hpp"
#include "view/render_world.hpp"

namespace gs {

namespace {

constexpr std::string_view kElements[] = {
    "H",  "He", "Li", "Be", "B",  "C",  "N",  "O",  "F",  "Ne", "Na", "Mg", "Al", "Si", "P",
    "S",  "Cl", "Ar", "K",  "Ca", "Sc", "Ti", "V",  "Cr", "Mn", "Fe", "Co", "Ni", "Cu", "Zn",
    "Ga", "Ge", "As", "Se", "Br", "Kr", "Rb", "Sr", "Y",  "Zr", "Nb", "Mo", "Tc", "Ru", "Rh",
    "Pd", "Ag", "Cd", "In", "Sn", "Sb", "Te", "I",  "Xe", "Cs", "Ba", "La", "Ce", "Pr", "Nd",
    "Pm", "Sm", "Eu", "Gd", "Tb", "Dy", "Ho", "Er", "Tm", "Yb", "Lu", "Hf", "Ta", "W",  "Re",
    "Os", "Ir", "Pt", "Au", "Hg", "Tl", "Pb", "Bi", "Po", "At", "Rn", "Fr", "Ra", "Ac", "Th",
    "Pa", "U",  "Np", "Pu", "Am", "Cm", "Bk", "Cf", "Es", "Fm", "Md", "No", "Lr", "Rf", "Db",
    "Sg", "Bh", "Hs", "Mt", "Ds", "Rg", "Cn", "Nh", "Fl", "Mc", "Lv", "Ts", "Og"};

}  // namespace

std::string_view species_symbol(std::size_t k) {
  return kElements[k % (sizeof kElements / sizeof kElements[0])];
}

std::string name_token(const std::string& name) {
  std::string t = name;
  for (char& c : t)
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  return t;
}

void write_trajectory_frame(std::ostream& out, const World& w, const ContactSet* contacts,
                            Vec2 gravity, std::optional<long> tap) {
  const std::size_t n = w.size();
  char buf[640];
  // the comment line: box as a lattice (z of unit thickness), periodicity, clock, gravity
  const bool px = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
  const bool py = w.box == BoxKind::Periodic;
  std::snprintf(buf, sizeof buf,
                "Lattice=\"%.10g 0 0 0 %.10g 0 0 0 1\" Origin=\"0 0 -0.5\" Properties=%s "
                "Time=%.10g Step=%lld Gravity=\"%.8g %.8g 0\"",
                w.Lx, w.Ly, kTrajectoryProperties, w.s.t, static_cast<long long>(w.s.step),
                gravity.x, gravity.y);
  out << n << '\n' << buf;
  if (tap) out << " Tap=" << *tap;
  out << " pbc=\"" << (px ? 'T' : 'F') << ' ' << (py ? 'T' : 'F') << " F\"\n";
  const std::vector<double> z = contacts ? contact_counts(w, *contacts) : std::vector<double>(n);
  std::vector<std::string> names;
  for (const Species& k : w.species) names.push_back(name_token(k.name));
  // one line per particle, in label order (a spatial sort moves particles between slots)
  const std::vector<std::uint32_t> slot = w.slots_by_id();
  for (std::size_t label = 0; label < n; ++label) {
    const std::size_t i = slot.size() == n ? slot[label] : label;
    const std::size_t sp = static_cast<std::size_t>(w.sp[i]);
    const Species& k = w.species[sp];
    const double vx = w.s.vx[i], vy = w.s.vy[i], th = w.s.th[i];
    // orientation: the unit quaternion (x, y, z, w) of the turn by θ about z
    std::snprintf(
        buf, sizeof buf,
        " %.10g %.10g 0 %s %zu %zu %.10g %.10g 0 %.10g %.10g 0 0 %.10g %.10g 0 0 %.10g %.10g "
        "%d %d\n",
        w.s.x[i], w.s.y[i], names[sp].c_str(), sp, label, vx, vy, w.radius[i], th,
        std::sin(0.5 * th), std::cos(0.5 * th), w.s.omega[i], std::hypot(vx, vy),
        k.shape == ShapeKind::Polygon ? k.sides : 0, static_cast<int>(z[i]));
    out << species_symbol(sp) << buf;
  }
}

// ---------------------------------------------------------------------------------------------
// reading

namespace {
// checked before the stream opens it (a FIFO would block the open)
const std::string& checked_trajectory(const std::string& path) {
  check_input_file(path, "trajectory file");
  return path;
}
}  // namespace

TrajectoryReader::TrajectoryReader(const std::string& path)
    : path_(path), in_(checked_trajectory(path)) {
  if (!in_) throw InputError(path, "", "cannot open the trajectory file");
}

void TrajectoryReader::fail(const std::string& what) const {
  throw InputError(path_ + ":" + std::to_string(line_), "", what);
}

namespace {

// key=value pairs of an extended XYZ comment line (values may be "quoted")
std::map<std::string, std::string> comment_keys(const std::string& line) {
  std::map<std::string, std::string> kv;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t k0 = i;
    while (i < line.size() && line[i] != '=' && !std::isspace(static_cast<unsigned char>(line[i])))
      ++i;
    const std::string key = line.substr(k0, i - k0);
    std::string value;
    if (i < line.size() && line[i] == '=') {
      ++i;
      if (i < line.size() && line[i] == '"') {
        const std::size_t e = line.find('"', i + 1);
        value = line.substr(i + 1, e == std::string::npos ? std::string::npos : e - i - 1);
        i = e == std::string::npos ? line.size() : e + 1;
      } else {
        const std::size_t v0 = i;
        while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
        value = line.substr(v0, i - v0);
      }
    }
    if (!key.empty()) kv[key] = value;
  }
  return kv;
}

// numbers of a space-separated list
std::vector<double> number_list(const std::string& s) {
  std::istringstream in(s);
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

}  // namespace

bool TrajectoryReader::next(TrajectoryFrame& f) {
  // the particle count (blank lines between frames are tolerated)
  std::string line;
  do {
    if (!std::getline(in_, line)) return false;
    ++line_;
  } while (line.find_first_not_of(" \t\r") == std::string::npos);
  long long n = -1;
  try {
    std::size_t used = 0;
    n = std::stoll(line, &used);
    if (line.find_first_not_of(" \t\r", used) != std::string::npos) n = -1;
  } catch (...) {
  }
  if (n < 0) fail("expected the number of particles of a frame, got '" + line + "'");

  // the comment line: Properties= says where each column is
  if (!std::getline(in_, line)) fail("the frame ends before its comment line");
  ++line_;
  const auto kv = comment_keys(line);
  const auto props = kv.find("Properties");
  if (props == kv.end()) fail("no Properties= in the comment line (not extended XYZ)");
  std::map<std::string, std::pair<int, int>> col;  // name → first column, count
  {
    std::vector<std::string> parts;
    std::istringstream ps(props->second);
    for (std::string p; std::getline(ps, p, ':');) parts.push_back(p);
    if (parts.size() % 3 != 0) fail("Properties= must be name:type:count triples");
    int c = 0;
    for (std::size_t k = 0; k < parts.size(); k += 3) {
      const int cnt = std::atoi(parts[k + 2].c_str());
      if (cnt < 1) fail("bad column count in Properties= for '" + parts[k] + "'");
      col[parts[k]] = {c, cnt};
      c += cnt;
    }
  }
  for (const char* need : {"species", "pos"})
    if (!col.count(need)) fail(std::string("Properties= has no '") + need + "' column");
  f = TrajectoryFrame{};
  if (auto it = kv.find("Time"); it != kv.end()) f.time = std::atof(it->second.c_str());
  if (auto it = kv.find("Step"); it != kv.end()) f.step = std::atoll(it->second.c_str());
  if (auto it = kv.find("Tap"); it != kv.end()) f.tap = std::atol(it->second.c_str());
  if (auto it = kv.find("Gravity"); it != kv.end()) {
    const auto g = number_list(it->second);
    if (g.size() >= 2) f.gravity = Vec2{g[0], g[1]};
  }
  if (auto it = kv.find("Lattice"); it != kv.end()) {
    const auto l = number_list(it->second);
    if (l.size() == 9) f.lattice = {l[0], l[4]};
  }

  // the particle lines
  auto value = [&](const std::vector<std::string>& tok, const char* name, int k, double def) {
    auto it = col.find(name);
    if (it == col.end() || k >= it->second.second) return def;
    const std::string& s = tok[it->second.first + k];
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (end == s.c_str() || *end != '\0')
      fail(std::string("column '") + name + "': not a number: '" + s + "'");
    return v;
  };
  int ncol = 0;
  for (const auto& [name, c] : col) ncol = std::max(ncol, c.first + c.second);
  // ω: the z component of an `omega` vector, or the single `omega` column of older files
  const int omega_k = col.count("omega") && col.at("omega").second >= 3 ? 2 : 0;
  const int species_col = col.count("name") ? col.at("name").first : col.at("species").first;
  for (long long i = 0; i < n; ++i) {
    if (!std::getline(in_, line))
      fail("the frame ends after " + std::to_string(i) + " of " + std::to_string(n) + " particles");
    ++line_;
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (static_cast<int>(tok.size()) < ncol)
      fail("expected " + std::to_string(ncol) + " columns, got " + std::to_string(tok.size()));
    // species by name: the `name` column when there is one, else `species` (older files)
    f.species.push_back(tok[species_col]);
    f.x.push_back(value(tok, "pos", 0, 0.0));
    f.y.push_back(value(tok, "pos", 1, 0.0));
    f.vx.push_back(value(tok, "velo", 0, 0.0));
    f.vy.push_back(value(tok, "velo", 1, 0.0));
    f.radius.push_back(value(tok, "radius", 0, 0.0));
    f.theta.push_back(value(tok, "theta", 0, 0.0));
    f.omega.push_back(value(tok, "omega", omega_k, 0.0));
    f.speed.push_back(value(tok, "speed", 0, std::hypot(f.vx.back(), f.vy.back())));
    f.sides.push_back(static_cast<int>(value(tok, "sides", 0, 0.0)));
  }
  ++frames_;
  return true;
}

void load_trajectory_frame(World& w, const TrajectoryFrame& f, const std::string& where) {
  // the particles are replaced, the constants (species, walls, box) kept
  World fresh = w;
  fresh.clear_particles();
  for (std::size_t i = 0; i < f.size(); ++i) {
    int k = -1;
    for (std::size_t s = 0; s < w.species.size(); ++s)
      if (w.species[s].name == f.species[i] || name_token(w.species[s].name) == f.species[i])
        k = static_cast<int>(s);
    if (k < 0)
      throw InputError(where, "species",
                       "particle " + std::to_string(i) + " has species '" + f.species[i] +
                           "', which the scene does not define");
    fresh.add_particle(k, {f.x[i], f.y[i]}, f.theta[i], {f.vx[i], f.vy[i]}, f.omega[i]);
  }
  fresh.s.t = f.time;
  fresh.s.step = f.step;
  w = std::move(fresh);
}

}  // namespace gs
