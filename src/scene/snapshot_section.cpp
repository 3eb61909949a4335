// [output.snapshots]: checked once here like every other table (docs/scene-format.md)
#include "scene/snapshot_section.hpp"

#include <cmath>

#include "scene/reader.hpp"

namespace gs::scene_detail {

namespace {

// a TOML array node, or a message naming what was found instead
const toml::array& array_of(const TableReader& r, std::string_view k, const toml::node& n,
                            const std::string& form) {
  const toml::array* a = n.as_array();
  if (!a) r.fail(k, "expected " + form + ", got " + std::string(type_name(n)));
  return *a;
}

}  // namespace

void read_snapshots(const TableReader& output, SceneSpec& s) {
  const toml::table* t = sub_table(output, "snapshots");
  if (!t) return;
  TableReader r(output.ctx(), *t, "output.snapshots",
                {"every_time", "times", "at_taps", "formats", "vtp_encoding", "contacts"});
  SnapshotSpec& o = s.output.snapshots;
  o.given = true;
  o.every_time = r.number("every_time", 0.0, Range::non_negative());
  // no schedule is finer than a step: one snapshot per step at most
  if (o.every_time > 0.0 && o.every_time < s.integrator.dt)
    r.fail("every_time",
           "is shorter than the time step integrator.dt = " + format_double(s.integrator.dt) +
               " s; a snapshot is taken after a step at most once: give every_time "
               ">= integrator.dt (or 0 for none)");
  // times: finite, non-negative, strictly ascending
  if (const toml::node* n = r.get("times")) {
    const std::string form = "an array of times in s, ascending";
    const toml::array& a = array_of(r, "times", *n, form);
    for (std::size_t i = 0; i < a.size(); ++i) {
      const toml::node& e = a[i];
      std::optional<double> v;
      if (auto f = e.as_floating_point()) v = f->get();
      if (auto q = e.as_integer()) v = static_cast<double>(q->get());
      if (!v)
        r.fail("times",
               form + "; element " + std::to_string(i) + " is " + std::string(type_name(e)));
      if (!std::isfinite(*v) || *v < 0.0)
        r.fail("times", "element " + std::to_string(i) + " must be a finite time >= 0 s (got " +
                            node_text(e) + ")");
      if (!o.times.empty() && *v <= o.times.back())
        r.fail("times", "must be strictly ascending (element " + std::to_string(i) + " = " +
                            node_text(e) + " follows " + format_double(o.times.back()) + ")");
      o.times.push_back(*v);
    }
  }
  o.at_taps = r.boolean("at_taps", false);
  const bool tapping = s.drive.kind == DriveKind::NegativeG || s.drive.kind == DriveKind::RotatingG;
  if (o.at_taps && !tapping)
    r.fail("at_taps", "needs a tapping drive (drive.kind = \"negative_g\" or \"rotating_g\"; got " +
                          quote(scene_name(s.drive.kind)) + ")");
  // formats: a list of distinct names out of "vtp", "xyz" (may be empty with contacts on)
  if (const toml::node* n = r.get("formats")) {
    const std::string form = "an array of format names (\"vtp\", \"xyz\")";
    const toml::array& a = array_of(r, "formats", *n, form);
    o.vtp = o.xyz = false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const auto* e = a[i].as_string();
      if (!e)
        r.fail("formats",
               form + "; element " + std::to_string(i) + " is " + std::string(type_name(a[i])));
      const std::string v = e->get();
      if (v != "vtp" && v != "xyz")
        r.fail("formats", "element " + std::to_string(i) + " must be \"vtp\" or \"xyz\" (got " +
                              quote(v) + ")" + suggestion(v, {"vtp", "xyz"}));
      bool& flag = v == "vtp" ? o.vtp : o.xyz;
      if (flag) r.fail("formats", "names " + quote(v) + " twice");
      flag = true;
    }
  }
  // the .vtp arrays: compressed binary (smaller, exact) or ASCII text (readable by eye)
  const std::string enc = r.string("vtp_encoding", "binary", false);
  if (enc != "binary" && enc != "ascii")
    r.fail("vtp_encoding", "must be \"binary\" or \"ascii\" (got " + quote(enc) + ")" +
                               suggestion(enc, {"binary", "ascii"}));
  o.vtp_binary = enc == "binary";
  o.contacts = r.boolean("contacts", o.contacts);
  if (!o.vtp && !o.xyz && !o.contacts)
    r.fail(r.has("contacts") ? "contacts" : "formats",
           "with formats = [] and contacts = false a snapshot writes nothing");
}

std::vector<std::pair<std::string, std::string>> snapshot_entries(const SnapshotSpec& o) {
  auto flag = [](bool b) { return std::string(b ? "true" : "false"); };
  std::string times = "[";
  for (std::size_t i = 0; i < o.times.size(); ++i)
    times += format_double(o.times[i]) + (i + 1 < o.times.size() ? ", " : "");
  times += "]";
  std::string formats = "[";
  if (o.vtp) formats += "\"vtp\"";
  if (o.xyz) formats += std::string(o.vtp ? ", " : "") + "\"xyz\"";
  formats += "]";
  return {{"every_time", format_double(o.every_time)},
          {"times", times},
          {"at_taps", flag(o.at_taps)},
          {"formats", formats},
          {"vtp_encoding", quote(o.vtp_binary ? "binary" : "ascii")},
          {"contacts", flag(o.contacts)}};
}

}  // namespace gs::scene_detail
