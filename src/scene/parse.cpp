// scene file → SceneSpec: parse the TOML, apply --set overrides, then read every section
// once through a TableReader (reader.hpp) that types, range-checks and locates each key.
// Defaults that depend on other keys (model → integrator, box → placement) are resolved here.
#include "scene/parse.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "core/input_file.hpp"
#include "scene/reader.hpp"
#include "scene/render_section.hpp"
#include "scene/rfm_section.hpp"
#include "scene/snapshot_section.hpp"

namespace gs {

using scene_detail::Ctx;
using scene_detail::quote;
using scene_detail::Range;
using scene_detail::TableReader;

namespace {

constexpr std::int64_t kIntMax = INT_MAX;

// the keys of a [[species]] table (read twice: properties first, counts after the particles)
const std::vector<std::string_view> kSpeciesKeys = {"name",  "shape",   "sides", "radius",
                                                    "count", "density", "mass",  "material"};

constexpr std::int64_t kInt64Max = std::numeric_limits<std::int64_t>::max();

// an absent section reads as an empty table, so its keys take their defaults
const toml::table& table_or_empty(const toml::table* t) {
  static const toml::table empty;
  return t ? *t : empty;
}

// the line of a table, for "first defined at line N"
std::string line_of(const toml::node& n) { return std::to_string(n.source().begin.line); }

// ---------------------------------------------------------------------------------------
// [model]

void read_model(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(
      ctx, table_or_empty(sub_table(top, "model")), "model",
      {"kind", "hdot_finite_difference", "rocking_damping", "clip_attractive", "rotation"});
  s.model.kind = r.choice("kind", ModelKind::Polygon);
  s.model.hdot_finite_difference = r.boolean("hdot_finite_difference", false);
  s.model.rocking_damping = r.boolean("rocking_damping", true);
  s.model.clip_attractive = r.boolean("clip_attractive", false);
  s.model.rotation = r.boolean("rotation", true);
}

// ---------------------------------------------------------------------------------------
// [[material]]: a default material named "default" when none is given

void read_materials(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  auto tables = scene_detail::table_array(top, "material");
  std::vector<const toml::table*> seen;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    TableReader r(ctx, *tables[i], "material[" + std::to_string(i) + "]",
                  {"name", "E", "gamma", "mu", "ks", "eps_n", "eps_t"});
    MaterialSpec m;
    auto name = r.string_optional("name", true);
    if (!name) r.fail("name", "missing: required (a unique string; species refer to it)");
    m.name = *name;
    // names are unique
    for (std::size_t j = 0; j < s.materials.size(); ++j)
      if (s.materials[j].name == m.name)
        r.fail("name", "duplicate material name " + quote(m.name) + " (first defined at line " +
                           line_of(*seen[j]) + ")");
    // Model P constants (P.34–P.36)
    m.E = r.number("E", m.E, Range::positive());
    m.gamma = r.number("gamma", m.gamma, Range::non_negative());
    m.mu = r.number("mu", m.mu, Range::non_negative());
    // Model S constants (T.2.4–T.2.12): restitutions in (0, 1] since γ ∝ ln ε
    m.ks = r.number("ks", m.ks, Range::positive());
    m.eps_n = r.number("eps_n", m.eps_n, Range::unit_interval_open_closed());
    m.eps_t = r.number("eps_t", m.eps_t, Range::unit_interval_open_closed());
    m.line = static_cast<int>(tables[i]->source().begin.line);
    s.materials.push_back(m);
    seen.push_back(tables[i]);
  }
  if (s.materials.empty()) {
    MaterialSpec m;
    m.name = "default";
    s.materials.push_back(m);
  }
}

// a material reference: empty → the first material; otherwise it must exist
std::string material_ref(const TableReader& r, const SceneSpec& s) {
  auto name = r.string_optional("material", true);
  if (!name) return s.materials.front().name;
  std::vector<std::string_view> names;
  std::string list;
  for (const auto& m : s.materials) {
    if (m.name == *name) return *name;
    names.push_back(m.name);
    list += (list.empty() ? "" : ", ") + quote(m.name);
  }
  r.fail("material", "unknown material " + quote(*name) + "; defined materials: " + list +
                         scene_detail::suggestion(*name, names));
}

// ---------------------------------------------------------------------------------------
// [[species]]: count stays optional until we know whether particles are listed explicitly

struct SpeciesRead {
  std::optional<std::int64_t> count;  ///< as given
  const toml::table* table = nullptr;
};

std::vector<SpeciesRead> read_species(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  auto tables = scene_detail::table_array(top, "species");
  if (tables.empty()) top.fail("species", "missing: at least one [[species]] table is required");
  std::vector<SpeciesRead> out;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    TableReader r(ctx, *tables[i], "species[" + std::to_string(i) + "]", kSpeciesKeys);
    SpeciesSpec sp;
    auto name = r.string_optional("name", true);
    if (!name) r.fail("name", "missing: required (a unique string)");
    sp.name = *name;
    for (std::size_t j = 0; j < s.species.size(); ++j)
      if (s.species[j].name == sp.name)
        r.fail("name", "duplicate species name " + quote(sp.name) + " (first defined at line " +
                           std::to_string(s.species[j].line) + ")");
    // shape: Model S is soft disks only, so its default is "disk"
    ShapeKind def_shape = s.model.kind == ModelKind::Disk ? ShapeKind::Disk : ShapeKind::Polygon;
    sp.shape = r.choice("shape", def_shape);
    if (s.model.kind == ModelKind::Disk && sp.shape != ShapeKind::Disk)
      r.fail("shape", "model S (soft disks, docs/physics.md §3) needs shape = \"disk\"");
    // sides: regular n-gons with 3..64 sides, polygons only
    if (sp.shape == ShapeKind::Disk && r.has("sides"))
      r.fail("sides", "only for shape = \"polygon\" (this species is a disk)");
    sp.sides = static_cast<int>(r.integer("sides", sp.sides, 3, 64));
    sp.radius = r.number_required("radius", Range::positive(), "circumradius or disk radius in m");
    sp.density = r.number("density", sp.density, Range::positive());
    sp.mass = r.number_optional("mass", Range::positive());
    sp.material = material_ref(r, s);
    sp.line = static_cast<int>(tables[i]->source().begin.line);
    out.push_back({r.integer_optional("count", 0, kIntMax), tables[i]});
    s.species.push_back(sp);
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// [box]

void read_box(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  const toml::table* t = sub_table(top, "box");
  if (!t) top.fail("box", "missing: a [box] section is required (kind, width, ...)");
  TableReader r(ctx, *t, "box",
                {"kind", "width", "height", "lid", "wall_thickness", "reduced_length", "material"});
  BoxSpec& b = s.box;
  b.kind = r.choice("kind", BoxKind::Walls);
  b.reduced_length = r.number_optional("reduced_length", Range::positive());
  if (b.reduced_length) {
    // ring: L = L′ + N·d (docs/physics.md §5.2); the two lengths are not given together
    if (b.kind != BoxKind::Ring1D)
      r.fail("reduced_length", "only for kind = \"ring\" (the 1D periodic line)");
    if (r.has("width"))
      r.fail("width",
             "give either box.width (L) or box.reduced_length (L′ = L − N·d), "
             "not both");
  } else {
    b.width =
        r.number_required("width", Range::positive(), "inner width in m; for a ring its length L");
  }
  // periodic boxes are square unless told otherwise
  double def_height = b.kind == BoxKind::Periodic ? b.width : b.height;
  b.height = r.number("height", def_height, Range::positive());
  b.lid = r.boolean("lid", b.lid);
  b.wall_thickness = r.number("wall_thickness", b.wall_thickness, Range::positive());
  b.material = material_ref(r, s);
  // a ring holds disks on a line
  if (b.kind == BoxKind::Ring1D)
    for (const auto& sp : s.species)
      if (sp.shape != ShapeKind::Disk)
        r.fail("kind", "a ring (1D RFM, docs/physics.md §5.2) holds disks only; species " +
                           quote(sp.name) + " is a polygon");
  // at most 10⁶ grain diameters a side: placement lattices and cell grids stay finite
  double d = 0;
  for (const auto& sp : s.species) d = std::max(d, 2.0 * sp.radius);
  constexpr double kMaxDiameters = 1e6;
  auto bound = [&](std::string_view k, double v) {
    if (d > 0 && v > kMaxDiameters * d) {
      std::ostringstream m;
      m << "is " << v / d << " grain diameters (" << v << " m for grains of diameter " << d
        << " m); at most 1e6 are supported";
      r.fail(k, m.str());
    }
  };
  if (b.reduced_length)
    bound("reduced_length", *b.reduced_length);
  else
    bound("width", b.width);
  if (b.kind != BoxKind::Ring1D) bound("height", b.height);
}

// ---------------------------------------------------------------------------------------
// [preparation] and [[preparation.particle]]; species counts are settled here

void read_preparation(const Ctx& ctx, const TableReader& top, SceneSpec& s,
                      const std::vector<SpeciesRead>& species) {
  TableReader r(ctx, table_or_empty(sub_table(top, "preparation")), "preparation",
                {"placement", "seed", "column_height", "velocity_amplitude", "settle_time",
                 "particle", "from_state"});
  PreparationSpec& p = s.prep;
  // a loose column needs a floor; periodic boxes and rings default to random placement
  p.placement = r.choice("placement", s.box.kind == BoxKind::Walls ? PlacementKind::LooseColumn
                                                                   : PlacementKind::Random);
  p.seed = static_cast<std::uint64_t>(r.integer("seed", 1, 0, kInt64Max));
  p.column_height = r.number("column_height", p.column_height, Range::non_negative());
  p.velocity_amplitude = r.number("velocity_amplitude", 0.0, Range::non_negative());
  p.settle_time = r.number("settle_time", 0.0, Range::non_negative());

  // a saved state: relative to the scene file's folder (to the working directory when given
  // with --set), written back absolute so that the resolved scene runs from anywhere
  if (auto from = r.string_optional("from_state", true)) {
    const toml::node* n = r.get("from_state");
    const auto& src = n->source();
    const bool cli = src.path && src.path->rfind(scene_detail::kOverrideTag, 0) == 0;
    std::filesystem::path fp(*from);
    if (fp.is_relative() && !cli) fp = std::filesystem::path(ctx.file).parent_path() / fp;
    p.from_state = std::filesystem::absolute(fp).lexically_normal().string();
    p.from_state_where = ctx.where(n);
  }

  // explicit particles: the species may be omitted when there is only one
  auto tables = scene_detail::table_array(r, "particle");
  if (!tables.empty() && !p.from_state.empty())
    r.fail("from_state",
           "cannot be combined with [[preparation.particle]] entries: the saved "
           "state gives every grain");
  std::vector<std::int64_t> listed(s.species.size(), 0);
  for (std::size_t i = 0; i < tables.size(); ++i) {
    TableReader q(ctx, *tables[i], "preparation.particle[" + std::to_string(i) + "]",
                  {"species", "x", "y", "theta", "vx", "vy", "omega"});
    PreparationSpec::Particle part;
    auto name = q.string_optional("species", true);
    if (!name && s.species.size() > 1)
      q.fail("species", "missing: required when there is more than one species");
    part.species = name.value_or(s.species.front().name);
    std::size_t k = 0;
    while (k < s.species.size() && s.species[k].name != part.species) ++k;
    if (k == s.species.size()) {
      std::vector<std::string_view> names;
      for (const auto& sp : s.species) names.push_back(sp.name);
      q.fail("species", "unknown species " + quote(part.species) +
                            scene_detail::suggestion(part.species, names));
    }
    ++listed[k];
    part.x = q.number_required("x", Range::any(), "position in m");
    part.y = q.number_required("y", Range::any(), "position in m");
    part.theta = q.number("theta", 0.0, Range::any());
    part.vx = q.number("vx", 0.0, Range::any());
    part.vy = q.number("vy", 0.0, Range::any());
    part.omega = q.number("omega", 0.0, Range::any());
    p.particles.push_back(part);
  }
  // two grains at one point touch in no direction: their contact could not push them apart
  {
    std::vector<std::size_t> order(p.particles.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    auto at = [&](std::size_t i) { return std::pair{p.particles[i].x, p.particles[i].y}; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return std::pair{at(a), a} < std::pair{at(b), b};
    });
    for (std::size_t k = 1; k < order.size(); ++k)
      if (at(order[k]) == at(order[k - 1])) {
        const std::size_t i = std::min(order[k], order[k - 1]),
                          j = std::max(order[k], order[k - 1]);
        TableReader q(ctx, *tables[j], "preparation.particle[" + std::to_string(j) + "]",
                      {"species", "x", "y", "theta", "vx", "vy", "omega"});
        q.fail("x", "is at the same point as preparation.particle[" + std::to_string(i) + "] (" +
                        scene_detail::format_double(p.particles[j].x) + ", " +
                        scene_detail::format_double(p.particles[j].y) +
                        "): their contact has no direction; move one of them");
      }
  }

  // counts: required for placement, implied by the list for explicit particles
  std::int64_t total = 0;
  for (std::size_t k = 0; k < s.species.size(); ++k) {
    TableReader sr(ctx, *species[k].table, "species[" + std::to_string(k) + "]", kSpeciesKeys);
    if (!p.from_state.empty()) {
      // the saved state sets a count left out (sim/saved_state.cpp checks one given)
      s.species[k].count_given = species[k].count.has_value();
      s.species[k].count = static_cast<int>(species[k].count.value_or(0));
      if (!species[k].count && s.box.reduced_length)
        sr.fail("count",
                "missing: box.reduced_length needs every count, also with "
                "preparation.from_state");
    } else if (tables.empty()) {
      if (!species[k].count)
        sr.fail("count", "missing: required (number of grains, an integer >= 0)");
      s.species[k].count = static_cast<int>(*species[k].count);
    } else {
      if (species[k].count && *species[k].count != listed[k])
        sr.fail("count", "is " + std::to_string(*species[k].count) + " but " +
                             std::to_string(listed[k]) +
                             " [[preparation.particle]] entries name this species");
      s.species[k].count = static_cast<int>(listed[k]);
    }
    total += s.species[k].count;
  }
  if (total == 0 && p.from_state.empty()) {
    TableReader sr(ctx, *species[0].table, "species[0]", kSpeciesKeys);
    sr.fail("count", "the scene has no grains: every species count is 0");
  }
}

// ---------------------------------------------------------------------------------------
// [integrator]: Model P defaults to Gear 6 at 5e-5 s (docs/physics.md §2.3), Model S to velocity
// Verlet at 1e-6 s (docs/physics.md §3)

void read_integrator(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(ctx, table_or_empty(sub_table(top, "integrator")), "integrator",
                {"kind", "dt", "broad_phase", "sort_every"});
  bool soft = s.model.kind == ModelKind::Disk;
  s.integrator.kind =
      r.choice("kind", soft ? IntegratorKind::VelocityVerlet : IntegratorKind::Gear6);
  s.integrator.dt = r.number("dt", soft ? 1e-6 : 5e-5, Range::positive());
  s.integrator.broad_phase = r.choice("broad_phase", BroadPhaseKind::Auto);
  s.integrator.sort_every = static_cast<int>(r.integer("sort_every", -1, -1, kIntMax));
  if (s.integrator.sort_every > 0 && s.model.kind == ModelKind::Polygon)
    r.fail("sort_every",
           "spatial sorting is for disk scenes (Model S); polygon contacts keep "
           "a directed history. Use 0 or -1 (auto)");
  if (s.integrator.sort_every > 0 && s.box.kind == BoxKind::Ring1D)
    r.fail("sort_every", "the 1D ring keeps its particles in ring order; use 0 or -1 (auto)");
}

// ---------------------------------------------------------------------------------------
// [drive]: every key is checked whatever the kind, so an override can switch kinds

void read_drive(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(ctx, table_or_empty(sub_table(top, "drive")), "drive",
                {"kind", "g", "gx", "gy", "g_p", "t1", "period", "f", "relax", "D",
                 "com_removal_every", "early_rest", "rest_speed", "rest_energy", "rest_hold",
                 "quench", "quench_speed", "quench_hold", "taps"});
  DriveSpec& d = s.drive;
  // closed boxes fall under gravity by default; periodic boxes and rings are undriven
  d.kind = r.choice("kind", s.box.kind == BoxKind::Walls ? DriveKind::Gravity : DriveKind::None);
  d.g = r.number("g", d.g, Range::non_negative());
  d.gx = r.number("gx", d.gx, Range::any());
  d.gy = r.number("gy", d.gy, Range::any());
  if (d.gx == 0.0 && d.gy == 0.0)
    r.fail(r.has("gy") ? "gy" : "gx", "gravity direction (gx, gy) must not be zero");
  // negative g (P.37)
  d.g_p = r.number("g_p", d.g_p, Range::positive());
  d.t1 = r.number("t1", d.t1, Range::positive());
  d.period = r.number("period", d.period, Range::positive());
  if (d.t1 >= d.period)
    r.fail(r.has("t1") ? "t1" : "period", "pulse duration t1 (" +
                                              scene_detail::format_double(d.t1) +
                                              " s) must be shorter than the period (" +
                                              scene_detail::format_double(d.period) + " s)");
  // rotating g (P.38)
  d.f = r.number("f", d.f, Range::positive());
  d.relax = r.number("relax", d.relax, Range::non_negative());
  // random force (T.2.16)
  d.D = r.number("D", d.D, Range::non_negative());
  if (d.kind == DriveKind::RandomForce && d.D == 0.0)
    r.fail("D", "must be > 0 for kind = \"random_force\" (got 0)");
  d.com_removal_every =
      static_cast<int>(r.integer("com_removal_every", d.com_removal_every, 0, kIntMax));
  // early end of a relaxation once at rest (docs/physics.md §2.4)
  d.early_rest = r.boolean("early_rest", d.early_rest);
  d.rest_speed = r.number("rest_speed", d.rest_speed, Range::positive());
  d.rest_energy = r.number("rest_energy", d.rest_energy, Range::positive());
  d.rest_hold = r.number("rest_hold", d.rest_hold, Range::non_negative());
  // kinetic damping of the ringing pile once its contact network froze (drive/protocol.hpp)
  d.quench = r.boolean("quench", d.quench);
  d.quench_speed = r.number("quench_speed", d.quench_speed, Range::positive());
  d.quench_hold = r.number("quench_hold", d.quench_hold, Range::non_negative());
  // taps only exist for the tapping protocols
  d.taps = static_cast<int>(r.integer("taps", 0, 0, kIntMax));
  if (d.taps > 0 && d.kind != DriveKind::NegativeG && d.kind != DriveKind::RotatingG)
    r.fail("taps", "only for kind = \"negative_g\" or \"rotating_g\" (got kind = " +
                       quote(scene_name(d.kind)) + ")");
}

// ---------------------------------------------------------------------------------------
// [health] and [output]

void read_health(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(ctx, table_or_empty(sub_table(top, "health")), "health",
                {"max_overlap", "check_every", "allow_unstable"});
  s.health.max_overlap = r.number("max_overlap", s.health.max_overlap, {0.0, 1.0, true, false});
  s.health.check_every =
      static_cast<int>(r.integer("check_every", s.health.check_every, 1, kIntMax));
  s.health.allow_unstable = r.boolean("allow_unstable", false);
}

void read_output(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(ctx, table_or_empty(sub_table(top, "output")), "output",
                {"series_every", "final_state", "test_rect", "discard_taps", "checkpoint_minutes",
                 "checkpoint_taps", "checkpoint_steps", "snapshots"});
  OutputSpec& o = s.output;
  o.series_every = static_cast<int>(r.integer("series_every", o.series_every, 1, kIntMax));
  o.final_state = r.boolean("final_state", o.final_state);
  o.discard_taps = static_cast<int>(r.integer("discard_taps", o.discard_taps, 0, kIntMax));
  o.checkpoint_minutes =
      r.number("checkpoint_minutes", o.checkpoint_minutes, {0.0, 1e7, false, false});
  o.checkpoint_taps = static_cast<int>(r.integer("checkpoint_taps", o.checkpoint_taps, 0, kIntMax));
  o.checkpoint_steps = r.integer("checkpoint_steps", o.checkpoint_steps, 0,
                                 std::numeric_limits<std::int64_t>::max());
  // test_rect = [x0, y0, x1, y1] with x1 > x0 and y1 > y0
  if (const toml::node* n = r.get("test_rect")) {
    const toml::array* a = n->as_array();
    const char* form = "expected an array of 4 numbers [x0, y0, x1, y1] in m";
    if (!a || a->size() != 4)
      r.fail("test_rect", std::string(form) + ", got " +
                              (a ? "an array of " + std::to_string(a->size())
                                 : std::string(scene_detail::type_name(*n))));
    for (std::size_t i = 0; i < 4; ++i) {
      const toml::node& e = (*a)[i];
      std::optional<double> v;
      if (auto f = e.as_floating_point()) v = f->get();
      if (auto i = e.as_integer()) v = static_cast<double>(i->get());
      if (!v)
        r.fail("test_rect", std::string(form) + "; element " + std::to_string(i) + " is " +
                                std::string(scene_detail::type_name(e)));
      if (!std::isfinite(*v))
        r.fail("test_rect", "element " + std::to_string(i) + " must be a finite number (got " +
                                scene_detail::node_text(e) + ")");
      o.test_rect[i] = *v;
    }
    if (o.test_rect[2] <= o.test_rect[0])
      r.fail("test_rect", "needs x1 > x0 (got x0 = " + scene_detail::node_text((*a)[0]) +
                              ", x1 = " + scene_detail::node_text((*a)[2]) + ")");
    if (o.test_rect[3] <= o.test_rect[1])
      r.fail("test_rect", "needs y1 > y0 (got y0 = " + scene_detail::node_text((*a)[1]) +
                              ", y1 = " + scene_detail::node_text((*a)[3]) + ")");
  }
  scene_detail::read_snapshots(r, s);  // [output.snapshots]: scene/snapshot_section.cpp
}

// [scene]: the name defaults to the file's stem
void read_scene(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  TableReader r(ctx, table_or_empty(sub_table(top, "scene")), "scene",
                {"name", "description", "duration"});
  std::string stem = std::filesystem::path(ctx.file).stem().string();
  s.name = r.string("name", stem.empty() ? "scene" : stem, true);
  // the name becomes a folder under runs/: it must stay one folder there
  const bool control = std::any_of(s.name.begin(), s.name.end(),
                                   [](char c) { return static_cast<unsigned char>(c) < 32; });
  if (s.name.empty() || s.name[0] == '.' || s.name.find_first_of("/\\") != std::string::npos ||
      control)
    r.fail("name",
           "must be a plain folder name (no '/', '\\', leading '.', or control "
           "characters; got " +
               quote(s.name) + ")");
  s.description = r.string("description", "", false);
  s.duration = r.number("duration", s.duration, Range::positive());
}

}  // namespace

// ---------------------------------------------------------------------------------------
// entry points

SceneSpec parse_scene_string(std::string_view text, const std::string& name_for_messages,
                             const std::vector<std::string>& overrides) {
  Ctx ctx{name_for_messages};
  // syntax first: toml++ reports line and column
  toml::table root;
  // bytes toml++ 3.3.0 cannot survive: non-ASCII outside strings and comments
  if (const auto [l, c] = scene_detail::non_ascii_outside_strings(text); l != 0)
    throw InputError(name_for_messages + ":" + std::to_string(l) + ":" + std::to_string(c), "",
                     "TOML syntax error: a non-ASCII character outside a string or comment, or "
                     "after a backslash "
                     "(keys and values must be ASCII; write e.g. eps_n, not ε_n)");
  try {
    root = toml::parse(text, name_for_messages);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw InputError(
        name_for_messages + ":" + std::to_string(b.line) + ":" + std::to_string(b.column), "",
        "TOML syntax error: " + std::string(e.description()));
  }
  // overrides replace or add keys before anything is validated
  for (const auto& o : overrides) scene_detail::apply_override(ctx, root, o);

  // then every section, in dependency order
  SceneSpec s;
  s.path = name_for_messages;
  TableReader top(ctx, root, "",
                  {"scene", "model", "material", "species", "box", "preparation", "integrator",
                   "drive", "health", "output", "render", "rfm"});
  read_model(ctx, top, s);
  read_materials(ctx, top, s);
  auto species = read_species(ctx, top, s);
  read_box(ctx, top, s);
  read_preparation(ctx, top, s, species);
  // a ring given by L′ gets its full length L = L′ + N·d (docs/physics.md §5.2)
  if (s.box.reduced_length) {
    double nd = 0;
    for (const auto& sp : s.species) nd += sp.count * 2.0 * sp.radius;
    s.box.width = *s.box.reduced_length + nd;
  }
  read_integrator(ctx, top, s);
  read_drive(ctx, top, s);
  read_health(ctx, top, s);
  read_output(ctx, top, s);
  read_scene(ctx, top, s);
  scene_detail::read_render(ctx, top, s);  // [render]: scene/render_section.cpp
  scene_detail::read_rfm(ctx, top, s);     // [rfm]: scene/rfm_section.cpp
  s.resolved = scene_resolved(s);
  return s;
}

SceneSpec parse_scene_file(const std::string& path, const std::vector<std::string>& overrides) {
  // a directory opens as a stream on Linux: refuse it by name
  check_input_file(path, "scene file", kMaxSceneBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the scene file");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_scene_string(buf.str(), path, overrides);
}

}  // namespace gs
