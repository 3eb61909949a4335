// the `study` subcommand's options (dispatched from app/cli.cpp to study_command)
#include <CLI/CLI.hpp>

#include "app/study/study.hpp"

namespace gs {

CLI::App* add_study_command(CLI::App& app, StudyOptions& o) {
  auto* st = app.add_subcommand(
      "study",
      "speed against accuracy: integrators × dt × broad phase × model switches on "
      "reference problems, and the stability map (docs/speed-accuracy.md)");
  st->add_option("study", o.file, "study file (TOML, e.g. scenes/studies/quick.toml)")->required();
  st->add_option("-o,--out", o.out, "study directory (default runs/study-<name>)");
  st->add_flag("--force", o.force, "reuse a non-empty study directory (its contents are removed)");
  st->add_flag("-q,--quiet", o.quiet, "no line per combination");
  return st;
}

}  // namespace gs
