#include "app/cli.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/run.hpp"
#include "app/version.hpp"
#include "core/error.hpp"

namespace gs {

int run_cli(int argc, char** argv) {
  CLI::App app{"gransim: headless 2D granular dynamics (polygon DEM tapping, Random Force Model)",
               "gransim"};
  app.set_version_flag("--version", std::string(program_version()));
  app.require_subcommand(1);

  // run
  RunOptions ro;
  auto* run = app.add_subcommand("run", "run a scene and write a run directory");
  run->add_option("scene", ro.scene, "scene file (TOML, see docs/scene-format.md)")->required();
  run->add_option("-o,--out", ro.out, "run directory (default runs/<name>-<time>)");
  run->add_option("--set", ro.sets, "override a scene key, e.g. --set drive.g_p=8 (repeatable)");
  run->add_flag("--force", ro.force, "reuse a non-empty run directory (its contents are removed)");
  run->add_flag("-q,--quiet", ro.quiet, "no progress display");
  run->add_flag("--allow-unstable", ro.allow_unstable, "skip the up-front time-step check");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    if (*run) return run_command(ro);
  } catch (const InputError& e) {
    std::fprintf(stderr, "gransim: error: %s\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gransim: internal error: %s\n", e.what());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace gs
