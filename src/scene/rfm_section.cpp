// [rfm]: when and how the Random Force Model observers sample (docs/physics.md §5.3, docs/rfm.md);
// checked once here like every other section (docs/scene-format.md)
#include "scene/rfm_section.hpp"

#include <algorithm>
#include <climits>

#include "scene/reader.hpp"

namespace gs::scene_detail {

void read_rfm(const Ctx& ctx, const TableReader& top, SceneSpec& s) {
  const toml::table* t = sub_table(top, "rfm");
  static const toml::table empty;
  TableReader r(ctx, t ? *t : empty, "rfm",
                {"enabled", "sample_every", "discard_time", "blocks", "v_max", "v_bins",
                 "structure_every", "sk_nmax", "gr_bins", "gr_rmax", "path_bins", "path_min",
                 "path_max", "gap_bins", "gap_min"});
  RfmSpec& o = s.rfm;
  o.given = t != nullptr;
  // on for the random force and whenever the section is there (a freely cooling gas)
  o.enabled = r.boolean("enabled", o.given || s.drive.kind == DriveKind::RandomForce);
  // sampling: every K steps once the transient is over
  o.sample_every = static_cast<int>(r.integer("sample_every", o.sample_every, 1, INT_MAX));
  o.discard_time = r.number("discard_time", o.discard_time, Range::non_negative());
  o.blocks = static_cast<int>(r.integer("blocks", o.blocks, 2, 100000));
  // velocity histograms (T.A.3): 0 = automatic range
  o.v_max = r.number("v_max", o.v_max, Range::non_negative());
  o.v_bins = static_cast<int>(r.integer("v_bins", o.v_bins, 4, 1000000));
  // structure (2D): S(k) cutoff and g(R) bins
  o.structure_every = static_cast<int>(r.integer("structure_every", o.structure_every, 1, INT_MAX));
  o.sk_nmax = static_cast<int>(r.integer("sk_nmax", o.sk_nmax, 0, 1024));
  o.gr_bins = static_cast<int>(r.integer("gr_bins", o.gr_bins, 1, 1000000));
  o.gr_rmax = r.number("gr_rmax", o.gr_rmax, Range::non_negative());
  if (s.box.kind == BoxKind::Periodic && o.gr_rmax > 0.5 * std::min(s.box.width, s.box.height))
    r.fail("gr_rmax", "must be at most half the box (minimum image, T.4.10): got " +
                          format_double(o.gr_rmax) + " m");
  // free paths (T.4.18): log bins, 0 = automatic range
  o.path_bins = static_cast<int>(r.integer("path_bins", o.path_bins, 1, 1000000));
  o.path_min = r.number("path_min", o.path_min, Range::non_negative());
  o.path_max = r.number("path_max", o.path_max, Range::non_negative());
  if (o.path_min > 0 && o.path_max > 0 && o.path_max <= o.path_min)
    r.fail("path_max", "must exceed path_min (" + format_double(o.path_min) + " m)");
  // 1D gaps (T.3.24): log bins of R/L′ on [gap_min, 1)
  o.gap_bins = static_cast<int>(r.integer("gap_bins", o.gap_bins, 1, 1000000));
  o.gap_min = r.number("gap_min", o.gap_min, {0.0, 1.0, true, true});
}

std::vector<std::pair<std::string, std::string>> rfm_entries(const RfmSpec& o) {
  return {
      {"enabled", o.enabled ? "true" : "false"},
      {"sample_every", std::to_string(o.sample_every)},
      {"discard_time", format_double(o.discard_time)},
      {"blocks", std::to_string(o.blocks)},
      {"v_max", format_double(o.v_max)},
      {"v_bins", std::to_string(o.v_bins)},
      {"structure_every", std::to_string(o.structure_every)},
      {"sk_nmax", std::to_string(o.sk_nmax)},
      {"gr_bins", std::to_string(o.gr_bins)},
      {"gr_rmax", format_double(o.gr_rmax)},
      {"path_bins", std::to_string(o.path_bins)},
      {"path_min", format_double(o.path_min)},
      {"path_max", format_double(o.path_max)},
      {"gap_bins", std::to_string(o.gap_bins)},
      {"gap_min", format_double(o.gap_min)},
  };
}

bool rfm_written(const SceneSpec& s) {
  return s.rfm.given || s.drive.kind == DriveKind::RandomForce;
}

}  // namespace gs::scene_detail
