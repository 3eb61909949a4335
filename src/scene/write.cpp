// SceneSpec → TOML and → the resolved key map. One list of blocks (emit) feeds both, so the
// TOML written and the keys shown in run.json cannot disagree.
#include <sstream>

#include "scene/parse.hpp"
#include "scene/reader.hpp"
#include "scene/render_section.hpp"
#include "scene/rfm_section.hpp"
#include "scene/snapshot_section.hpp"

namespace gs {

namespace {

using scene_detail::format_double;
using scene_detail::quote;

/// one TOML section: its header, its dotted prefix and its key = value lines
struct Block {
  std::string header;  ///< "[box]" or "[[species]]"
  std::string prefix;  ///< "box" or "species[0]"
  std::vector<std::pair<std::string, std::string>> kv;
  void num(const std::string& k, double v) { kv.emplace_back(k, format_double(v)); }
  void integer(const std::string& k, long long v) { kv.emplace_back(k, std::to_string(v)); }
  void flag(const std::string& k, bool v) { kv.emplace_back(k, v ? "true" : "false"); }
  void str(const std::string& k, std::string_view v) { kv.emplace_back(k, quote(v)); }
  template <class E>
  void name(const std::string& k, E v) {
    kv.emplace_back(k, quote(scene_name(v)));
  }
};

// a material reference as written: empty means the first material
std::string material_name(const SceneSpec& s, const std::string& m) {
  return m.empty() && !s.materials.empty() ? s.materials.front().name : m;
}

std::vector<Block> emit(const SceneSpec& s) {
  std::vector<Block> out;
  // [scene]
  Block& sc = out.emplace_back(Block{"[scene]", "scene", {}});
  sc.str("name", s.name);
  sc.str("description", s.description);
  sc.num("duration", s.duration);
  // [model]
  Block& m = out.emplace_back(Block{"[model]", "model", {}});
  m.name("kind", s.model.kind);
  m.flag("hdot_finite_difference", s.model.hdot_finite_difference);
  m.flag("rocking_damping", s.model.rocking_damping);
  m.flag("clip_attractive", s.model.clip_attractive);
  m.flag("rotation", s.model.rotation);
  // [[material]]
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    const MaterialSpec& mat = s.materials[i];
    Block& b = out.emplace_back(Block{"[[material]]", "material[" + std::to_string(i) + "]", {}});
    b.str("name", mat.name);
    b.num("E", mat.E);
    b.num("gamma", mat.gamma);
    b.num("mu", mat.mu);
    b.num("ks", mat.ks);
    b.num("eps_n", mat.eps_n);
    b.num("eps_t", mat.eps_t);
  }
  // [[species]]: sides only for polygons, mass only when given
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    const SpeciesSpec& sp = s.species[i];
    Block& b = out.emplace_back(Block{"[[species]]", "species[" + std::to_string(i) + "]", {}});
    b.str("name", sp.name);
    b.name("shape", sp.shape);
    if (sp.shape == ShapeKind::Polygon) b.integer("sides", sp.sides);
    b.num("radius", sp.radius);
    // with explicit particles the list is the truth (builders may leave count at 0)
    long long count = sp.count;
    if (!s.prep.particles.empty()) {
      count = 0;
      for (const auto& q : s.prep.particles) count += q.species == sp.name;
    }
    b.integer("count", count);
    b.num("density", sp.density);
    if (sp.mass) b.num("mass", *sp.mass);
    std::string mat = material_name(s, sp.material);
    if (!mat.empty()) b.str("material", mat);
  }
  // [box]: a ring given by L′ writes L′ only (L follows from it)
  Block& bx = out.emplace_back(Block{"[box]", "box", {}});
  bx.name("kind", s.box.kind);
  if (s.box.reduced_length)
    bx.num("reduced_length", *s.box.reduced_length);
  else
    bx.num("width", s.box.width);
  bx.num("height", s.box.height);
  bx.flag("lid", s.box.lid);
  bx.num("wall_thickness", s.box.wall_thickness);
  std::string bmat = material_name(s, s.box.material);
  if (!bmat.empty()) bx.str("material", bmat);
  // [preparation] and its explicit particles
  Block& p = out.emplace_back(Block{"[preparation]", "preparation", {}});
  p.name("placement", s.prep.placement);
  p.integer("seed", static_cast<long long>(s.prep.seed));
  p.num("column_height", s.prep.column_height);
  p.num("velocity_amplitude", s.prep.velocity_amplitude);
  p.num("settle_time", s.prep.settle_time);
  if (!s.prep.from_state.empty()) p.str("from_state", s.prep.from_state);
  for (std::size_t i = 0; i < s.prep.particles.size(); ++i) {
    const auto& q = s.prep.particles[i];
    Block& b = out.emplace_back(
        Block{"[[preparation.particle]]", "preparation.particle[" + std::to_string(i) + "]", {}});
    b.str("species", q.species);
    b.num("x", q.x);
    b.num("y", q.y);
    b.num("theta", q.theta);
    b.num("vx", q.vx);
    b.num("vy", q.vy);
    b.num("omega", q.omega);
  }
  // [integrator]
  Block& in = out.emplace_back(Block{"[integrator]", "integrator", {}});
  in.name("kind", s.integrator.kind);
  in.num("dt", s.integrator.dt);
  in.name("broad_phase", s.integrator.broad_phase);
  in.integer("sort_every", s.integrator.sort_every);
  // [drive]
  const DriveSpec& d = s.drive;
  Block& dr = out.emplace_back(Block{"[drive]", "drive", {}});
  dr.name("kind", d.kind);
  dr.num("g", d.g);
  dr.num("gx", d.gx);
  dr.num("gy", d.gy);
  dr.num("g_p", d.g_p);
  dr.num("t1", d.t1);
  dr.num("period", d.period);
  dr.num("f", d.f);
  dr.num("relax", d.relax);
  dr.num("D", d.D);
  dr.integer("com_removal_every", d.com_removal_every);
  dr.flag("early_rest", d.early_rest);
  dr.num("rest_speed", d.rest_speed);
  dr.num("rest_energy", d.rest_energy);
  dr.num("rest_hold", d.rest_hold);
  dr.flag("quench", d.quench);
  dr.num("quench_speed", d.quench_speed);
  dr.num("quench_hold", d.quench_hold);
  dr.integer("taps", d.taps);
  // [health]
  Block& h = out.emplace_back(Block{"[health]", "health", {}});
  h.num("max_overlap", s.health.max_overlap);
  h.integer("check_every", s.health.check_every);
  h.flag("allow_unstable", s.health.allow_unstable);
  // [output]
  Block& o = out.emplace_back(Block{"[output]", "output", {}});
  o.integer("series_every", s.output.series_every);
  o.flag("final_state", s.output.final_state);
  const double* r = s.output.test_rect;
  std::string rect = "[";
  for (int i = 0; i < 4; ++i) rect += format_double(r[i]) + (i < 3 ? ", " : "]");
  o.kv.emplace_back("test_rect", rect);
  o.integer("discard_taps", s.output.discard_taps);
  o.num("checkpoint_minutes", s.output.checkpoint_minutes);
  o.integer("checkpoint_taps", s.output.checkpoint_taps);
  o.integer("checkpoint_steps", s.output.checkpoint_steps);
  // [output.snapshots]: scene/snapshot_section.cpp (only when the scene has it, so other
  // scenes keep their key list)
  if (s.output.snapshots.given)
    out.push_back(Block{"[output.snapshots]", "output.snapshots",
                        scene_detail::snapshot_entries(s.output.snapshots)});
  // [render]: scene/render_section.cpp
  out.push_back(Block{"[render]", "render", scene_detail::render_entries(s.render)});
  // [rfm]: scene/rfm_section.cpp (random-force scenes, or when the file had one)
  if (scene_detail::rfm_written(s))
    out.push_back(Block{"[rfm]", "rfm", scene_detail::rfm_entries(s.rfm)});
  return out;
}

}  // namespace

std::map<std::string, std::string> scene_resolved(const SceneSpec& s) {
  std::map<std::string, std::string> out;
  for (const Block& b : emit(s))
    for (const auto& [k, v] : b.kv) out[b.prefix + "." + k] = v;
  return out;
}

std::string scene_to_toml(const SceneSpec& s) {
  std::ostringstream os;
  os << "# gransim scene, every key written out (scene_to_toml)\n";
  for (const Block& b : emit(s)) {
    os << '\n' << b.header << '\n';
    for (const auto& [k, v] : b.kv) os << k << " = " << v << '\n';
  }
  return os.str();
}

}  // namespace gs
